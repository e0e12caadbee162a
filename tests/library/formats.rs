//! Mesh file formats end to end: the hand-written fixtures in `tests/data/`, exact round trips of
//! the writers, binary variants built byte by byte, directories, every kind of bad input, and
//! property tests that feed random and truncated bytes to every parser.

use std::path::{Path, PathBuf};

use csg::{DVec3, Mesh};
use cutaway::io::{self, Format};
use proptest::prelude::*;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data")
        .join(name)
}

/// A fresh empty directory under cargo's per-target scratch space.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("formats-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The one-line error `main` would print.
fn error_of<T: std::fmt::Debug>(result: anyhow::Result<T>) -> String {
    let line = cutaway::cli::error_line(&result.expect_err("expected an error"));
    assert_eq!(line.lines().count(), 1, "{line}");
    line
}

/// Triangles as corner coordinates (bit patterns), independent of vertex numbering.
fn corner_bits(mesh: &Mesh) -> Vec<[[u64; 3]; 3]> {
    (0..mesh.triangles.len())
        .map(|t| mesh.corners(t).map(|p| p.to_array().map(f64::to_bits)))
        .collect()
}

fn assert_closed_volume(mesh: &Mesh, volume: f64) {
    let report = mesh.report();
    assert!(report.closed && report.manifold, "{report:?}");
    assert!(
        (mesh.volume() - volume).abs() < 1e-12,
        "volume {}",
        mesh.volume()
    );
}

/// A closed mesh with coordinates that decimal and f32 formats would not keep exactly.
fn awkward_tetrahedron() -> Mesh {
    let positions = vec![
        DVec3::new(0.1, 1.0 / 3.0, -0.0),
        DVec3::new(123456789012.25, std::f64::consts::PI, 2.5e-300),
        DVec3::new(-7.000000000000001, 0.30000000000000004, 1e-7),
        DVec3::new(123456.789, -1e-310, 42.0),
    ];
    let triangles = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn obj_groups_are_named_parts_and_normals_do_not_split_vertices() {
    let parts = io::read_parts(&data("two_cubes.obj")).unwrap();
    let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["left", "right"]);
    for part in &parts {
        assert_eq!(part.mesh.vertex_count(), 8, "{}", part.name);
        assert_eq!(part.mesh.triangle_count(), 12, "{}", part.name);
        assert_closed_volume(&part.mesh, 1.0);
    }
    assert_eq!(parts[1].mesh.bbox().min, DVec3::new(2.0, 0.0, 0.0));
}

#[test]
fn ascii_stl_fixture_reads_as_one_closed_part() {
    let parts = io::read_parts(&data("tetra_ascii.stl")).unwrap();
    assert_eq!(parts.len(), 1);
    assert_eq!(parts[0].name, "tetra_ascii");
    assert_eq!(parts[0].mesh.vertex_count(), 4);
    assert_eq!(parts[0].mesh.triangle_count(), 4);
    assert_closed_volume(&parts[0].mesh, 1.0 / 6.0);
}

#[test]
fn ascii_ply_fixture_quads_are_triangulated() {
    let mesh = io::read_mesh(&data("cube_ascii.ply")).unwrap();
    assert_eq!(mesh.vertex_count(), 8);
    assert_eq!(mesh.triangle_count(), 12);
    assert_eq!(mesh.bbox().min, DVec3::new(10.0, 20.0, 30.0));
    assert_closed_volume(&mesh, 1.0);
}

#[test]
fn vtk_strips_and_polygons_make_a_consistently_oriented_cube() {
    let mesh = io::read_mesh(&data("cube_strips.vtk")).unwrap();
    assert_eq!(mesh.triangle_count(), 12);
    // Closed, manifold and positive volume only if every other strip triangle was flipped.
    assert_closed_volume(&mesh, 1.0);
}

#[test]
fn obj_and_ply_round_trip_f64_exactly() {
    let dir = scratch("roundtrip");
    let mesh = awkward_tetrahedron();
    for name in ["t.obj", "t.ply"] {
        let path = dir.join(name);
        io::write_mesh(&path, &mesh).unwrap();
        let back = io::read_mesh(&path).unwrap();
        assert_eq!(corner_bits(&back), corner_bits(&mesh), "{name}");
    }
}

#[test]
fn binary_stl_round_trips_f32_values_and_survives_a_solid_header() {
    let dir = scratch("stl");
    let mesh = awkward_tetrahedron();
    let path = dir.join("t.stl");
    io::write_mesh(&path, &mesh).unwrap();
    let rounded = Mesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| p.as_vec3().as_dvec3())
            .collect(),
        triangles: mesh.triangles.clone(),
    };
    assert_eq!(
        corner_bits(&io::read_mesh(&path).unwrap()),
        corner_bits(&rounded)
    );
    // Many exporters start the binary header with "solid": it must still read as binary.
    let mut bytes = std::fs::read(&path).unwrap();
    bytes[..12].copy_from_slice(b"solid binary");
    let parts = io::parse_bytes(Format::Stl, &bytes, "t").unwrap();
    assert_eq!(corner_bits(&parts[0].mesh), corner_bits(&rounded));
}

/// Binary PLY written the way other tools do: `float` vertices, `uint` indices, a quad, an extra
/// property before and after the coordinates.
#[test]
fn binary_little_endian_float_ply_from_another_writer() {
    let mut bytes =
        b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty uchar flag\n\
property float x\nproperty float y\nproperty float z\nproperty float confidence\n\
element face 1\nproperty list uint8 uint32 vertex_indices\nend_header\n"
            .to_vec();
    let corners = [
        [0.1f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    for c in corners {
        bytes.push(7);
        for v in c {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes.extend_from_slice(&0.5f32.to_le_bytes());
    }
    bytes.push(4);
    for i in [0u32, 1, 2, 3] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let parts = io::parse_bytes(Format::Ply, &bytes, "quad").unwrap();
    let mesh = &parts[0].mesh;
    assert_eq!(mesh.triangle_count(), 2);
    assert_eq!(mesh.positions[0].x, f64::from(0.1f32));
}

/// Legacy binary VTK (big endian) with `TRIANGLE_STRIPS` and point normals, as in the SPL atlas.
fn binary_vtk_cube() -> Vec<u8> {
    let mut bytes =
        b"# vtk DataFile Version 4.0\nbinary cube\nBINARY\nDATASET POLYDATA\nPOINTS 8 float\n"
            .to_vec();
    let points = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    for p in points {
        for v in p {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
    }
    let ints = |bytes: &mut Vec<u8>, values: &[i32]| {
        for v in values {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
    };
    bytes.extend_from_slice(b"\nPOLYGONS 2 10\n");
    ints(&mut bytes, &[4, 0, 3, 2, 1, 4, 4, 5, 6, 7]);
    bytes.extend_from_slice(b"\nTRIANGLE_STRIPS 1 11\n");
    ints(&mut bytes, &[10, 4, 0, 5, 1, 6, 2, 7, 3, 4, 0]);
    bytes.extend_from_slice(b"\nPOINT_DATA 8\nNORMALS Normals float\n");
    for _ in 0..8 {
        for v in [0.0f32, 0.0, 1.0] {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
    }
    bytes.push(b'\n');
    bytes
}

#[test]
fn binary_vtk_with_strips_and_normals() {
    let parts = io::parse_bytes(Format::Vtk, &binary_vtk_cube(), "cube").unwrap();
    assert_eq!(parts[0].mesh.triangle_count(), 12);
    assert_closed_volume(&parts[0].mesh, 1.0);
}

#[test]
fn load_models_names_regions_by_stem_and_number_in_sorted_file_order() {
    let dir = scratch("dir");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::copy(data("two_cubes.obj"), dir.join("b_cubes.obj")).unwrap();
    std::fs::copy(data("tetra_ascii.stl"), dir.join("sub/c_tetra.STL")).unwrap();
    std::fs::copy(data("cube_ascii.ply"), dir.join("a_cube.ply")).unwrap();
    std::fs::write(dir.join("README.txt"), "not a mesh").unwrap();
    // One STL file holding two disjoint tetrahedra: two regions, numbered 1 and 2.
    let tetra = io::read_mesh(&data("tetra_ascii.stl")).unwrap();
    let mut pair = tetra.clone();
    let mut moved = tetra.clone();
    moved.positions.iter_mut().for_each(|p| p.x += 5.0);
    pair.append(&moved);
    io::write_mesh(&dir.join("d_pair.stl"), &pair).unwrap();

    let models = io::load_models(&dir).unwrap();
    let names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "a_cube",
            "b_cubes#left 1",
            "b_cubes#right 2",
            "d_pair 1",
            "d_pair 2",
            "c_tetra"
        ],
    );
    assert_eq!(models[5].source, dir.join("sub/c_tetra.STL"));
    assert!(models.iter().all(|m| m.mesh.report().closed));
    assert!(models[4].mesh.bbox().min.x >= 5.0);

    // A single file gives the same models as in the directory.
    let single = io::load_models(&dir.join("d_pair.stl")).unwrap();
    assert_eq!(single.len(), 2);
    assert_eq!(single[0].mesh.triangle_count(), 4);
}

#[test]
fn obj_polygon_and_polyline_writers() {
    let dir = scratch("polys");
    let cube = io::read_parts(&data("two_cubes.obj"))
        .unwrap()
        .remove(0)
        .mesh;
    // Quads of the cube written as polygons read back as the same closed cube.
    let quads: Vec<Vec<u32>> = cube
        .triangles
        .chunks(2)
        .map(|pair| vec![pair[0][0], pair[0][1], pair[0][2], pair[1][2]])
        .collect();
    let path = dir.join("quads.obj");
    io::write_obj_polygons(&path, &cube.positions, &quads).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 6);
    let back = io::read_mesh(&path).unwrap();
    assert_closed_volume(&back, 1.0);

    let loop_points = vec![
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::X,
        DVec3::Y,
        DVec3::new(0.1, 0.2, 0.3),
    ];
    let path = dir.join("contour.obj");
    io::write_obj_polylines(&path, &[loop_points.clone(), vec![DVec3::Z, DVec3::ONE]]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let vertices: Vec<[f64; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(vertices[0], [0.1, 0.2, 0.3]);
    assert_eq!(vertices.len(), 5);
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
    assert_eq!(lines, ["l 1 2 3 1", "l 4 5"]);

    // Bad input to the writers is an error, and nothing is written.
    let bad = dir.join("bad.obj");
    assert!(io::write_obj_polygons(&bad, &cube.positions, &[vec![0, 1, 99]]).is_err());
    assert!(io::write_obj_polylines(&bad, &[vec![DVec3::ZERO]]).is_err());
    assert!(!bad.exists());
}

#[test]
fn missing_unknown_empty_and_directory_inputs_are_one_line_errors() {
    let dir = scratch("bad");
    let missing = dir.join("knee.stl");
    let line = error_of(io::read_parts(&missing));
    assert!(
        line.contains("knee.stl") && line.contains("No such file"),
        "{line}"
    );

    let unknown = dir.join("notes.txt");
    std::fs::write(&unknown, "v 0 0 0").unwrap();
    let line = error_of(io::read_parts(&unknown));
    assert!(
        line.contains("notes.txt") && line.contains("unknown mesh format"),
        "{line}"
    );

    for ext in ["obj", "stl", "ply", "vtk"] {
        let empty = dir.join(format!("empty.{ext}"));
        std::fs::write(&empty, b"").unwrap();
        let line = error_of(io::read_parts(&empty));
        assert!(
            line.contains(&format!("empty.{ext}: the file is empty")),
            "{line}"
        );
    }

    let folder = dir.join("folder.obj");
    std::fs::create_dir_all(&folder).unwrap();
    let line = error_of(io::read_parts(&folder));
    assert!(line.contains("is a directory"), "{line}");

    let no_meshes = scratch("no-meshes");
    std::fs::write(no_meshes.join("a.txt"), "x").unwrap();
    let line = error_of(io::load_models(&no_meshes));
    assert!(line.contains("no mesh files"), "{line}");
    let line = error_of(io::load_models(&dir.join("nowhere")));
    assert!(line.contains("nowhere"), "{line}");
}

#[test]
fn content_that_does_not_match_the_extension_is_named() {
    let ply = std::fs::read(data("cube_ascii.ply")).unwrap();
    let line = error_of(io::parse_bytes(Format::Stl, &ply, "x"));
    assert!(line.contains("looks like PLY, not STL"), "{line}");
    let stl = std::fs::read(data("tetra_ascii.stl")).unwrap();
    let line = error_of(io::parse_bytes(Format::Vtk, &stl, "x"));
    assert!(line.contains("looks like STL, not VTK"), "{line}");
    let obj = std::fs::read(data("two_cubes.obj")).unwrap();
    let line = error_of(io::parse_bytes(Format::Ply, &obj, "x"));
    assert!(line.contains("looks like OBJ, not PLY"), "{line}");
}

#[test]
fn absurd_header_counts_are_errors() {
    let ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n\
property float y\nproperty float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n\
\0\0\0\0\0\0\0\0\0\0\0\0";
    let line = error_of(io::parse_bytes(Format::Ply, ply, "x"));
    assert!(line.contains("PLY"), "{line}");
    let ascii_ply = b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n\
property float y\nproperty float z\nend_header\n0 0 0\n";
    error_of(io::parse_bytes(Format::Ply, ascii_ply, "x"));

    let mut stl = vec![0u8; 84 + 50];
    stl[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    let line = error_of(io::parse_bytes(Format::Stl, &stl, "x"));
    assert!(line.contains("4000000000 triangles"), "{line}");

    let vtk = b"# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 4000000000 float\n\0\0\0\0";
    error_of(io::parse_bytes(Format::Vtk, vtk, "x"));
    let vtk = b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n\
POLYGONS 4000000000 4000000000\n3 0 1 2\n";
    error_of(io::parse_bytes(Format::Vtk, vtk, "x"));

    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n";
    error_of(io::parse_bytes(Format::Obj, obj, "x"));
}

#[test]
fn bad_values_and_indices_are_errors_naming_the_problem() {
    let nan = b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let line = error_of(io::parse_bytes(Format::Obj, nan, "x"));
    assert!(line.contains("non-finite"), "{line}");
    let vtk = b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n\
POLYGONS 1 4\n3 0 1 7\n";
    let line = error_of(io::parse_bytes(Format::Vtk, vtk, "x"));
    assert!(line.contains("uses vertex 7"), "{line}");
    let garbage: Vec<u8> = (0..1000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    for format in Format::ALL {
        error_of(io::parse_bytes(format, &garbage, "x"));
    }
    let points_only = b"v 0 0 0\nv 1 0 0\n";
    let line = error_of(io::parse_bytes(Format::Obj, points_only, "x"));
    assert!(line.contains("no triangles"), "{line}");
}

#[test]
fn special_and_oversized_files_are_refused_before_reading() {
    let dir = scratch("special");
    // A link to /dev/zero would be read forever: refused by kind, after following the link.
    let zero = dir.join("zero.stl");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let line = error_of(io::read_parts(&zero));
    assert!(
        line.contains("zero.stl") && line.contains("character device"),
        "{line}"
    );
    // A FIFO without a writer would block the open: refused before it is opened.
    let fifo = dir.join("pipe.obj");
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let line = error_of(io::read_parts(&fifo));
        assert!(line.contains("pipe.obj") && line.contains("FIFO"), "{line}");
        let line = error_of(io::read_mesh_verbatim(&fifo));
        assert!(line.contains("FIFO"), "{line}");
    } else {
        eprintln!("FIFO case skipped: mkfifo is not available");
    }
    // A 40 GB (sparse) file: refused by its size, nothing read.
    let big = dir.join("big.ply");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(40_000_000_000)
        .unwrap();
    let line = error_of(io::read_parts(&big));
    assert!(
        line.contains("big.ply") && line.contains("40000000000 bytes"),
        "{line}"
    );
    // The JSON readers share the check.
    let session = dir.join("s.json");
    std::os::unix::fs::symlink("/dev/zero", &session).unwrap();
    let line = error_of(cutaway::session::load(&session));
    assert!(
        line.contains("s.json") && line.contains("character device"),
        "{line}"
    );
    let line = error_of(cutaway::io::gesture::read_gesture(&session));
    assert!(line.contains("character device"), "{line}");
    let line = error_of(cutaway::io::path_file::read_path_file(&session));
    assert!(line.contains("character device"), "{line}");
}

#[test]
fn absurd_and_non_finite_coordinates_are_refused_naming_the_vertex() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 3e38 0\nf 1 2 3\n";
    let line = error_of(io::parse_bytes(Format::Obj, obj, "x"));
    assert!(
        line.contains("vertex 2 (counted from 0)") && line.contains("3e38"),
        "{line}"
    );
    let ply = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1e13 0 0\n0 1 0\n3 0 1 2\n";
    let line = error_of(io::parse_bytes(Format::Ply, ply, "x"));
    assert!(line.contains("vertex 1 (counted from 0)"), "{line}");
    let vtk = b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n0 0 0 1 0 0 0 -inf 0\n\
POLYGONS 1 4\n3 0 1 2\n";
    let line = error_of(io::parse_bytes(Format::Vtk, vtk, "x"));
    assert!(
        line.contains("vertex 2") && line.contains("non-finite"),
        "{line}"
    );
    // Binary STL: 3e38 is a valid f32.
    let mut stl = vec![0u8; 84];
    stl[80..84].copy_from_slice(&1u32.to_le_bytes());
    stl.extend_from_slice(&[0u8; 12]);
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 3e38, 0.0] {
        stl.extend_from_slice(&v.to_le_bytes());
    }
    stl.extend_from_slice(&[0u8; 2]);
    let line = error_of(io::parse_bytes(Format::Stl, &stl, "x"));
    assert!(line.contains("vertex 2"), "{line}");
    // Through a file: the line names it.
    let dir = scratch("coordinates");
    let path = dir.join("far.obj");
    std::fs::write(&path, obj).unwrap();
    let line = error_of(io::read_mesh(&path));
    assert!(
        line.starts_with(&format!("error: {}: ", path.display())),
        "{line}"
    );
    // 1e12 itself is accepted.
    let edge = b"v 0 0 0\nv 1e12 0 0\nv 0 -1e12 0\nf 1 2 3\n";
    io::parse_bytes(Format::Obj, edge, "x").unwrap();
}

#[test]
fn obj_vertex_weight_is_ignored_not_divided_by() {
    let dir = scratch("w");
    let path = dir.join("w.obj");
    // The normal reference sends the file through tobj, which would divide by w (and refuse 0).
    std::fs::write(
        &path,
        "v 2 4 6 0.5\nv 1 0 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n",
    )
    .unwrap();
    let mesh = io::read_mesh(&path).unwrap();
    let mut positions = mesh.positions.clone();
    positions.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    assert_eq!(
        positions,
        [
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::X,
            DVec3::new(2.0, 4.0, 6.0)
        ]
    );
}

#[test]
fn control_bytes_from_a_file_never_reach_the_error_line_raw() {
    // Two named parts, the second with a non-finite vertex: the error quotes its name.
    let obj =
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\no first\nf 1 2 3\no evil\x1b[2J\x07name\nf 1 2 4\n";
    let line = error_of(io::parse_bytes(Format::Obj, obj, "x"));
    assert!(line.contains("evil\\u{1b}[2J\\u{7}name"), "{line:?}");
    assert!(!line.chars().any(|c| c.is_control()), "{line:?}");
    let stl = b"solid \x1b]0;title\x07\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 \x1b[31m 0\nendloop\nendfacet\nendsolid\n";
    let line = error_of(io::parse_bytes(Format::Stl, stl, "x"));
    assert!(line.contains("\\u{1b}"), "{line:?}");
    assert!(!line.chars().any(|c| c.is_control()), "{line:?}");
    let session = "{\"format\": \"cutaway-session/1\", \"models\": [{\"path\": \"a.obj\", \"style\": \"\\u001b[31mred\\n\"}]}";
    let dir = scratch("control");
    let path = dir.join("s.json");
    std::fs::write(&path, session).unwrap();
    std::fs::write(dir.join("a.obj"), b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let line = error_of(cutaway::session::load(&path));
    assert!(line.contains("style"), "{line}");
    assert!(!line.chars().any(|c| c.is_control()), "{line:?}");
}

/// Valid files of every format and flavour, for truncation tests (built once).
fn valid_files() -> &'static [(Format, Vec<u8>)] {
    static FILES: std::sync::OnceLock<Vec<(Format, Vec<u8>)>> = std::sync::OnceLock::new();
    FILES.get_or_init(build_valid_files)
}

fn build_valid_files() -> Vec<(Format, Vec<u8>)> {
    let dir = scratch("valid");
    let mesh = awkward_tetrahedron();
    let mut files = vec![
        (Format::Obj, std::fs::read(data("two_cubes.obj")).unwrap()),
        (Format::Stl, std::fs::read(data("tetra_ascii.stl")).unwrap()),
        (Format::Ply, std::fs::read(data("cube_ascii.ply")).unwrap()),
        (Format::Vtk, std::fs::read(data("cube_strips.vtk")).unwrap()),
        (Format::Vtk, binary_vtk_cube()),
    ];
    for (format, name) in [
        (Format::Stl, "t.stl"),
        (Format::Ply, "t.ply"),
        (Format::Obj, "t.obj"),
    ] {
        io::write_mesh(&dir.join(name), &mesh).unwrap();
        files.push((format, std::fs::read(dir.join(name)).unwrap()));
    }
    files
}

#[test]
fn every_truncation_of_every_valid_file_is_handled() {
    for &(format, ref bytes) in valid_files() {
        assert!(
            io::parse_bytes(format, bytes, "x").is_ok(),
            "{format:?} fixture must parse"
        );
        for len in 0..bytes.len() {
            // Ok (a shorter file can still be a valid mesh) or an error; never a panic.
            let _ = io::parse_bytes(format, &bytes[..len], "x");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600), which in 0usize..4) {
        let _ = io::parse_bytes(Format::ALL[which], &bytes, "x");
    }

    /// Random bytes behind a valid header reach the parsers' payload code.
    #[test]
    fn random_payload_after_valid_header_never_panics(
        tail in proptest::collection::vec(any::<u8>(), 0..400),
        which in 0usize..5,
    ) {
        let headers: [(Format, &[u8]); 5] = [
            (Format::Ply, b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"),
            (Format::Ply, b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"),
            (Format::Vtk, b"# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n"),
            (Format::Stl, b"solid x\nfacet normal 0 0 1\nouter loop\n"),
            (Format::Obj, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf "),
        ];
        let (format, header) = headers[which];
        let mut bytes = header.to_vec();
        bytes.extend_from_slice(&tail);
        let _ = io::parse_bytes(format, &bytes, "x");
    }

    /// Flipping bytes of valid files exercises the paths between "valid" and "garbage".
    #[test]
    fn corrupted_valid_files_never_panic(which in 0usize..8, flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8)) {
        let files = valid_files();
        let (format, mut bytes) = files[which % files.len()].clone();
        for (at, value) in flips {
            let n = bytes.len();
            bytes[at % n] = value;
        }
        let _ = io::parse_bytes(format, &bytes, "x");
    }

    /// Byte flips of the contract's session, gesture and path examples: every JSON reader
    /// returns a value or an error, never panics.
    #[test]
    fn corrupted_json_documents_never_panic(which in 0usize..3, flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8)) {
        let samples: [&str; 3] = [
            r#"{"format": "cutaway-session/1", "models": [{"path": "knee.obj", "color": [0.9, 0.7, 0.6]}],
                "cutters": [{"target": 0, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                "views": {"ribbons": {"count": 5, "width": 2.0}}}]}"#,
            r#"{"format": "cutaway-gesture/1", "viewport": [1280, 800],
                "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
                "events": [{"type": "press", "x": 600, "y": 380}, {"type": "wheel", "delta": 3}]}"#,
            r#"{"format": "cutaway-path/1", "depth": 4.0, "points": [[0, 0, 0], [1, 2, 3]], "open": {"width": 1.5}}"#,
        ];
        let mut bytes = samples[which].as_bytes().to_vec();
        for (at, value) in flips {
            let n = bytes.len();
            bytes[at % n] = value;
        }
        let text = String::from_utf8_lossy(&bytes);
        match which {
            0 => { let _ = cutaway::session::parse(&text); }
            1 => { let _ = cutaway::io::gesture::parse_gesture(&text); }
            _ => { let _ = cutaway::io::path_file::parse_path_file(&text); }
        }
    }
}
