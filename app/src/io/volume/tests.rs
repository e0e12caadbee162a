//! The volume loader end to end on synthetic volumes: one anatomy written with different axis
//! orders, flips, spaces and formats gives the same structures and the same surfaces.

use std::path::{Path, PathBuf};

use glam::{DAffine3, DMat3, DVec3};

use super::*;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-volume-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The canonical grid: x fastest, RAS, spacing (1, 1.5, 2), origin (10, -5, 3).
const DIMS: [usize; 3] = [7, 6, 5];

fn canonical_affine() -> DAffine3 {
    DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::new(1.0, 1.5, 2.0)),
        DVec3::new(10.0, -5.0, 3.0),
    )
}

/// Three labels: a box, an L on the grid border, a single voxel; value 0 elsewhere.
fn canonical_label(i: usize, j: usize, k: usize) -> u8 {
    if (1..4).contains(&i) && (1..3).contains(&j) && (1..4).contains(&k) {
        2
    } else if i == 6 && k <= 2 || (i >= 5 && j == 5 && k == 0) {
        5
    } else if (i, j, k) == (3, 4, 3) {
        9
    } else {
        0
    }
}

/// A file's axis order: file axis a runs along canonical axis `axes[a]`, reversed when
/// `flips[a]`. Returns the file's dims, its samples (file x fastest) and its RAS affine.
fn permuted(axes: [usize; 3], flips: [bool; 3]) -> ([usize; 3], Vec<u8>, DAffine3) {
    let dims = axes.map(|a| DIMS[a]);
    let canonical = canonical_affine();
    let mut columns = [DVec3::ZERO; 3];
    let mut origin_index = [0usize; 3];
    for a in 0..3 {
        let step = canonical.matrix3.col(axes[a]);
        columns[a] = if flips[a] { -step } else { step };
        if flips[a] {
            origin_index[axes[a]] = DIMS[axes[a]] - 1;
        }
    }
    let origin = canonical.transform_point3(DVec3::new(
        origin_index[0] as f64,
        origin_index[1] as f64,
        origin_index[2] as f64,
    ));
    let mut samples = Vec::with_capacity(dims.iter().product());
    for r in 0..dims[2] {
        for q in 0..dims[1] {
            for p in 0..dims[0] {
                let mut c = [0usize; 3];
                for (a, f) in [p, q, r].into_iter().enumerate() {
                    c[axes[a]] = if flips[a] { DIMS[axes[a]] - 1 - f } else { f };
                }
                samples.push(canonical_label(c[0], c[1], c[2]));
            }
        }
    }
    let affine = DAffine3::from_mat3_translation(
        DMat3::from_cols(columns[0], columns[1], columns[2]),
        origin,
    );
    (dims, samples, affine)
}

fn nrrd_vector(v: DVec3) -> String {
    format!("({},{},{})", v.x, v.y, v.z)
}

/// Writes the permuted volume as NRRD in LPS (x and y negated) or RAS.
fn write_nrrd(path: &Path, axes: [usize; 3], flips: [bool; 3], lps: bool, gzip: bool) {
    let (dims, samples, affine) = permuted(axes, flips);
    let to_space = if lps {
        DVec3::new(-1.0, -1.0, 1.0)
    } else {
        DVec3::ONE
    };
    let directions = (0..3)
        .map(|a| nrrd_vector(affine.matrix3.col(a) * to_space))
        .collect::<Vec<_>>()
        .join(" ");
    let space = if lps {
        "left-posterior-superior"
    } else {
        "right-anterior-superior"
    };
    let bytes = nrrd::write_for_test(
        space,
        "unsigned char",
        &dims,
        &directions,
        affine.translation * to_space,
        &samples,
        gzip,
        "kinds: domain domain domain",
    );
    std::fs::write(path, bytes).unwrap();
}

fn write_nifti_gz(path: &Path, axes: [usize; 3], flips: [bool; 3]) {
    use std::io::Write as _;
    let (dims, samples, affine) = permuted(axes, flips);
    let m = affine.matrix3;
    let t = affine.translation;
    let row = |r: usize| {
        [
            m.x_axis[r] as f32,
            m.y_axis[r] as f32,
            m.z_axis[r] as f32,
            t[r] as f32,
        ]
    };
    let bytes = nifti::write_for_test(dims, 2, [row(0), row(1), row(2)], &samples);
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(&bytes).unwrap();
    std::fs::write(path, e.finish().unwrap()).unwrap();
}

/// The largest distance from a vertex of `a` to the nearest vertex of `b` (small meshes only).
fn vertex_distance(a: &csg::Mesh, b: &csg::Mesh) -> f64 {
    a.positions
        .iter()
        .map(|p| {
            b.positions
                .iter()
                .map(|q| p.distance(*q))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn assert_same_surfaces(a: &[StructureSurface], b: &[StructureSurface], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.structure, y.structure, "{what}");
        let report = y.mesh.report();
        assert!(
            report.closed && report.manifold,
            "{what}: label {} not closed",
            y.structure.value
        );
        let (va, vb) = (x.mesh.volume(), y.mesh.volume());
        assert!(
            vb > 0.0,
            "{what}: label {} inside out ({vb})",
            y.structure.value
        );
        assert!(
            (va - vb).abs() <= 1e-9 * va.abs(),
            "{what}: volume {va} vs {vb}"
        );
        assert_eq!(x.mesh.triangles.len(), y.mesh.triangles.len(), "{what}");
        assert_eq!(x.mesh.positions.len(), y.mesh.positions.len(), "{what}");
        let d = vertex_distance(&x.mesh, &y.mesh).max(vertex_distance(&y.mesh, &x.mesh));
        assert!(
            d < 1e-9,
            "{what}: label {} vertices differ by {d}",
            x.structure.value
        );
    }
}

#[test]
fn permuted_flipped_and_lps_volumes_give_the_same_surfaces() {
    let dir = scratch("permuted");
    let reference = dir.join("reference.nrrd");
    write_nrrd(&reference, [0, 1, 2], [false; 3], false, false);
    let base = read_volume(&reference, None).unwrap();
    let counts: Vec<(u32, u64)> = base
        .structures
        .iter()
        .map(|s| (s.value, s.voxels))
        .collect();
    assert_eq!(counts, vec![(2, 18), (5, 19), (9, 1)]);
    assert_eq!(base.structures[0].name, "label 2");
    assert_eq!(base.spacing(), [1.0, 1.5, 2.0]);
    let base_surfaces = surfaces(&base, None, &|_| true).unwrap();

    let variants: [([usize; 3], [bool; 3]); 4] = [
        ([0, 1, 2], [true, false, false]),
        ([2, 0, 1], [false, true, false]),
        ([1, 2, 0], [true, true, true]),
        ([2, 1, 0], [false, false, true]),
    ];
    for (n, (axes, flips)) in variants.into_iter().enumerate() {
        for (lps, gzip) in [(true, true), (false, false)] {
            let path = dir.join(format!("v{n}-{lps}.nrrd"));
            write_nrrd(&path, axes, flips, lps, gzip);
            let volume = read_volume(&path, None).unwrap();
            let what = format!("NRRD axes {axes:?} flips {flips:?} lps {lps}");
            assert_same_surfaces(
                &base_surfaces,
                &surfaces(&volume, None, &|_| true).unwrap(),
                &what,
            );
        }
        let path = dir.join(format!("v{n}.nii.gz"));
        write_nifti_gz(&path, axes, flips);
        let volume = read_volume(&path, None).unwrap();
        let what = format!("NIfTI axes {axes:?} flips {flips:?}");
        assert_same_surfaces(
            &base_surfaces,
            &surfaces(&volume, None, &|_| true).unwrap(),
            &what,
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_table_beside_the_volume_names_its_labels() {
    let dir = scratch("beside");
    let path = dir.join("atlas.nrrd");
    write_nrrd(&path, [0, 1, 2], [false; 3], true, true);
    std::fs::write(dir.join("LICENSE.txt"), "Permission is granted.\n").unwrap();
    std::fs::write(
        dir.join("atlas-lut.ctbl"),
        "2 box 10 20 30 255\n9 dot 1 2 3 255\n",
    )
    .unwrap();
    let volume = read_volume(&path, None).unwrap();
    let names: Vec<(&str, [u8; 3])> = volume
        .structures
        .iter()
        .map(|s| (s.name.as_str(), s.color))
        .collect();
    assert_eq!(
        names,
        vec![
            ("box", [10, 20, 30]),
            ("label 5", default_color(5)),
            ("dot", [1, 2, 3])
        ]
    );
    // --labels wins over the table beside.
    let other = dir.join("other.txt");
    std::fs::write(&other, "5    0 0 255    1 1 1  \"L shape\"\n").unwrap();
    let volume = read_volume(&path, Some(&other)).unwrap();
    assert_eq!(volume.structures[1].name, "L shape");
    assert_eq!(volume.structures[0].name, "label 2");
    // A broken table found by its name is an error naming it.
    std::fs::write(dir.join("atlas.txt"), "2 box 10 20\n").unwrap();
    let err = format!("{:#}", read_volume(&path, None).unwrap_err());
    assert!(err.contains("atlas.txt: line 1"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_mask_directory_is_one_structure_per_file() {
    let dir = scratch("masks");
    let (dims, samples, affine) = permuted([0, 1, 2], [false; 3]);
    let m = affine.matrix3;
    let t = affine.translation;
    let row = |r: usize| {
        [
            m.x_axis[r] as f32,
            m.y_axis[r] as f32,
            m.z_axis[r] as f32,
            t[r] as f32,
        ]
    };
    let srow = [row(0), row(1), row(2)];
    for (name, value) in [("box", 2u8), ("ell", 5), ("dot", 9)] {
        let mask: Vec<u8> = samples.iter().map(|&s| u8::from(s == value)).collect();
        std::fs::write(
            dir.join(format!("{name}.nii")),
            nifti::write_for_test(dims, 2, srow, &mask),
        )
        .unwrap();
    }
    // An overlapping mask goes to a second layer.
    let all: Vec<u8> = samples.iter().map(|&s| u8::from(s != 0)).collect();
    std::fs::write(
        dir.join("zall.nii"),
        nifti::write_for_test(dims, 2, srow, &all),
    )
    .unwrap();
    assert!(is_volume(&dir));
    let volume = read_volume(&dir, None).unwrap();
    let got: Vec<(u32, &str, u64, usize)> = volume
        .structures
        .iter()
        .map(|s| (s.value, s.name.as_str(), s.voxels, s.layer))
        .collect();
    assert_eq!(
        got,
        vec![
            (1, "box", 18, 0),
            (2, "dot", 1, 0),
            (3, "ell", 19, 0),
            (4, "zall", 38, 1)
        ]
    );
    let parts = crate::io::read_parts(&dir).unwrap();
    assert_eq!(parts.len(), 4);
    assert_eq!(parts[3].name, "zall");
    // Surfaced mask by mask (overlaps and all), each structure is the packed path's.
    let packed = surfaces(&volume, None, &|_| true).unwrap();
    let streamed = std::sync::Mutex::new(Vec::new());
    let folder = super::mask_surfaces::surfaces_each(
        &dir,
        &[],
        &csg::labels::SurfaceOptions::default(),
        &|_| true,
        &|_, s| {
            streamed.lock().unwrap().extend(s);
            true
        },
    )
    .unwrap();
    assert_eq!(
        folder.structures,
        volume
            .structures
            .iter()
            .map(|s| Structure {
                layer: 0,
                ..s.clone()
            })
            .collect::<Vec<_>>()
    );
    let mut streamed = streamed.into_inner().unwrap();
    streamed.sort_by_key(|s| s.structure.value);
    assert_eq!(streamed.len(), packed.len());
    for (a, b) in packed.iter().zip(&streamed) {
        assert_eq!(
            (a.structure.value, &a.structure.name),
            (b.structure.value, &b.structure.name)
        );
        assert_eq!(
            a.mesh.triangles.len(),
            b.mesh.triangles.len(),
            "{}",
            a.structure.name
        );
        let (va, vb) = (a.mesh.volume(), b.mesh.volume());
        assert!(
            (va - vb).abs() <= 1e-9 * va.abs(),
            "{}: {va} vs {vb}",
            a.structure.name
        );
    }
    // A mask on another grid is refused, naming it.
    let shifted = [[1.0, 0.0, 0.0, 99.0], srow[1], srow[2]];
    std::fs::write(
        dir.join("moved.nii"),
        nifti::write_for_test(dims, 2, shifted, &all),
    )
    .unwrap();
    let err = format!("{:#}", read_volume(&dir, None).unwrap_err());
    assert!(err.contains("moved.nii: not on the same grid as"), "{err}");
    let options = csg::labels::SurfaceOptions::default();
    let err = super::mask_surfaces::surfaces_each(&dir, &[], &options, &|_| true, &|_, _| true);
    let err = format!("{:#}", err.unwrap_err());
    assert!(err.contains("moved.nii: not on the same grid as"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_empty_label_map_is_an_error() {
    let dir = scratch("empty");
    let path = dir.join("empty.nrrd");
    let bytes = nrrd::write_for_test(
        "RAS",
        "uchar",
        &[2, 2, 2],
        "(1,0,0) (0,1,0) (0,0,1)",
        DVec3::ZERO,
        &[0; 8],
        false,
        "",
    );
    std::fs::write(&path, bytes).unwrap();
    let err = format!("{:#}", read_volume(&path, None).unwrap_err());
    assert!(
        err.ends_with("empty.nrrd: empty label map: every voxel is 0 (background)"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn detection_by_extension_and_content() {
    assert_eq!(
        VolumeFormat::from_path(Path::new("a/b.SEG.NRRD")),
        Some(VolumeFormat::Nrrd)
    );
    assert_eq!(
        VolumeFormat::from_path(Path::new("b.nhdr")),
        Some(VolumeFormat::Nrrd)
    );
    assert_eq!(
        VolumeFormat::from_path(Path::new("b.nii.gz")),
        Some(VolumeFormat::Nifti)
    );
    assert_eq!(VolumeFormat::from_path(Path::new("b.gz")), None);
    assert_eq!(VolumeFormat::sniff(b"NRRD0004\n"), Some(VolumeFormat::Nrrd));
    let nii = nifti::write_for_test(
        [1, 1, 1],
        2,
        [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ],
        &[1],
    );
    assert_eq!(VolumeFormat::sniff(&nii), Some(VolumeFormat::Nifti));
    assert_eq!(VolumeFormat::sniff(b"ply\n"), None);
    assert_eq!(volume_stem(Path::new("x/chest.seg.nrrd")), "chest");
    assert_eq!(volume_stem(Path::new("left_lung.nii.gz")), "left_lung");
    // A volume without a volume extension is found by its content.
    let dir = scratch("sniff");
    let path = dir.join("labels.dat");
    std::fs::write(&path, &nii).unwrap();
    assert!(is_volume(&path));
    assert_eq!(read_volume(&path, None).unwrap().structures.len(), 1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn default_colours_are_stable_and_distinct() {
    assert_eq!(default_color(17), default_color(17));
    let colours: std::collections::HashSet<[u8; 3]> = (1..=64).map(default_color).collect();
    assert_eq!(colours.len(), 64);
}

#[test]
fn detached_header_reads_its_data_file() {
    use std::io::Write as _;
    let dir = scratch("nhdr");
    let (dims, samples, _) = permuted([0, 1, 2], [false; 3]);
    let wide: Vec<u8> = samples
        .iter()
        .flat_map(|&s| (s as u16 * 1000).to_be_bytes())
        .collect();
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(&[b"skip me\n".as_slice(), &wide].concat())
        .unwrap();
    std::fs::write(dir.join("data.raw.gz"), e.finish().unwrap()).unwrap();
    let header = format!(
        "NRRD0004\n# detached\ntype: ushort\ndimension: 3\nspace: RAS\nsizes: {} {} {}\nspace directions: (1,0,0) (0,1.5,0) (0,0,2)\nspace origin: (10,-5,3)\nendian: big\nencoding: gzip\nbyte skip: 8\ndata file: data.raw.gz\n",
        dims[0], dims[1], dims[2]
    );
    let path = dir.join("vol.nhdr");
    std::fs::write(&path, header).unwrap();
    let volume = read_volume(&path, None).unwrap();
    let counts: Vec<(u32, u64)> = volume
        .structures
        .iter()
        .map(|s| (s.value, s.voxels))
        .collect();
    assert_eq!(counts, vec![(2000, 18), (5000, 19), (9000, 1)]);
    assert_eq!(volume.world_from_voxel, canonical_affine());
    std::fs::remove_dir_all(&dir).ok();
}

/// A gzip mask read a few bytes at a time: runs cut by a chunk's edge join up again.
#[test]
fn a_gzip_mask_read_in_small_chunks_has_the_runs_of_the_whole() {
    use std::io::Write as _;
    let dir = scratch("mask_chunks");
    let dims = [5usize, 4, 3];
    let mask: Vec<u8> = (0..60u32)
        .map(|i| u8::from(i % 7 < 3 || (20..31).contains(&i)))
        .collect();
    let srow = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ];
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&nifti::write_for_test(dims, 2, srow, &mask))
        .unwrap();
    let path = dir.join("m.nii.gz");
    std::fs::write(&path, gz.finish().unwrap()).unwrap();
    let whole = masks::read_mask(&path).unwrap();
    let expected = masks::runs_of(mask.len(), |i| mask[i] != 0);
    assert_eq!(whole.layers, vec![expected.clone()]);
    for chunk in [1, 2, 3, 7, 64] {
        let read = masks::read_mask_chunked(&path, chunk).unwrap();
        assert_eq!(read.layers, vec![expected.clone()], "chunk {chunk}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
