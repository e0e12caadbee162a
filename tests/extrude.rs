//! End-to-end tests of `cutaway extrude`: recorded gestures (tests/data/gestures) replayed on
//! generated targets and on real anatomy, through the binary and through the library.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DVec2, DVec3};

use csg::Mesh;
use cutaway::cli::extrude::replay;
use cutaway::gesture::{CutSettings, Gesture, parse_gesture, read_gesture};
use cutter::{Camera, CutKind, EditorEvent, EditorSettings};

fn gestures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/gestures")
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-extrude-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// The radius-50 sphere the gesture fixtures were recorded on, written as OBJ.
fn sphere_obj(dir: &Path) -> PathBuf {
    let path = dir.join("sphere.obj");
    cutaway::io::write_mesh(&path, &csg::testkit::icosphere(5, 50.0)).expect("write sphere");
    path
}

struct Run {
    json: serde_json::Value,
    obj: String,
}

fn run_cli(target: &Path, gesture: &Path, dir: &Path) -> Run {
    let out = dir.join("cutter.obj");
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("extrude")
        .arg(target)
        .arg("--gesture")
        .arg(gesture)
        .arg("--out")
        .arg(&out)
        .arg("--json")
        .output()
        .expect("run cutaway");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "cutaway extrude failed: {stderr}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let json: serde_json::Value = serde_json::from_str(stdout.trim()).expect("one JSON object");
    let obj = std::fs::read_to_string(&out).expect("cutter written");
    Run { json, obj }
}

/// Checks the contract's JSON fields and the OBJ, returns (planes, delta).
fn check_contract(run: &Run, kind: &str) -> (u64, f64) {
    let j = &run.json;
    let planes = j["planes"].as_u64().expect("planes");
    let boxes = j["boxes"].as_u64().expect("boxes");
    assert_eq!(boxes + 1, planes);
    assert_eq!(j["kind"], kind);
    assert_eq!(j["closed"], true);
    let delta = j["delta"].as_f64().expect("delta");
    let gap = j["max_surface_gap"].as_f64().expect("max_surface_gap");
    assert!(delta > 0.0 && gap >= 0.0);
    // Quads (and the wedge's triangles), 1-based indices in range.
    let vertices = run.obj.lines().filter(|l| l.starts_with("v ")).count();
    let faces: Vec<Vec<usize>> = run
        .obj
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| {
            l.split_whitespace()
                .skip(1)
                .map(|t| t.parse().expect("index"))
                .collect()
        })
        .collect();
    assert!(!faces.is_empty());
    for f in &faces {
        assert!(
            f.len() == 4 || (kind == "wedge" && f.len() == 3),
            "face {f:?}"
        );
        assert!(f.iter().all(|&i| i >= 1 && i <= vertices));
    }
    if kind != "wedge" && j["smooth"] != true {
        assert_eq!(faces.len() as u64, 4 * boxes + 2);
    }
    (planes, delta)
}

#[test]
fn s_path_on_sphere_through_the_cli() {
    let dir = scratch("s");
    let target = sphere_obj(&dir);
    let run = run_cli(&target, &gestures().join("sphere_s.json"), &dir);
    let (planes, delta) = check_contract(&run, "curving");
    assert!(planes >= 8, "{planes} planes");
    // δ: the distance framing the sphere's bounding box with the gesture's 30° field of view / 2000.
    let bbox = csg::testkit::icosphere(5, 50.0).bbox();
    let expected = Camera::framing_distance(&bbox, 30.0) / 2000.0;
    assert!(
        (delta - expected).abs() < 1e-12 * expected,
        "{delta} vs {expected}"
    );
    let gap = run.json["max_surface_gap"].as_f64().unwrap();
    assert!(gap <= 3.0 * delta, "max_surface_gap {gap} > 3δ ({delta})");
}

#[test]
fn cli_and_library_replay_agree() {
    let dir = scratch("agree");
    let target = sphere_obj(&dir);
    let file = gestures().join("sphere_edits.json");
    let run = run_cli(&target, &file, &dir);
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let gesture = read_gesture(&file).unwrap();
    let r = replay(&mesh, &gesture).unwrap();
    r.cutter.sanity_check().unwrap();
    assert_eq!(
        run.json["planes"].as_u64().unwrap() as usize,
        r.cutter.planes.len()
    );
    assert!((run.json["max_surface_gap"].as_f64().unwrap() - r.max_surface_gap).abs() < 1e-12);
    // The edits happened: deeper than the initial 5δ.
    assert!(r.cutter.planes[0].depth() > 10.0 * r.delta);
}

#[test]
fn wedge_rounded_and_straight_fixtures() {
    let dir = scratch("kinds");
    let target = sphere_obj(&dir);
    let wedge = run_cli(&target, &gestures().join("sphere_wedge.json"), &dir);
    let (planes, _) = check_contract(&wedge, "wedge");
    assert!(planes >= 3, "wedge extruded: {planes} planes");
    let rounded = run_cli(&target, &gestures().join("sphere_rounded.json"), &dir);
    check_contract(&rounded, "curving");
    assert_eq!(rounded.json["smooth"], true);
    let straight = run_cli(&target, &gestures().join("sphere_straight.json"), &dir);
    check_contract(&straight, "curving");
    // Straight: the library replay's path midpoints lie in one plane through the sphere's
    // centre (a great circle: straight on the sphere).
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let r = replay(
        &mesh,
        &read_gesture(&gestures().join("sphere_straight.json")).unwrap(),
    )
    .unwrap();
    let path = r.cutter.path();
    let n = (path[1] - path[0])
        .cross(path[path.len() - 1] - path[0])
        .normalize();
    for p in &path {
        assert!(
            ((*p - path[0]).dot(n)).abs() < 0.5 * r.delta,
            "{p} off the path plane"
        );
    }
}

#[test]
fn bad_gesture_files_fail_with_one_line_naming_the_file() {
    let dir = scratch("bad");
    let target = sphere_obj(&dir);
    let cases = [
        ("broken.json", "{\"format\": "),
        (
            "wrong_format.json",
            "{\"format\": \"cutaway-gesture/2\", \"viewport\": [10, 10], \"camera\": {\"eye\": [0,-3,0], \"target\": [0,0,0], \"up\": [0,0,1], \"fov_y_deg\": 30}, \"events\": []}",
        ),
        (
            "no_cutter.json",
            "{\"format\": \"cutaway-gesture/1\", \"viewport\": [1280, 800], \"camera\": {\"eye\": [0,-300,0], \"target\": [0,0,0], \"up\": [0,0,1], \"fov_y_deg\": 30}, \"events\": [{\"type\": \"press\", \"x\": 1, \"y\": 1}]}",
        ),
    ];
    for (name, text) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
            .args(["extrude"])
            .arg(&target)
            .arg("--gesture")
            .arg(&path)
            .arg("--out")
            .arg(dir.join("x.obj"))
            .arg("--json")
            .output()
            .unwrap();
        assert!(!output.status.success(), "{name} must fail");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.starts_with("error: "), "{name}: {stderr}");
        assert!(
            stderr.contains(name),
            "{name}: error must name the file: {stderr}"
        );
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{name}: one line: {stderr}"
        );
        assert!(!stderr.contains("panicked"));
    }
}

#[test]
fn the_region_under_the_press_is_painted() {
    // Two spheres side by side in one file; press on the right one.
    let mut two = csg::testkit::icosphere(4, 20.0);
    for p in &mut two.positions {
        p.x -= 40.0;
    }
    let mut right = csg::testkit::icosphere(4, 20.0);
    for p in &mut right.positions {
        p.x += 40.0;
    }
    two.append(&right);
    let camera = Camera {
        eye: DVec3::new(0.0, -300.0, 0.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 30.0,
    };
    let viewport = DVec2::new(1280.0, 800.0);
    let centre = camera
        .project(viewport, DVec3::new(40.0, -20.0, 0.0))
        .unwrap();
    let mut events = vec![EditorEvent::press(centre.x, centre.y + 25.0)];
    events.push(EditorEvent::move_to(centre.x, centre.y - 25.0));
    events.push(EditorEvent::release(centre.x, centre.y - 25.0));
    let gesture = Gesture {
        viewport,
        camera,
        cut: CutSettings::default(),
        events,
    };
    let r = replay(&two, &gesture).unwrap();
    assert_eq!(r.region, 1);
    assert!(r.cutter.planes.iter().all(|p| p.front_mid().x > 15.0));
    // δ comes from the whole file, not the region.
    let whole = EditorSettings::delta_for_scene(&two.bbox(), 30.0);
    assert_eq!(r.delta, whole);
    // And the library parse of the contract example works (same parser as the CLI).
    assert!(
        parse_gesture(&std::fs::read_to_string(gestures().join("sphere_s.json")).unwrap()).is_ok()
    );
    assert_eq!(gesture.cut.kind, CutKind::Curving);
}

/// The anatomy folder: `CUTAWAY_ANATOMY`, else `../shared/anatomy` beside the workspace.
fn anatomy() -> Option<PathBuf> {
    if let Ok(dir) = std::env::var("CUTAWAY_ANATOMY") {
        let p = PathBuf::from(dir);
        return p.is_dir().then_some(p);
    }
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy");
    p.is_dir().then_some(p)
}

/// A gesture framed on `mesh`: a vertical drag at the centre of the view, then a rightward S.
fn gesture_for(mesh: &Mesh, kind: CutKind) -> Gesture {
    let bbox = mesh.bbox();
    let camera = Camera::framing(&bbox, DVec3::NEG_Y, DVec3::Z, 30.0);
    let viewport = DVec2::new(1280.0, 800.0);
    // Press where the view ray hits the bone nearest the centre.
    let index = csg::SpatialIndex::build(mesh);
    let mut a = DVec2::new(640.0, 440.0);
    'search: for r in 0..20 {
        for k in 0..16 {
            let ang = k as f64 * std::f64::consts::TAU / 16.0;
            let px =
                DVec2::new(640.0, 420.0) + DVec2::new(ang.cos(), ang.sin()) * (r as f64 * 10.0);
            let ray = camera.ray_through_pixel(viewport, px);
            if index
                .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
                .is_some()
            {
                a = px;
                break 'search;
            }
        }
    }
    let b = a - DVec2::new(0.0, 30.0);
    let mut events = vec![
        EditorEvent::press(a.x, a.y),
        EditorEvent::move_to(b.x, b.y),
        EditorEvent::release(b.x, b.y),
    ];
    // Press on the handle (roughly the middle of the leading plane, a few px right of the drag).
    let h = (a + b) * 0.5 + DVec2::new(4.0, 0.0);
    events.push(EditorEvent::press(h.x, h.y));
    for k in 1..=40 {
        let t = k as f64 / 40.0;
        events.push(EditorEvent::move_to(
            h.x + 60.0 * t,
            h.y - 10.0 * (t * 6.0).sin(),
        ));
    }
    events.push(EditorEvent::release(h.x + 60.0, h.y));
    events.push(EditorEvent::wheel(5.0, 5.0, 3.0, false));
    Gesture {
        viewport,
        camera,
        cut: CutSettings {
            kind,
            spacing: 20.0,
            smooth: false,
        },
        events,
    }
}

#[test]
fn gestures_on_real_anatomy() {
    let Some(dir) = anatomy() else {
        eprintln!("skipped: no anatomy folder (set CUTAWAY_ANATOMY)");
        return;
    };
    for (file, kind) in [
        (
            "knee_vhf_left_denver/VHF_Left_Bone_Tibia_smooth.stl",
            CutKind::Curving,
        ),
        (
            "knee_vhf_left_denver/VHF_Left_Bone_Patella_smooth.stl",
            CutKind::Wedge,
        ),
        (
            "spine_lumbar_vhm_remus/lumbar_spine_L1-S1_with_discs.obj",
            CutKind::Curving,
        ),
    ] {
        let path = dir.join(file);
        if !path.exists() {
            eprintln!("skipped {file}: not present");
            continue;
        }
        let mesh = cutaway::io::read_mesh(&path).expect("anatomy loads");
        let gesture = gesture_for(&mesh, kind);
        let r = replay(&mesh, &gesture).unwrap_or_else(|e| panic!("{file}: {e:#}"));
        r.cutter
            .sanity_check()
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let q = r.cutter.quad_mesh();
        q.check_closed().unwrap();
        assert!(q.volume() > 0.0);
        eprintln!(
            "{file}: {} planes, max gap {:.2}δ, region {}",
            r.cutter.planes.len(),
            r.max_surface_gap / r.delta,
            r.region
        );
        assert!(r.cutter.planes.len() >= 3, "{file}: the roller moved");
        // Through the CLI too (writes the OBJ).
        let scratch = scratch("anatomy");
        let g = scratch.join("g.json");
        cutaway::gesture::write_gesture(&g, &gesture).unwrap();
        let run = run_cli(&path, &g, &scratch);
        check_contract(&run, kind.name());
    }
}
