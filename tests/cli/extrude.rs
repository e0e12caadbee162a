//! End-to-end tests of `cutaway extrude`: recorded gestures (tests/data/gestures) replayed on
//! generated targets and on real anatomy, through the binary and through the library.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DVec2, DVec3};

use csg::Mesh;
use cutaway::cli::extrude::replay;
use cutaway::io::gesture::{CutSettings, Gesture, parse_gesture, read_gesture};
use cutter::{Camera, CutDirection, CutKind, EditorEvent, EditorSettings, Rules};

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
    // δ: the distance framing the sphere's bounding box with the gesture's 30° field of view, or
    // the gesture camera's distance from the sphere when that is farther, / 2000.
    let bbox = csg::testkit::icosphere(5, 50.0).bbox();
    let eye = read_gesture(&gestures().join("sphere_s.json"))
        .unwrap()
        .camera
        .eye;
    let expected =
        Camera::framing_distance(&bbox, 30.0).max((bbox.center() - eye).length()) / 2000.0;
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
            "{\"format\": \"cutaway-gesture/9\", \"viewport\": [10, 10], \"camera\": {\"eye\": [0,-3,0], \"target\": [0,0,0], \"up\": [0,0,1], \"fov_y_deg\": 30}, \"events\": []}",
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
    // Closer to the right sphere than the distance that frames it.
    let camera = Camera {
        eye: DVec3::new(40.0, -100.0, 0.0),
        target: DVec3::new(40.0, 0.0, 0.0),
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
        cut: CutSettings {
            direction: CutDirection::Normal,
            ..CutSettings::default()
        },
        events,
        rules: Rules::Delta,
    };
    let r = replay(&two, &gesture).unwrap();
    assert_eq!(r.region, 1);
    assert!(r.cutter.planes.iter().all(|p| p.front_mid().x > 15.0));
    // δ comes from the painted region (the sphere framed), not the whole file.
    let region = right.bbox();
    let framed = EditorSettings::delta_for_scene(&region, 30.0);
    assert!(
        (r.delta - framed).abs() < 1e-12 * framed,
        "{} vs {framed}",
        r.delta
    );
    let whole = EditorSettings::delta_for_scene(&two.bbox(), 30.0);
    assert!(r.delta < 0.6 * whole, "{} vs the file's {whole}", r.delta);
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

/// True when the view ray through pixel `px` hits `mesh`.
fn sees_surface(
    mesh: &Mesh,
    index: &csg::SpatialIndex,
    camera: &Camera,
    viewport: DVec2,
    px: DVec2,
) -> bool {
    let ray = camera.ray_through_pixel(viewport, px);
    index
        .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
        .is_some()
}

/// Pixels of the extrusion path of [`gesture_for`]: from the handle `h` along `dir` for `length`
/// pixels, with an S-shaped sideways wiggle.
fn s_path(h: DVec2, dir: DVec2, length: f64) -> Vec<DVec2> {
    let side = DVec2::new(-dir.y, dir.x);
    (1..=40)
        .map(|k| {
            let t = k as f64 / 40.0;
            h + dir * (length * t) + side * (10.0 * (t * 6.0).sin())
        })
        .collect()
}

/// A gesture framed on `mesh` that stays over the structure: an initial drag near the centre of
/// the view, then an S-shaped extrusion along the screen direction in which every pixel of the
/// path (with a margin on both sides) sees the surface, so the roller always has surface under
/// it (a narrow bone seen from the front is followed along its length, not off its edge).
fn gesture_for(mesh: &Mesh, kind: CutKind) -> Gesture {
    let bbox = mesh.bbox();
    let camera = Camera::framing(&bbox, DVec3::NEG_Y, DVec3::Z, 30.0);
    let viewport = DVec2::new(1280.0, 800.0);
    let index = csg::SpatialIndex::build(mesh);
    let regions = csg::regions::Regions::build(mesh, &csg::EdgeAdjacency::build(mesh));
    // The region the view ray through `px` meets first.
    let region_at = |px: DVec2| {
        let ray = camera.ray_through_pixel(viewport, px);
        index
            .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
            .map(|hit| regions.region_of_triangle[hit.face as usize])
    };
    let sees = |px: DVec2| region_at(px).is_some();
    // The press: where the view ray hits the structure nearest the centre.
    let mut a = DVec2::new(640.0, 440.0);
    'search: for r in 0..20 {
        for k in 0..16 {
            let ang = k as f64 * std::f64::consts::TAU / 16.0;
            let px =
                DVec2::new(640.0, 420.0) + DVec2::new(ang.cos(), ang.sin()) * (r as f64 * 10.0);
            if sees(px) {
                a = px;
                break 'search;
            }
        }
    }
    // The path direction and length: the longest path (of a few) that stays over the surface.
    let mut best: Option<(DVec2, f64)> = None;
    for length in [90.0, 70.0, 50.0, 35.0] {
        for k in 0..16 {
            let ang = k as f64 * std::f64::consts::TAU / 16.0;
            let dir = DVec2::new(ang.cos(), ang.sin());
            let side = DVec2::new(-dir.y, dir.x);
            let s = DVec2::new(dir.y, -dir.x) * 30.0;
            let h = a + s * 0.5 + dir * 4.0;
            // Over the painted region (the one under the press) all along.
            let painted = region_at(a);
            let all = std::iter::once(a + s * 0.5)
                .chain(s_path(h, dir, length))
                .all(|p| {
                    [-6.0, 0.0, 6.0]
                        .iter()
                        .all(|&o| region_at(p + side * o) == painted)
                });
            if all {
                best = Some((dir, length));
                break;
            }
        }
        if best.is_some() {
            break;
        }
    }
    let (dir, length) = best.unwrap_or((DVec2::X, 35.0));
    // A→B so that the strip (built to the screen-right of A→B) extends along `dir`.
    let b = a + DVec2::new(dir.y, -dir.x) * 30.0;
    let mut events = vec![
        EditorEvent::press(a.x, a.y),
        EditorEvent::move_to(b.x, b.y),
        EditorEvent::release(b.x, b.y),
    ];
    // Press on the handle (the middle of the leading plane, a few pixels along the path).
    let h = (a + b) * 0.5 + dir * 4.0;
    events.push(EditorEvent::press(h.x, h.y));
    let path = s_path(h, dir, length);
    for p in &path {
        events.push(EditorEvent::move_to(p.x, p.y));
    }
    let end = path[path.len() - 1];
    events.push(EditorEvent::release(end.x, end.y));
    events.push(EditorEvent::wheel(5.0, 5.0, 3.0, false));
    Gesture {
        viewport,
        camera,
        cut: CutSettings {
            kind,
            spacing: 20.0,
            smooth: false,
            direction: CutDirection::Normal,
        },
        events,
        rules: Rules::Delta,
    }
}

#[test]
fn gestures_on_real_anatomy() {
    let Some(dir) = anatomy() else {
        return skip(Resource::Data, "no anatomy folder (set CUTAWAY_ANATOMY)");
    };
    // (file, kind, largest front-face gap allowed over the surface in δ: the contract's surface-gap goal is 3δ).
    for (file, kind, bound) in [
        (
            "knee_vhf_left_denver/VHF_Left_Bone_Tibia_smooth.stl",
            CutKind::Curving,
            3.0,
        ),
        (
            "knee_vhf_left_denver/VHF_Left_Bone_Patella_smooth.stl",
            CutKind::Wedge,
            f64::INFINITY,
        ),
        (
            "spine_lumbar_vhm_remus/lumbar_spine_L1-S1_with_discs.obj",
            CutKind::Curving,
            3.0,
        ),
    ] {
        let path = dir.join(file);
        if !path.exists() {
            skip(Resource::Data, format!("{}: not present", path.display()));
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
        // The front faces stick to the surface (within 3δ, see `bound`) wherever the surface is
        // under the path. A box's front face AE''H''D rests on the surface (thesis 3.3.2.1: it is
        // turned about DA until it touches, then lifted 2δ), so its distance to the painted
        // region's surface, the closest of a grid of points on it, is the gap. "Under the path":
        // the camera sees the region through the face's centre. The path was chosen over the
        // structure, so most boxes are checked. Wedge planes share their top on the axis: no
        // roller there (unbounded).
        if bound.is_finite() {
            let region = csg::regions::split_regions(&mesh).swap_remove(r.region);
            let index = csg::SpatialIndex::build(&region);
            let planes = &r.cutter.planes;
            let mut checked = 0;
            let mut worst = 0.0f64;
            // The last box is the one being painted when the button was released: it may be
            // thinner than one rotation step, and such a box is not turned (extrude.rs).
            for i in 1..planes.len() - 1 {
                let face = [
                    planes[i - 1].front_top,
                    planes[i].front_top,
                    planes[i].front_bottom,
                    planes[i - 1].front_bottom,
                ];
                let centre = face.iter().copied().sum::<DVec3>() / 4.0;
                let Some(px) = gesture.camera.project(gesture.viewport, centre) else {
                    continue;
                };
                if !sees_surface(&region, &index, &gesture.camera, gesture.viewport, px) {
                    continue;
                }
                let mut gap = f64::INFINITY;
                for u in 0..=4 {
                    for v in 0..=4 {
                        let (u, v) = (u as f64 / 4.0, v as f64 / 4.0);
                        let p = face[0].lerp(face[1], u).lerp(face[3].lerp(face[2], u), v);
                        gap = gap.min(index.closest_point(&region, p).unwrap().distance);
                    }
                }
                worst = worst.max(gap / r.delta);
                assert!(
                    gap <= bound * r.delta,
                    "{file}: box {i}'s front face is {:.2}δ from the surface",
                    gap / r.delta
                );
                checked += 1;
            }
            assert!(
                checked >= 2 && checked * 4 >= (planes.len() - 2) * 3,
                "{file}: only {checked} of {} boxes over the surface",
                planes.len() - 2
            );
            eprintln!(
                "{file}: largest front-face gap over the surface {worst:.2}δ ({checked} boxes)"
            );
        }
        // Through the CLI too (writes the OBJ).
        let scratch = scratch("anatomy");
        let g = scratch.join("g.json");
        cutaway::io::gesture::write_gesture(&g, &gesture).unwrap();
        let run = run_cli(&path, &g, &scratch);
        check_contract(&run, kind.name());
    }
}

#[test]
fn every_contract_field_is_present_and_means_what_the_contract_says() {
    // CONTRACT.md: `{"planes":N,"boxes":N,"kind":"…","closed":bool,"max_surface_gap":f,
    // "delta":f}`, `max_surface_gap` the largest distance from a plane's front edge midpoint
    // to the target surface, `delta` the camera distance / 2000, CUTTER.obj the closed cutter
    // as quads. Each field is recomputed here independently of the code that wrote it.
    let dir = scratch("contract");
    let target = sphere_obj(&dir);
    let file = gestures().join("sphere_s.json");
    let run = run_cli(&target, &file, &dir);
    let j = run.json.as_object().expect("a JSON object");
    for key in [
        "planes",
        "boxes",
        "kind",
        "closed",
        "max_surface_gap",
        "delta",
    ] {
        assert!(j.contains_key(key), "missing {key}: {j:?}");
    }
    let mesh = cutaway::io::read_mesh(&target).unwrap();
    let gesture = read_gesture(&file).unwrap();
    let r = replay(&mesh, &gesture).unwrap();
    // planes / boxes / kind: the replayed cutter's.
    assert_eq!(j["planes"].as_u64(), Some(r.cutter.planes.len() as u64));
    assert_eq!(j["boxes"].as_u64(), Some(r.cutter.planes.len() as u64 - 1));
    assert_eq!(j["kind"].as_str(), Some(gesture.cut.kind.name()));
    // closed: in the written OBJ every edge is shared by exactly two faces, used once in each
    // direction (closed and consistently oriented).
    let faces: Vec<Vec<usize>> = run
        .obj
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| {
            l.split_whitespace()
                .skip(1)
                .map(|t| t.parse().unwrap())
                .collect()
        })
        .collect();
    assert!(faces.iter().all(|f| f.len() == 4), "quads only");
    let mut directed = std::collections::HashMap::new();
    for f in &faces {
        for k in 0..f.len() {
            *directed.entry((f[k], f[(k + 1) % f.len()])).or_insert(0) += 1;
        }
    }
    let closed = directed
        .iter()
        .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1));
    assert!(closed);
    assert_eq!(j["closed"].as_bool(), Some(closed));
    // max_surface_gap: brute force over every target triangle.
    let brute = r
        .cutter
        .planes
        .iter()
        .map(|p| {
            let m = p.front_mid();
            (0..mesh.triangle_count())
                .map(|t| {
                    let [a, b, c] = mesh.corners(t);
                    (csg::spatial::closest_on_triangle(m, a, b, c).0 - m).length()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let gap = j["max_surface_gap"].as_f64().unwrap();
    assert!(
        (gap - brute).abs() <= 1e-9 * (1.0 + brute),
        "{gap} vs {brute}"
    );
    assert!(gap > 0.0, "front edges rest above the surface");
    // delta: the framing camera distance of the target's bounding box / 2000 (the gesture's
    // camera frames it, so it is not farther).
    let delta = j["delta"].as_f64().unwrap();
    let expected = Camera::framing_distance(&mesh.bbox(), gesture.camera.fov_y_deg) / 2000.0;
    assert!(
        (delta - expected).abs() <= 1e-12 * expected,
        "{delta} vs {expected}"
    );
    assert!(gap <= 3.0 * delta);
}

/// A replay is bounded: a viewport no window has is refused when the gesture is parsed, and a
/// drag that would build boxes by the hundred (here a spacing 40 times finer than the recorded
/// one) stops with an error once the cutter passes the box limit, instead of running for minutes.
#[test]
fn runaway_gestures_stop_with_an_error() {
    let text = std::fs::read_to_string(gestures().join("sphere_s.json")).unwrap();
    let recorded: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut tiny = recorded.clone();
    tiny["viewport"] = serde_json::json!([1, 2]);
    let e = format!("{:#}", parse_gesture(&tiny.to_string()).unwrap_err());
    assert!(e.contains("viewport [1, 2]"), "{e}");

    let mut fine = recorded;
    fine["cut"]["spacing"] = serde_json::json!(0.5);
    let gesture = parse_gesture(&fine.to_string()).unwrap();
    let sphere = csg::testkit::icosphere(5, 50.0);
    let e = format!("{:#}", replay(&sphere, &gesture).unwrap_err());
    let limit = cutaway::io::gesture::MAX_REPLAY_BOXES;
    assert!(
        e.contains(&format!("more than the limit of {limit}")),
        "{e}"
    );
}

/// The box cap alone does not bound a replay: thousands of moves in the smallest viewport a
/// gesture may have each re-fit a cutter of dozens of boxes while staying under the cap. The
/// replay stops with an error at the CPU-time limit instead of running for tens of seconds.
#[test]
fn thousands_of_moves_in_a_tiny_viewport_stop_at_the_time_limit() {
    let event = |kind: &str, x: f64, y: f64| serde_json::json!({"type": kind, "x": x, "y": y});
    let mut events = vec![
        event("press", 8.0, 10.0),
        event("move", 8.0, 8.0),
        event("release", 8.0, 5.0),
        event("press", 8.0, 5.0),
    ];
    for i in 0..9990 {
        let i = i as f64;
        events.push(event(
            "move",
            8.0 + 7.0 * (i * 0.05).sin(),
            8.0 + 7.0 * (i * 0.031).cos(),
        ));
    }
    let gesture = serde_json::json!({
        "format": "cutaway-gesture/1",
        "viewport": [16, 16],
        "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
        "cut": {"kind": "curving", "spacing": 20, "smooth": false},
        "events": events,
    });
    let gesture = parse_gesture(&gesture.to_string()).unwrap();
    let sphere = csg::testkit::icosphere(5, 50.0);
    let e = format!("{:#}", replay(&sphere, &gesture).unwrap_err());
    assert!(
        e.contains("the replay used more than 1.5 s of CPU time"),
        "{e}"
    );
}
