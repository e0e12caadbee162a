//! One scalpel path: strokes drawn in the window (pixels through the camera, the press, the
//! drag's picks, the release) and the same strokes replayed by `cutaway scalpel` from a
//! `cutaway-path/1` file give the same meshes, bit for bit: the top cut, the layer below it
//! and the opening.

use std::path::PathBuf;

use glam::{DVec2, DVec3};

use super::*;
use crate::cli::scalpel::{ScalpelArgs, path_settings, region_scene};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-parity-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn bits(mesh: &Mesh) -> (Vec<[u64; 3]>, Vec<[u32; 3]>) {
    (
        mesh.positions
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .collect(),
        mesh.triangles.clone(),
    )
}

/// Draws `strokes` (pixel paths) in a window's session on the scene of `target` and returns
/// the scene's meshes afterwards, with the points each stroke fed to the scalpel.
fn draw_in_window(
    target: &std::path::Path,
    settings: ScalpelSettings,
    strokes: &[Vec<DVec2>],
) -> (Vec<Mesh>, Vec<Vec<DVec3>>) {
    let mesh = crate::io::read_mesh(target).unwrap();
    let mut scene = region_scene(&mesh, target);
    scene.camera = scene.framing_camera();
    let viewport = DVec2::new(800.0, 600.0);
    let mut session = ScalpelSession {
        settings,
        ..ScalpelSession::default()
    };
    let mut fed = Vec::new();
    for px in strokes {
        assert_eq!(session.press(&scene, viewport, px[0]), Ok(Some(0)));
        for &p in &px[1..] {
            session.drag(&mut scene, viewport, p).expect("step");
        }
        let released = session.release(&mut scene);
        assert!(
            matches!(&released, Released::Committed { refused, .. } if refused.is_empty()),
            "{released:?}"
        );
        fed.push(session.last_points.clone());
    }
    let meshes = scene
        .models
        .iter()
        .map(|m| (*m.model.mesh).clone())
        .collect();
    (meshes, fed)
}

#[test]
fn a_stroke_replayed_by_the_command_line_gives_the_windows_meshes_bit_for_bit() {
    let dir = scratch("layers");
    // Skin over muscle: one file, two regions (two models in the scene).
    let mut file_mesh = csg::testkit::icosphere(4, 10.0);
    file_mesh.append(&csg::testkit::icosphere(3, 9.6));
    let target = dir.join("nested.obj");
    crate::io::write_mesh(&target, &file_mesh).unwrap();
    let settings = ScalpelSettings {
        tool: Tool::Scalpel,
        depth: 1.0,
        opening: 0.4,
        window: 0.5,
        layers: true,
    };
    let line = |y: f64, from: f64, to: f64| -> Vec<DVec2> {
        (0..=24)
            .map(|i| DVec2::new(800.0 * (from + (to - from) * i as f64 / 24.0), 600.0 * y))
            .collect()
    };
    // Two grooves, the second crossing the first.
    let strokes = vec![line(0.5, 0.38, 0.62), {
        let mut v: Vec<DVec2> = (0..=24)
            .map(|i| {
                DVec2::new(
                    400.0 + 20.0 * (i as f64 / 24.0 - 0.5),
                    600.0 * (0.4 + 0.2 * i as f64 / 24.0),
                )
            })
            .collect();
        v.dedup();
        v
    }];
    let (window, fed) = draw_in_window(&target, settings, &strokes);
    assert_eq!(window.len(), 2, "two models");
    let inner = crate::io::read_mesh(&target).unwrap();
    let inner_before = &csg::regions::split_regions(&inner)[1];
    assert_ne!(
        bits(&window[1]),
        bits(inner_before),
        "the blade reached the layer below in the window"
    );

    // The same points as a path file, replayed by `cutaway scalpel`.
    let strokes_json: Vec<Vec<[f64; 3]>> = fed
        .iter()
        .map(|s| s.iter().map(|p| p.to_array()).collect())
        .collect();
    let json = serde_json::json!({
        "format": "cutaway-path/1", "depth": settings.depth, "tool": "scalpel",
        "strokes": strokes_json,
        "open": {"width": settings.opening, "window": settings.window},
    });
    let path = dir.join("path.json");
    std::fs::write(&path, json.to_string()).unwrap();
    let parsed = crate::io::path_file::read_path_file(&path).unwrap();
    assert_eq!(
        parsed.strokes, fed,
        "the path file holds the window's points exactly"
    );
    assert_eq!(path_settings(&parsed), settings);
    let out = dir.join("out.obj");
    crate::cli::scalpel::run(&ScalpelArgs {
        target: target.clone(),
        path,
        out: out.clone(),
        json: false,
    })
    .unwrap();
    let written = crate::io::read_mesh_verbatim(&out).unwrap();
    let mut expected = Mesh::default();
    for m in &window {
        expected.append(m);
    }
    assert_eq!(
        written.triangles.len(),
        expected.triangles.len(),
        "triangle count"
    );
    assert!(
        bits(&written) == bits(&expected),
        "the command line's mesh is the window's, bit for bit"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
