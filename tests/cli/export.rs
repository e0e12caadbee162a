//! End-to-end tests of `cutaway export`: the cut scene as glTF 2.0 binary, read back with the
//! `gltf` crate and checked by the Khronos glTF validator when it is installed.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::gltf_validator::{validate, validator_package};
use crate::scene_files::{
    box_obj, box_planes, cut_view, cutter, model, scratch, sphere_obj, write_session,
};
use cutaway::cutting::cut_scene::{PartKind, preview_geometry};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

/// A skin box cut by a box cutter with every view on (walls, removed piece, ribbons, slices),
/// a sphere inside it (uncut), a second cutter on the sphere with the normal cut only, and a
/// hidden model that is not exported.
fn cut_scene(dir: &Path) -> PathBuf {
    let all_views = serde_json::json!({"cut": true, "transparency": 0.3,
        "ribbons": {"count": 3, "width": 0.5}, "slices": {"count": 2, "width": 0.5}});
    write_session(
        dir,
        &[
            (
                "skin.obj",
                box_obj([-20.0, -20.0, -20.0], [20.0, 20.0, 20.0]),
            ),
            ("organ.obj", sphere_obj([0.0, 0.0, 0.0], 8.0, 24, 12)),
            ("hidden.obj", box_obj([30.0, 0.0, 0.0], [31.0, 1.0, 1.0])),
        ],
        vec![
            model("skin.obj", [0.9, 0.75, 0.65]),
            model("organ.obj", [0.8, 0.2, 0.2]),
            serde_json::json!({"path": "hidden.obj", "visible": false}),
        ],
        vec![
            cutter(
                0,
                box_planes(-10.0, 10.0, -30.0, -5.0, -10.0, 30.0),
                all_views,
            ),
            cutter(1, box_planes(0.0, 20.0, -20.0, 0.0, 0.0, 20.0), cut_view()),
        ],
        [0.0, -200.0, 0.0],
    )
}

fn export_json(session: &Path, out: &Path) -> serde_json::Value {
    let output = cutaway()
        .arg("export")
        .arg(session)
        .arg("--out")
        .arg(out)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

#[test]
fn export_reads_back_with_the_cut_s_nodes_materials_and_triangles() {
    let dir = scratch("export-read-back");
    let session = cut_scene(&dir);
    let out = dir.join("scene.glb");
    let summary = export_json(&session, &out);
    assert_eq!(summary["exact"], true, "{summary}");

    let scene = cutaway::session::load(&session).unwrap();
    let geometry = preview_geometry(&scene);
    assert!(geometry.notes.is_empty(), "{:?}", geometry.notes);
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(summary["bytes"], bytes.len());
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.clone().expect("a BIN chunk");

    // One root node with the unit and axis conversion; one child per visible model.
    let root = gltf.default_scene().unwrap().nodes().next().unwrap();
    assert_eq!(root.name(), Some("cutaway scene"));
    let (_, rotation, scale) = root.transform().decomposed();
    assert_eq!(scale, [0.001; 3]);
    let r = glam::Quat::from_array(rotation);
    let superior = r * glam::Vec3::Z;
    let anterior = r * glam::Vec3::Y;
    assert!(
        superior.distance(glam::Vec3::Y) < 1e-6,
        "Z-up becomes Y-up: {superior}"
    );
    assert!(
        anterior.distance(glam::Vec3::Z) < 1e-6,
        "anterior faces +Z: {anterior}"
    );
    let names: Vec<_> = root
        .children()
        .map(|n| n.name().unwrap().to_string())
        .collect();
    assert_eq!(names, ["skin", "organ"]);
    assert_eq!(summary["nodes"], 2);

    // Materials: skin surface, wall, removed, ribbon; organ surface and wall; contour.
    assert_eq!(gltf.materials().count(), 7);
    assert_eq!(summary["materials"], 7);
    let removed = gltf
        .materials()
        .find(|m| m.name() == Some("skin removed"))
        .unwrap();
    assert_eq!(removed.alpha_mode(), gltf::material::AlphaMode::Blend);
    assert!((removed.pbr_metallic_roughness().base_color_factor()[3] - 0.3).abs() < 1e-6);

    // Per node, triangles and line segments as the cut made them.
    let mut total_triangles = 0;
    for (m, node) in root.children().enumerate() {
        let mut triangles = 0;
        let mut segments = 0;
        let mut positions_seen = 0;
        for primitive in node.mesh().unwrap().primitives() {
            let reader = primitive.reader(|_| Some(&blob[..]));
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            assert!(indices.iter().all(|&i| (i as usize) < positions.len()));
            match primitive.mode() {
                gltf::mesh::Mode::Triangles => {
                    triangles += indices.len() / 3;
                    let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
                    assert_eq!(normals.len(), positions.len());
                    for n in normals {
                        assert!((glam::Vec3::from_array(n).length() - 1.0).abs() < 1e-5);
                    }
                }
                gltf::mesh::Mode::Lines => segments += indices.len() / 2,
                other => panic!("unexpected mode {other:?}"),
            }
            // Positions stay in scene millimetres.
            let bbox = scene.models[m].model.mesh.bbox();
            for p in &positions {
                let p = glam::DVec3::from_array(p.map(f64::from));
                assert!(
                    p.cmpge(bbox.min - 1e-3).all() && p.cmple(bbox.max + 1e-3).all(),
                    "{p}"
                );
            }
            positions_seen += positions.len();
        }
        assert!(positions_seen > 0);
        let expected: usize = geometry
            .parts
            .iter()
            .filter(|p| p.model == m)
            .map(|p| p.mesh.triangle_count())
            .sum();
        assert_eq!(triangles, expected, "{}", scene.models[m].model.name);
        let expected_segments: usize = geometry
            .contours
            .iter()
            .filter(|(model, _)| *model == m)
            .map(|(_, line)| line.len() - 1)
            .sum();
        assert!(expected_segments > 0);
        assert_eq!(
            segments, expected_segments,
            "{}",
            scene.models[m].model.name
        );
        total_triangles += triangles;
    }
    assert_eq!(summary["triangles"], total_triangles);
    for kind in [
        PartKind::Kept,
        PartKind::Wall,
        PartKind::Removed,
        PartKind::Ribbon,
        PartKind::SliceWall,
    ] {
        assert!(
            geometry
                .parts
                .iter()
                .any(|p| p.kind == kind && p.mesh.triangle_count() > 0),
            "the scene exercises {kind:?}"
        );
    }
}

#[test]
fn export_passes_the_khronos_validator_with_no_errors() {
    let Some(package) = validator_package() else {
        return skip(
            Resource::Validator,
            "CUTAWAY_GLTF_VALIDATOR is not set (npm install gltf-validator, then set it to the \
             package folder, as .ci/run does)",
        );
    };
    if Command::new("node").arg("--version").output().is_err() {
        return skip(Resource::Validator, "node is not installed");
    }
    let dir = scratch("export-validator");
    let session = cut_scene(&dir);
    let out = dir.join("scene.glb");
    export_json(&session, &out);
    let report = validate(&package, &out);
    let issues = &report["issues"];
    assert_eq!(issues["numErrors"], 0, "{issues:#}");
    assert!(
        report["info"]["totalTriangleCount"].as_u64().unwrap() > 0,
        "{report}"
    );
    // A broken file is caught: the validator is really looking.
    let mut bytes = std::fs::read(&out).unwrap();
    bytes.truncate(bytes.len() - 8);
    let broken = dir.join("broken.glb");
    std::fs::write(&broken, bytes).unwrap();
    let report = validate(&package, &broken);
    assert!(report["issues"]["numErrors"].as_u64().unwrap() > 0);
}

#[test]
fn an_uncut_scene_exports_every_visible_model() {
    let dir = scratch("export-uncut");
    let session = write_session(
        &dir,
        &[
            ("a.obj", box_obj([0.0; 3], [1.0, 2.0, 3.0])),
            ("w.obj", box_obj([5.0; 3], [6.0; 3])),
        ],
        vec![
            model("a.obj", [0.5, 0.5, 0.5]),
            serde_json::json!({"path": "w.obj", "style": "wireframe"}),
        ],
        vec![],
        [0.0, -50.0, 0.0],
    );
    let out = dir.join("a.glb");
    let summary = export_json(&session, &out);
    // The wireframe box is its 18 edges (12 sides and 6 face diagonals), not triangles.
    assert_eq!(
        (
            summary["nodes"].as_u64(),
            summary["triangles"].as_u64(),
            summary["lines"].as_u64()
        ),
        (Some(2), Some(12), Some(18))
    );
    let gltf = gltf::Gltf::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let node = gltf.nodes().find(|n| n.name() == Some("a")).unwrap();
    let bounds = node
        .mesh()
        .unwrap()
        .primitives()
        .next()
        .unwrap()
        .bounding_box();
    assert_eq!((bounds.min, bounds.max), ([0.0; 3], [1.0, 2.0, 3.0]));
}

#[test]
fn export_errors_are_one_line_and_leave_no_file() {
    let dir = scratch("export-errors");
    let session = write_session(
        &dir,
        &[("a.obj", box_obj([0.0; 3], [1.0; 3]))],
        vec![model("a.obj", [0.5, 0.5, 0.5])],
        vec![],
        [0.0, -50.0, 0.0],
    );
    // The output folder does not exist.
    let out = dir.join("missing/scene.glb");
    let output = cutaway()
        .arg("export")
        .arg(&session)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: ", out.display())),
        "{stderr}"
    );
    // A missing session.
    let missing = dir.join("none.json");
    let output = cutaway()
        .arg("export")
        .arg(&missing)
        .arg("--out")
        .arg(dir.join("x.glb"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("none.json"), "{stderr}");
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "no partial or temporary files: {names:?}");
}

/// `export --critical` bakes the risk map into the walls' vertex colours: red within 2 mm of the
/// critical vessel, the wall colour beyond 10 mm, on a white `risk map` material.
#[test]
fn export_bakes_the_risk_map_into_the_walls_vertex_colours() {
    let dir = scratch("export-risk");
    // A 80 mm block cut in front of y = 0; a vessel of radius 5 centred 6 mm behind that wall.
    let session = write_session(
        &dir,
        &[
            ("skin.obj", box_obj([-40.0; 3], [40.0; 3])),
            ("vessel.obj", sphere_obj([0.0, 6.0, 0.0], 5.0, 48, 24)),
        ],
        vec![
            model("skin.obj", [0.9, 0.75, 0.65]),
            model("vessel.obj", [0.8, 0.2, 0.2]),
        ],
        vec![cutter(
            0,
            box_planes(-20.0, 20.0, -60.0, 0.0, -20.0, 20.0),
            cut_view(),
        )],
        [0.0, -200.0, 0.0],
    );
    let out = dir.join("risk.glb");
    let output = cutaway()
        .arg("export")
        .arg(&session)
        .args(["--out"])
        .arg(&out)
        .args(["--critical", "vessel", "--json"])
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let gltf = gltf::Gltf::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let blob = gltf.blob.clone().unwrap();
    let risk = gltf
        .meshes()
        .flat_map(|m| m.primitives().collect::<Vec<_>>())
        .find(|p| p.material().name() == Some("risk map"))
        .expect("a risk map primitive");
    assert_eq!(
        risk.material().pbr_metallic_roughness().base_color_factor(),
        [1.0; 4]
    );
    let reader = risk.reader(|_| Some(&blob[..]));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let colors: Vec<[f32; 3]> = reader.read_colors(0).unwrap().into_rgb_f32().collect();
    assert_eq!(positions.len(), colors.len());
    let linear = |c: [f32; 3]| c.map(cutaway::render::srgb_to_linear);
    let red = linear(cutaway::scene::risk::RISK_NEAR_COLOR);
    let wall_srgb: [f32; 3] = std::array::from_fn(|k| {
        let skin = [0.9, 0.75, 0.65][k];
        skin + (cutaway::render::WALL_TINT[k] - skin) * cutaway::render::WALL_MIX
    });
    let wall = linear(wall_srgb);
    let same = |a: [f32; 3], b: [f32; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-4);
    let (mut near, mut far) = (0, 0);
    for (p, &c) in positions.iter().zip(&colors) {
        let p = glam::DVec3::from_array(p.map(f64::from));
        // The sphere file's vertices lie on the radius, so its surface is at least this far.
        let d = (p - glam::DVec3::new(0.0, 6.0, 0.0)).length() - 5.0;
        if d <= 1.9 {
            near += 1;
            assert!(same(c, red), "{p} is {d:.2} mm from the vessel: {c:?}");
        }
        if d >= 10.6 {
            far += 1;
            assert!(same(c, wall), "{p} is {d:.2} mm from the vessel: {c:?}");
        }
    }
    assert!(near > 10 && far > 10, "{near} near, {far} far vertices");
    // Without a risk map the walls keep their material.
    let plain = dir.join("plain.glb");
    let summary = export_json(&session, &plain);
    assert_eq!(summary["exact"], true);
    let gltf = gltf::Gltf::from_slice(&std::fs::read(&plain).unwrap()).unwrap();
    assert!(gltf.materials().all(|m| m.name() != Some("risk map")));
}
