//! End-to-end tests of `cutaway metrics`: removed volumes and areas against analytic answers and
//! against the boolean's own removed piece, exposure on a sphere behind a plate with a hole, and
//! distances from the walls to critical structures.

use std::path::Path;
use std::process::Command;

use crate::scene_files::{
    box_obj, box_planes, cut_view, cutter, model, scratch, sphere_obj, write_session,
};

fn metrics(session: &Path, extra: &[&str]) -> serde_json::Value {
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("metrics")
        .arg(session)
        .args(extra)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

fn f(value: &serde_json::Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("not a number: {value}"))
}

fn assert_close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: {actual} != {expected} ± {tolerance}"
    );
}

/// A 10 mm cube with a corner box cutter (A: the 5 mm corner cube at x, z > 5, y < 5) and an
/// overlapping slot (B: x in 4..6, y < 3, through in z).
fn cube_with_two_cutters(dir: &Path) -> std::path::PathBuf {
    write_session(
        dir,
        &[("cube.obj", box_obj([0.0; 3], [10.0; 3]))],
        vec![model("cube.obj", [0.8, 0.6, 0.5])],
        vec![
            cutter(0, box_planes(5.0, 15.0, -5.0, 5.0, 5.0, 15.0), cut_view()),
            cutter(0, box_planes(4.0, 6.0, -5.0, 3.0, -5.0, 15.0), cut_view()),
        ],
        [0.0, -100.0, 5.0],
    )
}

#[test]
fn removed_volume_and_area_of_box_cuts_match_the_analytic_answer() {
    let dir = scratch("metrics-cube");
    let session = cube_with_two_cutters(&dir);
    let json = metrics(&session, &[]);
    let cutters = json["cutters"].as_array().unwrap();
    assert_eq!(cutters.len(), 2);
    // A removes the 5³ corner; B the 2×3×10 slot less the 1×3×5 it shares with A.
    assert_close(f(&cutters[0]["removed_volume"]), 125.0, 1e-9, "A volume");
    assert_close(f(&cutters[1]["removed_volume"]), 45.0, 1e-9, "B volume");
    // A takes three 5×5 squares of the cube's surface; B the y = 0 strip (2×10 less A's 1×5),
    // and the bottom and top strips (2×3 each, less A's 1×3 on the top).
    assert_close(f(&cutters[0]["removed_area"]), 75.0, 1e-9, "A area");
    assert_close(
        f(&cutters[1]["removed_area"]),
        15.0 + 6.0 + 3.0,
        1e-9,
        "B area",
    );
    // Walls left: A's x = 5, y = 5 and z = 5 squares, less what the slot took of its x = 5 wall
    // (y < 3, z > 5: 3×5) and of its z = 5 wall (x < 6, y < 3: 1×3); B's walls x = 4 (3×10),
    // y = 3 (2×10 less A's 1×5 above z = 5) and x = 6 below z = 5 (3×5).
    assert_close(
        f(&cutters[0]["wall_area"]),
        75.0 - 15.0 - 3.0,
        1e-9,
        "A walls",
    );
    assert_close(
        f(&cutters[1]["wall_area"]),
        30.0 + 15.0 + 15.0,
        1e-9,
        "B walls",
    );
    // Depth along the cutters' direction (+y): A enters at y = 0 and reaches y = 5, B reaches
    // y = 3.
    assert_close(f(&cutters[0]["depth"]), 5.0, 1e-9, "A depth");
    assert_close(f(&cutters[1]["depth"]), 3.0, 1e-9, "B depth");
    let cube = &json["structures"][0];
    assert_eq!(cube["name"], "cube");
    assert_eq!(cube["closed"], true);
    assert_close(f(&cube["removed_volume"]), 170.0, 1e-9, "total volume");
    assert!(cube["min_distance"].is_null());
    assert!(json["focus"].is_null());
}

/// The same cube and cutters in metres (a 10 mm cube is 0.01 m): a scene small enough to be
/// guessed as metres is measured in mm, mm² and mm³ all the same.
#[test]
fn a_scene_in_metres_is_measured_in_millimetres() {
    let dir = scratch("metrics-cube-metres");
    let m = 0.001;
    let session = write_session(
        &dir,
        &[("cube.obj", box_obj([0.0; 3], [10.0 * m; 3]))],
        vec![model("cube.obj", [0.8, 0.6, 0.5])],
        vec![
            cutter(
                0,
                box_planes(5.0 * m, 15.0 * m, -5.0 * m, 5.0 * m, 5.0 * m, 15.0 * m),
                cut_view(),
            ),
            cutter(
                0,
                box_planes(4.0 * m, 6.0 * m, -5.0 * m, 3.0 * m, -5.0 * m, 15.0 * m),
                cut_view(),
            ),
        ],
        [0.0, -100.0 * m, 5.0 * m],
    );
    let json = metrics(&session, &[]);
    let cutters = json["cutters"].as_array().unwrap();
    assert_close(f(&cutters[0]["removed_volume"]), 125.0, 1e-4, "A volume");
    assert_close(f(&cutters[0]["removed_area"]), 75.0, 1e-4, "A area");
    assert_close(f(&cutters[0]["depth"]), 5.0, 1e-4, "A depth");
    assert_close(
        f(&json["structures"][0]["removed_volume"]),
        170.0,
        1e-4,
        "total volume",
    );
}

#[test]
fn removed_volume_equals_the_boolean_s_removed_piece_closed_by_its_walls() {
    // A sphere cut by a box: no simple analytic answer for the polyhedron, so compare with the
    // volume of removed + reversed walls computed straight from csg (a different path: the
    // metrics take vol(before) − vol(after) of the in-turn cut).
    let dir = scratch("metrics-sphere");
    let session = write_session(
        &dir,
        &[("ball.obj", sphere_obj([1.0, 2.0, 3.0], 10.0, 32, 16))],
        vec![model("ball.obj", [0.7, 0.2, 0.2])],
        vec![cutter(
            0,
            box_planes(-3.0, 20.0, -20.0, 4.0, -1.0, 30.0),
            cut_view(),
        )],
        [0.0, -100.0, 0.0],
    );
    let json = metrics(&session, &[]);
    let scene = cutaway::session::load(&session).unwrap();
    let target = scene.models[0].model.mesh.clone();
    let index = csg::TargetIndex::build(target.clone()).unwrap();
    let surface = cutaway::cutting::cut_scene::cutter_mesh(&scene.cutters[0]);
    let result = csg::subtract(&index, &surface).unwrap();
    csg::cutcheck::check_measures(&target, &result).unwrap();
    let mut removed = result.removed.part().mesh.clone();
    removed.append(&result.walls.mesh.reversed());
    let expected = csg::cutcheck::volume(&removed);
    assert!(expected > 100.0, "the cut removes a real piece: {expected}");
    let actual = f(&json["structures"][0]["removed_volume"]);
    assert_close(actual, expected, 1e-9 * expected, "sphere volume");
    let area = result.removed.part().mesh.area();
    assert_close(
        f(&json["structures"][0]["removed_area"]),
        area,
        1e-9 * area,
        "sphere area",
    );
    assert_close(
        f(&json["structures"][0]["wall_area"]),
        result.walls.mesh.area(),
        1e-9 * area,
        "sphere walls",
    );
}

/// A sphere of radius 5 at the origin behind a 40 mm plate at y in -12..-10, seen from
/// (0, -100, 0); `hole` cuts a 16 mm square hole through the plate in front of the sphere.
fn sphere_behind_plate(dir: &Path, hole: bool) -> std::path::PathBuf {
    let cutters = if hole {
        vec![cutter(
            0,
            box_planes(-8.0, 8.0, -14.0, -8.0, -8.0, 8.0),
            cut_view(),
        )]
    } else {
        vec![]
    };
    write_session(
        dir,
        &[
            (
                "plate.obj",
                box_obj([-20.0, -12.0, -20.0], [20.0, -10.0, 20.0]),
            ),
            ("ball.obj", sphere_obj([0.0; 3], 5.0, 96, 48)),
        ],
        vec![
            model("plate.obj", [0.9, 0.8, 0.7]),
            model("ball.obj", [0.8, 0.1, 0.1]),
        ],
        cutters,
        [0.0, -100.0, 0.0],
    )
}

#[test]
fn exposure_of_a_sphere_through_a_hole_is_the_visible_cap() {
    let dir = scratch("metrics-exposure");
    let session = sphere_behind_plate(&dir, true);
    let json = metrics(&session, &["--focus", "ball", "--samples", "40000"]);
    let focus = &json["focus"];
    assert_eq!(focus["name"], "ball");
    assert_eq!(focus["samples"], 40000);
    // Behind the whole plate the sphere is hidden.
    assert_eq!(f(&focus["exposure_before"]), 0.0);
    // Through a hole wider than its silhouette, the eye at distance D sees the cap where
    // cos θ > r / D: the share (1 − r/D) / 2 of a sphere's area.
    let expected = (1.0 - 5.0 / 100.0) / 2.0;
    assert_close(f(&focus["exposure_after"]), expected, 0.01, "visible cap");
    // Without the hole nothing changes.
    let dir = scratch("metrics-exposure-closed");
    let session = sphere_behind_plate(&dir, false);
    let json = metrics(&session, &["--focus", "ball"]);
    assert_eq!(f(&json["focus"]["exposure_after"]), 0.0);
}

#[test]
fn min_distance_from_the_walls_to_critical_structures() {
    let dir = scratch("metrics-distance");
    let session = sphere_behind_plate(&dir, true);
    let json = metrics(&session, &["--critical", "ball"]);
    let ball = &json["structures"][1];
    // The nearest wall points are the hole's inner edges at y = -10, 8 from the axis:
    // √(8² + 10²) from the centre, less the radius (the polyhedron lies inside the sphere, its
    // faces less than r (1 − cos²(π/96)) ≈ 0.005 below it).
    let expected = (64.0_f64 + 100.0).sqrt() - 5.0;
    let d = f(&ball["min_distance"]);
    assert!(
        d >= expected - 1e-9 && d <= expected + 0.01,
        "{d} vs {expected}"
    );
    let on_wall: Vec<f64> = ball["wall_point"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    let on_ball: Vec<f64> = ball["closest_point"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    assert_close(
        on_wall[1],
        -10.0,
        1e-9,
        "wall point at the plate's back face",
    );
    let norm = on_ball.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm <= 5.0 + 1e-9 && norm > 4.99, "{on_ball:?}");
    assert!(
        json["structures"][0]["min_distance"].is_null(),
        "plate is not critical"
    );
    // The hole goes through the 2 mm plate.
    assert_close(f(&json["cutters"][0]["depth"]), 2.0, 1e-9, "hole depth");
    assert_eq!(
        json["structures"][1]["removed_area"].to_string(),
        "0.0",
        "uncut: +0"
    );

    // A rod through the corner cutter's x = 5 wall (inside the cube, not its target) touches it.
    let dir = scratch("metrics-distance-zero");
    let session = write_session(
        &dir,
        &[
            ("cube.obj", box_obj([0.0; 3], [10.0; 3])),
            ("rod.obj", box_obj([3.0, 1.0, 7.0], [7.0, 2.0, 8.0])),
        ],
        vec![
            model("cube.obj", [0.8, 0.6, 0.5]),
            model("rod.obj", [0.2, 0.2, 0.9]),
        ],
        vec![cutter(
            0,
            box_planes(5.0, 15.0, -5.0, 5.0, 5.0, 15.0),
            cut_view(),
        )],
        [0.0, -100.0, 5.0],
    );
    let json = metrics(&session, &["--critical", "rod"]);
    assert_eq!(f(&json["structures"][1]["min_distance"]), 0.0);
}

#[test]
fn unknown_structure_names_are_one_error_line_listing_the_structures() {
    let dir = scratch("metrics-unknown");
    let session = cube_with_two_cutters(&dir);
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("metrics")
        .arg(&session)
        .args(["--focus", "liver", "--json"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: ", session.display())),
        "{stderr}"
    );
    assert!(
        stderr.contains("'liver'") && stderr.contains("cube"),
        "{stderr}"
    );
    assert!(output.stdout.is_empty());
}

/// A session that names a single-region model: `metrics` and `compare` know it by that name,
/// unnumbered; a file holding several regions numbers them; a script still naming the model as
/// older versions did (`organ 1`) still finds it.
#[test]
fn a_single_region_model_is_found_by_the_name_the_session_gives_it() {
    let dir = scratch("metrics-names");
    std::fs::write(dir.join("organ.obj"), box_obj([0.0; 3], [10.0; 3])).unwrap();
    let pair = format!(
        "{}{}",
        box_obj([20.0, 0.0, 0.0], [24.0, 4.0, 4.0]),
        box_obj([30.0, 0.0, 0.0], [34.0, 4.0, 4.0])
            .lines()
            .map(|l| match l.strip_prefix("f ") {
                Some(f) => {
                    let shifted: Vec<String> = f
                        .split_whitespace()
                        .map(|i| (i.parse::<usize>().unwrap() + 8).to_string())
                        .collect();
                    format!("f {}\n", shifted.join(" "))
                }
                None => format!("{l}\n"),
            })
            .collect::<String>()
    );
    std::fs::write(dir.join("pair.obj"), pair).unwrap();
    let session = dir.join("named.json");
    std::fs::write(
        &session,
        r#"{"format": "cutaway-session/2", "models": [
            {"path": "organ.obj", "region": 0, "name": "organ"},
            {"path": "pair.obj", "region": 1}],
           "camera": {"eye": [5, -100, 5], "target": [5, 5, 5], "up": [0, 0, 1], "fov_y_deg": 30}}"#,
    )
    .unwrap();
    let json = metrics(&session, &["--focus", "organ", "--samples", "500"]);
    assert_eq!(json["focus"]["name"], "organ");
    let names: Vec<&str> = json["structures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    // The second of the pair's two regions, numbered as the file's.
    assert_eq!(names, ["organ", "pair 2"]);
    let old = metrics(&session, &["--focus", "organ 1", "--samples", "500"]);
    assert_eq!(old["focus"]["name"], "organ");
    // `compare` measures by the same names.
    let out = dir.join("compare");
    let output = Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("compare")
        .arg(&session)
        .args(["--focus", "organ", "--samples", "500", "--out"])
        .arg(&out)
        .arg("--json")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    if stderr.contains("no GPU adapter") {
        println!("compare skipped: {stderr}");
        return;
    }
    assert!(output.status.success(), "{stderr}");
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(
        json["variants"][0]["metrics"]["focus"]["name"], "organ",
        "{json}"
    );
}
