//! End-to-end tests of `cutaway scalpel` (CONTRACT.md: `cutaway-path/1` and its JSON).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("scalpel-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes an OBJ of an `n × n` unit grid on z = 0 (an open sheet).
fn write_sheet(path: &Path, n: u32) {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            writeln!(s, "v {i} {j} 0").unwrap();
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            writeln!(s, "f {} {} {}", id(i, j), id(i + 1, j), id(i + 1, j + 1)).unwrap();
            writeln!(s, "f {} {} {}", id(i, j), id(i + 1, j + 1), id(i, j + 1)).unwrap();
        }
    }
    std::fs::write(path, s).unwrap();
}

fn write_sphere(path: &Path) {
    let m = csg::testkit::icosphere(3, 10.0);
    let mut s = String::new();
    for p in &m.positions {
        writeln!(s, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    for t in &m.triangles {
        writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    std::fs::write(path, s).unwrap();
}

fn run_json(target: &Path, path: &Path, out: &Path) -> serde_json::Value {
    let o = cutaway()
        .arg("scalpel")
        .arg(target)
        .arg("--path")
        .arg(path)
        .arg("--out")
        .arg(out)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

fn face_count(obj: &Path) -> usize {
    std::fs::read_to_string(obj)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("f "))
        .count()
}

fn assert_one_error_line(out: &Output, file: &Path, needle: &str) {
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr.clone()).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: ", file.display())),
        "{stderr}"
    );
    assert!(stderr.contains(needle), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn slit_on_a_sheet_reports_the_contract_json() {
    let dir = scratch("slit");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 20);
    let points: Vec<[f64; 3]> = (0..=30)
        .map(|i| [3.3 + 0.4 * i as f64, 5.4 + 0.1 * i as f64, 0.0])
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 0.0, "tool": "scalpel", "points": points});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 31);
    assert_eq!(v["closed"], false);
    assert_eq!(v["manifold"], true);
    let created = v["triangles_created"].as_u64().unwrap();
    let cut = v["triangles_cut"].as_u64().unwrap();
    assert!(cut > 10 && created > 10, "{v}");
    assert!(created <= 2 * cut + 4, "{v}");
    assert!(v["step_us_p50"].as_f64().unwrap() > 0.0);
    assert!(v["step_us_max"].as_f64().unwrap() >= v["step_us_p50"].as_f64().unwrap());
    let first = v["step_us_first"].as_f64().unwrap();
    assert!(
        first > 0.0 && first <= v["step_us_max"].as_f64().unwrap(),
        "{v}"
    );
    assert_eq!(face_count(&out), 800 + created as usize);
    for key in [
        "steps",
        "triangles_cut",
        "triangles_created",
        "step_us_p50",
        "step_us_max",
        "step_us_first",
        "closed",
        "manifold",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v.as_object().unwrap().len(), 8);
}

#[test]
fn groove_on_a_sphere_stays_closed_and_opens() {
    let dir = scratch("groove");
    let (target, path, out) = (
        dir.join("sphere.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sphere(&target);
    let points: Vec<[f64; 3]> = (0..=30)
        .map(|i| {
            let a = 0.2 + 1.0 * i as f64 / 30.0;
            [10.0 * a.cos(), 10.0 * a.sin(), 0.0]
        })
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 1.0, "tool": "scalpel",
        "points": points, "open": {"width": 1.0, "window": 0.5}});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["closed"], true, "{v}");
    assert_eq!(v["manifold"], true, "{v}");
    assert!(v["triangles_created"].as_u64().unwrap() > 0);
}

#[test]
fn strokes_cross_and_loop_detaches() {
    let dir = scratch("strokes");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 20);
    let a: Vec<[f64; 3]> = (0..=20)
        .map(|i| [4.3 + 0.6 * i as f64, 10.5, 0.0])
        .collect();
    let b: Vec<[f64; 3]> = (0..=20)
        .map(|i| [10.1, 4.3 + 0.6 * i as f64, 0.0])
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "strokes": [a, b]});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 42);
    assert_eq!(v["manifold"], true);

    let circle: Vec<[f64; 3]> = (0..40)
        .map(|i| {
            let t = i as f64 / 40.0 * std::f64::consts::TAU;
            [10.2 + 4.0 * t.cos(), 9.7 + 4.0 * t.sin(), 0.0]
        })
        .collect();
    let json = serde_json::json!({"format": "cutaway-path/1", "tool": "loop", "points": circle});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["steps"], 40);
    assert_eq!(v["manifold"], true);
}

#[test]
fn bad_path_files_and_off_mesh_points_are_one_line_errors() {
    let dir = scratch("errors");
    let (target, path, out) = (
        dir.join("sheet.obj"),
        dir.join("p.json"),
        dir.join("out.obj"),
    );
    write_sheet(&target, 6);
    let run = || {
        cutaway()
            .arg("scalpel")
            .arg(&target)
            .arg("--path")
            .arg(&path)
            .arg("--out")
            .arg(&out)
            .arg("--json")
            .output()
            .unwrap()
    };
    std::fs::write(&path, r#"{"format":"cutaway-path/9","points":[[1,1,0]]}"#).unwrap();
    assert_one_error_line(&run(), &path, "cutaway-path/1");
    std::fs::write(&path, "not json").unwrap();
    assert_one_error_line(&run(), &path, "cutaway-path/1");
    std::fs::write(
        &path,
        r#"{"format":"cutaway-path/1","points":[[100,100,0],[1,1,0]]}"#,
    )
    .unwrap();
    assert_one_error_line(&run(), &path, "off the mesh");
    std::fs::write(
        &path,
        r#"{"format":"cutaway-path/1","points":[[1,1,0],[2,2,30]]}"#,
    )
    .unwrap();
    assert_one_error_line(&run(), &path, "off the mesh");
    assert!(!out.exists(), "nothing written on error");
}

/// A groove drawn across the knee's patella (millimetres, the anterior face) and opened 2 mm
/// wide: along the whole path, away from its ends, the opened surface has left the line the
/// blade drew (the two lips moved apart, the groove between them), and the mesh is closed. The
/// opening used to move both lips of a groove one way along most of such a path (the surface
/// stayed shut there) and tear it elsewhere.
#[test]
fn groove_on_the_patella_opens_along_its_whole_path() {
    let dir = scratch("patella");
    let target = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/knee/patella.ply");
    let (path, out) = (dir.join("p.json"), dir.join("out.ply"));
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    // Samples on the anterior face (-y): the front-most vertex near each (x, z) of a gentle arc.
    let points: Vec<[f64; 3]> = (0..=40)
        .map(|i| {
            let u = i as f64 / 40.0;
            let (x, z) = (-12.0 + 24.0 * u, 33.0 + 4.0 * (3.1 * u).sin());
            let front = mesh
                .positions
                .iter()
                .filter(|p| (p.x - x).abs() < 1.5 && (p.z - z).abs() < 1.5)
                .min_by(|a, b| a.y.total_cmp(&b.y))
                .unwrap();
            [x, front.y, z]
        })
        .collect();
    let width = 2.0;
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 3.0, "tool": "scalpel",
        "points": points, "open": {"width": width, "window": 0.5}});
    std::fs::write(&path, json.to_string()).unwrap();
    let v = run_json(&target, &path, &out);
    assert_eq!(v["closed"], true, "{v}");
    assert_eq!(v["manifold"], true, "{v}");
    let opened = cutaway::io::read_mesh(&out).unwrap();
    let (before, after) = (
        csg::SpatialIndex::build(&mesh),
        csg::SpatialIndex::build(&opened),
    );
    let on_surface: Vec<csg::DVec3> = points
        .iter()
        .map(|&p| before.closest_point(&mesh, p.into()).unwrap().point)
        .collect();
    let (first, last) = (on_surface[0], on_surface[on_surface.len() - 1]);
    // The lips follow mesh edges, which kink up to about half an edge (0.4 mm here) away from
    // the drawn line in places; there a lip passes closer to it. A shut groove passes at 0.
    let mut gaps = Vec::new();
    for &p in &on_surface {
        if p.distance(first) < 2.0 * width || p.distance(last) < 2.0 * width {
            continue;
        }
        gaps.push(after.closest_point(&opened, p).unwrap().point.distance(p));
    }
    assert!(gaps.len() >= 20, "{gaps:?}");
    let close = gaps.iter().filter(|&&g| g < 0.15 * width).count();
    assert!(
        6 * close <= gaps.len(),
        "the opened surface passes within 0.15 widths of the cut at {close} of {} points: {gaps:?}",
        gaps.len()
    );
    let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
    assert!(mean >= 0.2 * width, "mean gap {mean} mm: {gaps:?}");
}
