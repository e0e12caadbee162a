//! Rounded and freeform (smooth) cutters end to end: every recorded gesture in
//! `tests/data/gestures`, as recorded and as a smooth variant, replayed by the editor and cut out
//! of the sphere it was recorded on by the exact boolean, through the library (whole cut contract
//! checked by `csg::cutcheck`) and through `cutaway extrude` + `cutaway subtract`; and
//! `cutaway render --json` of a session with a smooth cutter, which must report an exact cut.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::process::Command;

use csg::{Mesh, TargetIndex};
use cutaway::cli::extrude::replay;
use cutaway::io::gesture::{read_gesture, write_gesture};

fn gestures() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/gestures");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("gesture folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    files
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-smooth-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// The radius-50 sphere the gestures were recorded on.
fn sphere() -> Mesh {
    csg::testkit::icosphere(5, 50.0)
}

fn cutaway(args: &[&std::ffi::OsStr]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(args)
        .output()
        .expect("run cutaway");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Writes `session` as `DIR/NAME.json`, renders it at 64×48 with `--json`, checks that the image
/// was written and returns the JSON; `None`, with the reason printed, when no GPU adapter exists.
fn render_json(dir: &Path, name: &str, session: &serde_json::Value) -> Option<serde_json::Value> {
    let session_path = dir.join(format!("{name}.json"));
    std::fs::write(&session_path, session.to_string()).unwrap();
    let png = dir.join(format!("{name}.png"));
    let (ok, out, err) = cutaway(&[
        "render".as_ref(),
        session_path.as_os_str(),
        "--out".as_ref(),
        png.as_os_str(),
        "--width".as_ref(),
        "64".as_ref(),
        "--height".as_ref(),
        "48".as_ref(),
        "--json".as_ref(),
    ]);
    if !ok && err.contains("adapter") {
        skip(Resource::Gpu, format!("no GPU adapter ({err})"));
        return None;
    }
    assert!(ok, "{name}: render failed: {err}");
    assert!(png.exists(), "{name}");
    Some(serde_json::from_str(out.trim()).expect("render JSON"))
}

fn read_obj(path: &Path) -> Mesh {
    cutaway::io::read_mesh(path).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()))
}

#[test]
fn every_gesture_plain_and_smooth_is_cut_exactly() {
    let target = sphere();
    let index = TargetIndex::build(target.clone()).expect("index");
    let mut smooth_cuts = 0;
    for file in gestures() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        for smooth in [false, true] {
            let mut gesture = read_gesture(&file).expect("gesture");
            gesture.cut.smooth = smooth;
            let r = replay(&target, &gesture).unwrap_or_else(|e| panic!("{name}: {e:#}"));
            assert_eq!(r.cutter.smooth, smooth);
            r.cutter
                .validate()
                .unwrap_or_else(|e| panic!("{name} smooth={smooth}: {e}"));
            let surface = r.cutter.surface();
            if smooth {
                // Subdivided (at least one level applied), not the boxes.
                let boxes = r.cutter.quad_mesh().triangulate();
                assert!(
                    surface.triangle_count() >= 4 * boxes.triangle_count(),
                    "{name}: smoothing gave up"
                );
                smooth_cuts += 1;
            }
            let result = csg::subtract(&index, &surface)
                .unwrap_or_else(|e| panic!("{name} smooth={smooth}: refused: {e}"));
            csg::cutcheck::check_measures(&target, &result)
                .unwrap_or_else(|e| panic!("{name} smooth={smooth}: {e}"));
            assert!(
                !result.walls.mesh.is_empty(),
                "{name} smooth={smooth}: the cutter missed the sphere"
            );
            let mut closed = result.materialize(&target);
            closed.append(&result.walls.mesh);
            let report = csg::weld::weld_exact(&closed).compacted().report();
            assert!(
                report.closed && report.manifold,
                "{name} smooth={smooth}: kept + walls {report:?}"
            );
        }
    }
    assert!(smooth_cuts >= 7);
}

#[test]
fn smooth_gestures_through_extrude_and_subtract() {
    let dir = scratch("cli");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &sphere()).expect("write sphere");
    let target_volume = sphere().volume();
    for file in gestures() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let mut gesture = read_gesture(&file).expect("gesture");
        gesture.cut.smooth = true;
        let smooth_gesture = dir.join(format!("{name}_smooth.json"));
        write_gesture(&smooth_gesture, &gesture).expect("write gesture");
        let cutter = dir.join(format!("{name}_cutter.obj"));
        let (ok, out, err) = cutaway(&[
            "extrude".as_ref(),
            target.as_os_str(),
            "--gesture".as_ref(),
            smooth_gesture.as_os_str(),
            "--out".as_ref(),
            cutter.as_os_str(),
            "--json".as_ref(),
        ]);
        assert!(ok, "{name}: extrude failed: {err}");
        let json: serde_json::Value = serde_json::from_str(out.trim()).expect("extrude JSON");
        assert_eq!(json["smooth"], true);
        assert_eq!(json["closed"], true);
        let parts = dir.join(format!("{name}_parts"));
        let (ok, out, err) = cutaway(&[
            "subtract".as_ref(),
            target.as_os_str(),
            cutter.as_os_str(),
            "--out".as_ref(),
            parts.as_os_str(),
            "--json".as_ref(),
        ]);
        assert!(ok, "{name}: subtract refused the smooth cutter: {err}");
        let json: serde_json::Value = serde_json::from_str(out.trim()).expect("subtract JSON");
        assert!(
            json["walls_triangles"].as_u64().unwrap() > 0,
            "{name}: {json}"
        );
        // kept + walls and removed + reversed walls close the sphere's volume between them.
        let kept = read_obj(&parts.join("kept.obj"));
        let walls = read_obj(&parts.join("walls.obj"));
        let removed = read_obj(&parts.join("removed.obj"));
        let mut outside = kept;
        outside.append(&walls);
        let mut inside = removed;
        inside.append(&walls.reversed());
        for (what, m) in [("kept + walls", &outside), ("removed + walls", &inside)] {
            let report = csg::weld::weld_exact(m).compacted().report();
            assert!(report.closed, "{name}: {what} is not closed: {report:?}");
        }
        let sum = outside.volume() + inside.volume();
        assert!(
            (sum - target_volume).abs() < 1e-6 * target_volume,
            "{name}: volumes {sum} vs {target_volume}"
        );
        assert!(inside.volume() > 0.0);
    }
}

#[test]
fn render_json_reports_the_smooth_cut_exact() {
    let dir = scratch("render");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &sphere()).expect("write sphere");
    let gesture = gestures()
        .into_iter()
        .find(|p| p.ends_with("sphere_tight_turns.json"))
        .expect("tight-turns gesture");
    let r = replay(&sphere(), &read_gesture(&gesture).unwrap()).unwrap();
    assert!(r.cutter.smooth);
    let planes: Vec<serde_json::Value> = r
        .cutter
        .planes
        .iter()
        .map(|p| serde_json::json!(p.corners().map(|c| c.to_array())))
        .collect();
    let session = serde_json::json!({
        "format": "cutaway-session/1",
        "models": [{"path": "sphere.obj", "color": [0.9, 0.7, 0.6]}],
        "cutters": [{"target": 0, "kind": "curving", "smooth": true, "planes": planes,
                     "views": {"cut": true, "ribbons": {"count": 3, "width": 0.4, "relative": true}}}],
        "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30}
    });
    let Some(json) = render_json(&dir, "session", &session) else {
        return;
    };
    let keys: Vec<&String> = json.as_object().unwrap().keys().collect();
    assert_eq!(keys, ["cutters", "render_ms"]);
    let cutters = json["cutters"].as_array().unwrap();
    assert_eq!(cutters.len(), 1);
    assert_eq!(cutters[0]["exact"], true, "{json}");
    assert!(cutters[0]["cut_ms"].as_f64().unwrap() > 0.0);
    assert!(json["render_ms"].as_f64().unwrap() > 0.0);

    // A cutter the boolean refuses (its boxes fold over each other): no image, a non-zero exit
    // naming the session, and the report says it was not exact.
    let mut folded = session.clone();
    let mut bad = r.cutter.clone();
    let last = bad.planes.len() - 1;
    bad.planes[1] = bad.planes[last];
    folded["cutters"][0]["planes"] = serde_json::json!(
        bad.planes
            .iter()
            .map(|p| serde_json::json!(p.corners().map(|c| c.to_array())))
            .collect::<Vec<_>>()
    );
    let folded_path = dir.join("folded.json");
    std::fs::write(&folded_path, folded.to_string()).unwrap();
    let png2 = dir.join("folded.png");
    let (ok, out, err) = cutaway(&[
        "render".as_ref(),
        folded_path.as_os_str(),
        "--out".as_ref(),
        png2.as_os_str(),
        "--width".as_ref(),
        "64".as_ref(),
        "--height".as_ref(),
        "48".as_ref(),
        "--json".as_ref(),
    ]);
    assert!(!ok, "a refused cut must fail");
    // (The Vulkan loader may add its own lines about the environment; ours is one line.)
    let ours: Vec<&str> = err
        .lines()
        .filter(|l| !l.contains("XDG_RUNTIME_DIR"))
        .collect();
    assert_eq!(ours.len(), 1, "{err}");
    assert!(
        ours[0].starts_with("error: ")
            && ours[0].contains("folded.json")
            && ours[0].contains("cannot cut"),
        "{err}"
    );
    let json: serde_json::Value = serde_json::from_str(out.trim()).expect("render JSON");
    assert_eq!(json["cutters"][0]["exact"], false);
    assert!(!png2.exists());
}

#[test]
fn extrude_levels_option_sets_the_subdivision() {
    let dir = scratch("levels");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &sphere()).expect("write sphere");
    let gesture = gestures()
        .into_iter()
        .find(|p| p.ends_with("sphere_rounded.json"))
        .expect("rounded gesture");
    let mut faces = Vec::new();
    for levels in ["0", "1", "3"] {
        let out = dir.join(format!("cutter{levels}.obj"));
        let (ok, stdout, err) = cutaway(&[
            "extrude".as_ref(),
            target.as_os_str(),
            "--gesture".as_ref(),
            gesture.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--levels".as_ref(),
            levels.as_ref(),
            "--json".as_ref(),
        ]);
        assert!(ok, "--levels {levels}: {err}");
        let json: serde_json::Value = serde_json::from_str(stdout.trim()).expect("extrude JSON");
        assert_eq!(json["levels"].to_string(), levels, "{json}");
        assert_eq!(json["closed"], true);
        let cutter = read_obj(&out);
        csg::check_cutter(&cutter).unwrap_or_else(|e| panic!("--levels {levels}: {e}"));
        // The written cutter is the adaptive surface: as many faces as the JSON says, at most
        // those of the uniform subdivision.
        let written = json["faces"].as_u64().unwrap() as usize;
        let uniform = json["uniform_faces"].as_u64().unwrap() as usize;
        assert!(
            cutter.triangle_count() >= written && written <= uniform,
            "{json}"
        );
        faces.push(uniform);
    }
    // Each level splits every quad in four (uniformly; adaptive subdivision then joins the
    // rings of straight runs).
    assert_eq!(faces[1], 4 * faces[0], "{faces:?}");
    assert_eq!(faces[2], 16 * faces[1], "{faces:?}");

    let out = dir.join("too_many.obj");
    let (ok, _, err) = cutaway(&[
        "extrude".as_ref(),
        target.as_os_str(),
        "--gesture".as_ref(),
        gesture.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--levels".as_ref(),
        "9".as_ref(),
    ]);
    assert!(!ok);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("--levels 9"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn render_json_reports_every_smooth_gesture_exact() {
    let dir = scratch("render-all");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &sphere()).expect("write sphere");
    for file in gestures() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let mut gesture = read_gesture(&file).expect("gesture");
        gesture.cut.smooth = true;
        let r = replay(&sphere(), &gesture).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let planes: Vec<serde_json::Value> = r
            .cutter
            .planes
            .iter()
            .map(|p| serde_json::json!(p.corners().map(|c| c.to_array())))
            .collect();
        let session = serde_json::json!({
            "format": "cutaway-session/1",
            "models": [{"path": "sphere.obj", "color": [0.9, 0.7, 0.6]}],
            "cutters": [{"target": 0, "kind": r.cutter.kind.name(), "smooth": true,
                         "planes": planes, "views": {"cut": true}}],
            "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30}
        });
        let Some(json) = render_json(&dir, &name, &session) else {
            return;
        };
        assert_eq!(json["cutters"][0]["exact"], true, "{name}: {json}");
        assert!(
            json["cutters"][0]["cut_ms"].as_f64().unwrap() > 0.0,
            "{name}"
        );
    }
}

/// Adaptive subdivision: for every gesture's smooth cutter at 2 and 3 levels, the cutter's surface
/// has fewer triangles than the uniform subdivision at the same level, stays a valid closed
/// cutter, and every point of the uniform surface is within the adaptive tolerance of it. Prints
/// the triangle counts and the deviation per gesture.
#[test]
fn adaptive_subdivision_keeps_the_uniform_surface_with_fewer_triangles() {
    let target = sphere();
    let (mut uniform_total, mut adaptive_total) = (0usize, 0usize);
    for file in gestures() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let mut gesture = read_gesture(&file).expect("gesture");
        gesture.cut.smooth = true;
        let r = replay(&target, &gesture).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let corners: Vec<[glam::DVec3; 4]> = r.cutter.planes.iter().map(|p| p.corners()).collect();
        let tolerance =
            cutter::adaptive::ADAPTIVE_TOLERANCE * cutter::adaptive::cross_section(&corners);
        for levels in [2, 3] {
            let uniform = r.cutter.uniform_smoothing(levels).mesh.triangulate();
            let smoothing = r.cutter.smoothing(levels);
            assert_eq!(smoothing.levels, levels, "{name}: levels given up");
            smoothing.mesh.check_closed().unwrap();
            let adaptive = smoothing.mesh.triangulate();
            csg::check_cutter(&adaptive).unwrap_or_else(|e| panic!("{name} {levels}: {e}"));
            assert!(adaptive.triangle_count() <= uniform.triangle_count());
            let index = csg::SpatialIndex::build(&adaptive);
            let deviation = uniform
                .positions
                .iter()
                .map(|&p| index.closest_point(&adaptive, p).unwrap().distance)
                .fold(0.0, f64::max);
            assert!(
                deviation <= tolerance * 1.0001,
                "{name} {levels}: deviation {deviation} > {tolerance}"
            );
            let volume_change = adaptive.volume() / uniform.volume() - 1.0;
            println!(
                "{name} {}, levels {levels}: {} → {} triangles ({:.0}%), max deviation {deviation:.2e} ({:.2}% of the cross-section), volume {:+.3}%",
                r.cutter.kind.name(),
                uniform.triangle_count(),
                adaptive.triangle_count(),
                100.0 * adaptive.triangle_count() as f64 / uniform.triangle_count() as f64,
                100.0 * deviation / cutter::adaptive::cross_section(&corners),
                100.0 * volume_change,
            );
            uniform_total += uniform.triangle_count();
            adaptive_total += adaptive.triangle_count();
        }
    }
    println!("all gestures: {uniform_total} → {adaptive_total} triangles");
    assert!(
        (adaptive_total as f64) < 0.9 * uniform_total as f64,
        "adaptive subdivision saved less than 10%: {uniform_total} → {adaptive_total}"
    );
}

/// `cutaway render --json` of a session whose smooth cutter has `levels` (the window's
/// Smoothness): the cut uses that many levels (reported with the cutter surface's triangles), and
/// a session without the field gets the default.
#[test]
fn render_json_of_a_session_uses_its_cutter_levels() {
    let dir = scratch("render-levels");
    let target = dir.join("sphere.obj");
    cutaway::io::write_mesh(&target, &sphere()).expect("write sphere");
    let gesture = gestures()
        .into_iter()
        .find(|p| p.ends_with("sphere_s.json"))
        .expect("S gesture");
    let mut gesture = read_gesture(&gesture).unwrap();
    gesture.cut.smooth = true;
    let r = replay(&sphere(), &gesture).unwrap();
    let planes: Vec<serde_json::Value> = r
        .cutter
        .planes
        .iter()
        .map(|p| serde_json::json!(p.corners().map(|c| c.to_array())))
        .collect();
    let mut triangles = Vec::new();
    for levels in [None, Some(0), Some(1), Some(3)] {
        let mut entry = serde_json::json!({"target": 0, "kind": "curving", "smooth": true,
                                           "planes": planes, "views": {"cut": true}});
        if let Some(l) = levels {
            entry["levels"] = serde_json::json!(l);
        }
        let session = serde_json::json!({
            "format": "cutaway-session/2",
            "models": [{"path": "sphere.obj", "color": [0.9, 0.7, 0.6]}],
            "cutters": [entry],
            "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30}
        });
        let Some(json) = render_json(&dir, &format!("levels{levels:?}"), &session) else {
            return;
        };
        let c = &json["cutters"][0];
        assert_eq!(c["exact"], true, "{json}");
        let expected = levels.unwrap_or(cutter::subdivision::DEFAULT_LEVELS);
        assert_eq!(c["levels"], expected, "{json}");
        let mut with_levels = r.cutter.clone();
        with_levels.levels = expected;
        assert_eq!(
            c["triangles"].as_u64().unwrap() as usize,
            with_levels.surface().triangle_count(),
            "{json}"
        );
        triangles.push(c["triangles"].as_u64().unwrap());
    }
    // No field means the default (2 levels): between 1 and 3 levels in size.
    assert!(
        triangles[1] < triangles[2] && triangles[2] < triangles[0] && triangles[0] < triangles[3],
        "{triangles:?}"
    );
}
