//! Small scenes written as files for the end-to-end tests of `export` and `metrics`: OBJ meshes
//! with known measures and `cutaway-session/1` files that cut them with box cutters.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A fresh scratch folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An axis-aligned box, outward-facing, as OBJ text.
pub fn box_obj(min: [f64; 3], max: [f64; 3]) -> String {
    let mut text = String::new();
    for i in 0..8 {
        let p = |k: usize| if i >> k & 1 == 0 { min[k] } else { max[k] };
        writeln!(text, "v {} {} {}", p(0), p(1), p(2)).unwrap();
    }
    for q in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        writeln!(text, "f {} {} {}", q[0] + 1, q[1] + 1, q[2] + 1).unwrap();
        writeln!(text, "f {} {} {}", q[0] + 1, q[2] + 1, q[3] + 1).unwrap();
    }
    text
}

/// A closed UV sphere (vertices on the sphere), outward-facing, as OBJ text.
pub fn sphere_obj(center: [f64; 3], radius: f64, segments: usize, rings: usize) -> String {
    let mut text = String::new();
    let v = |text: &mut String, p: [f64; 3]| {
        writeln!(
            text,
            "v {} {} {}",
            center[0] + p[0],
            center[1] + p[1],
            center[2] + p[2]
        )
        .unwrap()
    };
    v(&mut text, [0.0, 0.0, -radius]);
    for r in 1..rings {
        let theta = PI * r as f64 / rings as f64;
        for s in 0..segments {
            let phi = 2.0 * PI * s as f64 / segments as f64;
            let (st, ct) = theta.sin_cos();
            let (sp, cp) = phi.sin_cos();
            v(
                &mut text,
                [radius * st * cp, radius * st * sp, -radius * ct],
            );
        }
    }
    v(&mut text, [0.0, 0.0, radius]);
    let ring = |r: usize, s: usize| 2 + (r - 1) * segments + s % segments;
    let top = 2 + (rings - 1) * segments;
    for s in 0..segments {
        writeln!(text, "f 1 {} {}", ring(1, s + 1), ring(1, s)).unwrap();
        writeln!(
            text,
            "f {top} {} {}",
            ring(rings - 1, s),
            ring(rings - 1, s + 1)
        )
        .unwrap();
        for r in 1..rings - 1 {
            let (a, b, c, d) = (
                ring(r, s),
                ring(r, s + 1),
                ring(r + 1, s + 1),
                ring(r + 1, s),
            );
            writeln!(text, "f {a} {b} {c}").unwrap();
            writeln!(text, "f {a} {c} {d}").unwrap();
        }
    }
    text
}

/// The planes of a straight box cutter spanning x0..x1, y0..y1, z0..z1 (three parallel planes of
/// constant x), as session JSON.
pub fn box_planes(x0: f64, x1: f64, y0: f64, y1: f64, z0: f64, z1: f64) -> serde_json::Value {
    let plane = |x: f64| serde_json::json!([[x, y0, z1], [x, y1, z1], [x, y1, z0], [x, y0, z0]]);
    serde_json::json!([plane(x0), plane((x0 + x1) * 0.5), plane(x1)])
}

/// A model entry of a session.
pub fn model(path: &str, color: [f32; 3]) -> serde_json::Value {
    serde_json::json!({"path": path, "color": color, "opacity": 1.0, "style": "solid", "visible": true})
}

/// A cutter entry of a session with the given views.
pub fn cutter(
    target: usize,
    planes: serde_json::Value,
    views: serde_json::Value,
) -> serde_json::Value {
    serde_json::json!({"target": target, "kind": "straight", "smooth": false, "planes": planes, "views": views})
}

/// The normal-cut view only.
pub fn cut_view() -> serde_json::Value {
    serde_json::json!({"cut": true, "transparency": null, "ribbons": null, "slices": null})
}

/// Writes `files` (name, text) and a session of `models` and `cutters` seen from `eye` toward the
/// origin (Z up) into `dir`; returns the session's path.
pub fn write_session(
    dir: &Path,
    files: &[(&str, String)],
    models: Vec<serde_json::Value>,
    cutters: Vec<serde_json::Value>,
    eye: [f64; 3],
) -> PathBuf {
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let session = serde_json::json!({
        "format": "cutaway-session/1",
        "models": models,
        "cutters": cutters,
        "camera": {"eye": eye, "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
        "render": {"background": [1, 1, 1, 1], "antialias": true, "stereo": "none"}
    });
    let path = dir.join("session.json");
    std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
    path
}
