//! End-to-end tests of cut variants and `cutaway compare`: each variant's removed volumes equal
//! what `cutaway metrics` measures on a session holding only that variant's cutters (and the
//! analytic answer), the JSON and CSV files agree number for number, the pictures and the sheet
//! are written as one set, and sessions without variants keep loading as one variant.
//!
//! The command renders on the GPU (lavapipe with `WGPU_BACKEND=vulkan`); with no adapter the
//! tests print "skipped: …" and pass.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::scene_files::{box_obj, box_planes, cut_view, cutter, model, scratch, write_session};

fn cutaway(args: &[&str], session: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(args)
        .arg(session)
        .args(extra)
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .output()
        .unwrap()
}

/// Runs `cutaway compare` into `out`; `None` (after printing why) when there is no GPU adapter.
fn compare(session: &Path, out: &Path, extra: &[&str]) -> Option<serde_json::Value> {
    let mut args = vec![
        "--out",
        out.to_str().unwrap(),
        "--width",
        "96",
        "--height",
        "72",
    ];
    args.extend_from_slice(extra);
    args.push("--json");
    let run = cutaway(&["compare"], session, &args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    if !run.status.success() && stderr.contains("no GPU adapter") {
        skip(Resource::Gpu, stderr);
        return None;
    }
    assert!(run.status.success(), "{stderr}");
    let stdout = String::from_utf8(run.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    Some(serde_json::from_str(&stdout).unwrap())
}

fn metrics(session: &Path, extra: &[&str]) -> serde_json::Value {
    let run = cutaway(&["metrics"], session, &[extra, &["--json"]].concat());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    serde_json::from_slice(&run.stdout).unwrap()
}

/// Corner cube A (x, z > 5, y < 5) and slot B (4 < x < 6, y < 3) of a 10 mm cube, as cutters.
fn corner() -> serde_json::Value {
    cutter(0, box_planes(5.0, 15.0, -5.0, 5.0, 5.0, 15.0), cut_view())
}
fn slot() -> serde_json::Value {
    cutter(0, box_planes(4.0, 6.0, -5.0, 3.0, -5.0, 15.0), cut_view())
}

/// The cube, a second box beside it (never cut) and the three variants `corner`, `slot` and
/// `both`, `slot` active; returns the session's path.
fn cube_with_variants(dir: &Path) -> PathBuf {
    let session = write_session(
        dir,
        &[
            ("cube.obj", box_obj([0.0; 3], [10.0; 3])),
            ("side.obj", box_obj([20.0, 0.0, 0.0], [24.0, 4.0, 4.0])),
        ],
        vec![
            model("cube.obj", [0.8, 0.6, 0.5]),
            model("side.obj", [0.3, 0.5, 0.9]),
        ],
        vec![slot()],
        [0.0, -100.0, 5.0],
    );
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&session).unwrap()).unwrap();
    json["variants"] = serde_json::json!([
        {"name": "corner", "cutters": [corner()]},
        {"name": "slot", "cutters": [slot()]},
        {"name": "both, \"A\"+B", "cutters": [corner(), slot()]},
    ]);
    json["active_variant"] = serde_json::json!(1);
    std::fs::write(&session, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    session
}

fn f(value: &serde_json::Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("not a number: {value}"))
}

#[test]
fn each_variant_removes_what_metrics_measures_on_its_cutters_alone() {
    let dir = scratch("compare-volumes");
    let session = cube_with_variants(&dir);
    let Some(json) = compare(&session, &dir.join("out"), &["--critical", "side"]) else {
        return;
    };
    let variants = json["variants"].as_array().unwrap();
    let names: Vec<&str> = variants
        .iter()
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["corner", "slot", "both, \"A\"+B"]);
    let cutters = [vec![corner()], vec![slot()], vec![corner(), slot()]];
    let analytic = [125.0, 60.0, 170.0];
    for (k, variant) in variants.iter().enumerate() {
        // The same cuts as a plain session (no variants) measured by `cutaway metrics`.
        let alone_dir = scratch(&format!("compare-volumes-alone-{k}"));
        let alone = write_session(
            &alone_dir,
            &[
                ("cube.obj", box_obj([0.0; 3], [10.0; 3])),
                ("side.obj", box_obj([20.0, 0.0, 0.0], [24.0, 4.0, 4.0])),
            ],
            vec![
                model("cube.obj", [0.8, 0.6, 0.5]),
                model("side.obj", [0.3, 0.5, 0.9]),
            ],
            cutters[k].clone(),
            [0.0, -100.0, 5.0],
        );
        let expected = metrics(&alone, &["--critical", "side"]);
        let got = &variant["metrics"];
        for s in 0..2 {
            for field in [
                "removed_volume",
                "removed_area",
                "wall_area",
                "min_distance",
            ] {
                assert_eq!(
                    got["structures"][s][field], expected["structures"][s][field],
                    "variant {k}, structure {s}, {field}"
                );
            }
        }
        assert_eq!(got["cutters"], expected["cutters"], "variant {k} cutters");
        let volume = f(&got["structures"][0]["removed_volume"]);
        assert!(
            (volume - analytic[k]).abs() < 1e-9,
            "variant {k}: {volume} mm³, expected {}",
            analytic[k]
        );
        assert_eq!(f(&got["structures"][1]["removed_volume"]), 0.0);
        let image = image::open(dir.join("out").join(variant["image"].as_str().unwrap()))
            .unwrap()
            .to_rgba8();
        assert_eq!(image.dimensions(), (96, 72));
    }
    // The variants draw different pictures: the corner cut and the slot cut differ.
    let picture = |k: usize| image::open(dir.join("out/variants").join(format!("variant-{k}.png")));
    assert_ne!(
        picture(1).unwrap().to_rgba8(),
        picture(2).unwrap().to_rgba8()
    );
    let sheet = image::open(dir.join("out/compare.png")).unwrap().to_rgba8();
    assert!(
        sheet.width() > 3 * 96 && sheet.height() > 72,
        "{:?}",
        sheet.dimensions()
    );
    // The files hold what was printed.
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/metrics.json")).unwrap())
            .unwrap();
    assert_eq!(written, json);
}

/// Splits one CSV line into fields (quoted fields with doubled quotes).
fn csv_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                fields.last_mut().unwrap().push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(String::new()),
            (c, _) => fields.last_mut().unwrap().push(c),
        }
    }
    fields
}

#[test]
fn metrics_json_and_csv_agree_number_for_number() {
    let dir = scratch("compare-csv");
    let session = cube_with_variants(&dir);
    let extra = ["--focus", "side", "--critical", "side", "--samples", "400"];
    let Some(json) = compare(&session, &dir.join("out"), &extra) else {
        return;
    };
    let csv = std::fs::read_to_string(dir.join("out/metrics.csv")).unwrap();
    let mut lines = csv.lines();
    let header = csv_fields(lines.next().unwrap());
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<Vec<String>> = lines.map(csv_fields).collect();
    let variants = json["variants"].as_array().unwrap();
    assert_eq!(rows.len(), variants.len() * 2);
    let cell = |value: &serde_json::Value| match value {
        serde_json::Value::Null => String::new(),
        v => format!("{}", f(v)),
    };
    for (r, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len(), "{row:?}");
        let variant = &variants[r / 2];
        let structure = &variant["metrics"]["structures"][r % 2];
        assert_eq!(row[column("variant")], variant["name"].as_str().unwrap());
        assert_eq!(
            row[column("structure")],
            structure["name"].as_str().unwrap()
        );
        for (csv_name, json_name) in [
            ("removed_volume_mm3", "removed_volume"),
            ("removed_area_mm2", "removed_area"),
            ("wall_area_mm2", "wall_area"),
            ("min_distance_mm", "min_distance"),
        ] {
            assert_eq!(
                row[column(csv_name)],
                cell(&structure[json_name]),
                "row {r}, {csv_name}"
            );
            // The text is the shortest round trip: it parses back to the very same number.
            if let Ok(x) = row[column(csv_name)].parse::<f64>() {
                assert_eq!(x, f(&structure[json_name]));
            }
        }
        let focus = &variant["metrics"]["focus"];
        let is_focus = r % 2 == 1;
        for (csv_name, json_name) in [
            ("exposure_before", "exposure_before"),
            ("exposure_after", "exposure_after"),
        ] {
            let expected = if is_focus {
                cell(&focus[json_name])
            } else {
                String::new()
            };
            assert_eq!(row[column(csv_name)], expected, "row {r}, {csv_name}");
        }
    }
}

#[test]
fn a_session_without_variants_is_one_variant_and_reruns_replace_the_set() {
    let dir = scratch("compare-old");
    let out = dir.join("out");
    let session = cube_with_variants(&dir);
    let Some(json) = compare(&session, &out, &[]) else {
        return;
    };
    assert_eq!(json["variants"].as_array().unwrap().len(), 3);
    assert!(out.join("variants/variant-3.png").exists());
    // The same folder, now from a session written before variants existed.
    let old = write_session(
        &dir,
        &[("cube.obj", box_obj([0.0; 3], [10.0; 3]))],
        vec![model("cube.obj", [0.8, 0.6, 0.5])],
        vec![corner(), slot()],
        [0.0, -100.0, 5.0],
    );
    let json = compare(&old, &out, &[]).unwrap();
    let variants = json["variants"].as_array().unwrap();
    assert_eq!(variants.len(), 1);
    assert_eq!(variants[0]["name"], "current");
    let volume = f(&variants[0]["metrics"]["structures"][0]["removed_volume"]);
    assert!((volume - 170.0).abs() < 1e-9, "{volume}");
    assert!(out.join("variants/variant-1.png").exists());
    assert!(
        !out.join("variants/variant-3.png").exists(),
        "a picture of the earlier, larger set is left"
    );
}

#[test]
fn bad_requests_are_one_error_line_and_write_nothing() {
    let dir = scratch("compare-bad");
    let session = cube_with_variants(&dir);
    let out = dir.join("out");
    for (extra, expect) in [
        (&["--focus", "liver"][..], "no structure named 'liver'"),
        (&["--width", "5000"][..], "--width 5000"),
    ] {
        let run = cutaway(
            &["compare"],
            &session,
            &[&["--out", out.to_str().unwrap()], extra].concat(),
        );
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success());
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(expect), "{stderr}");
        assert!(!out.join("compare.png").exists());
    }
    // A variant whose cutter aims at a model that does not exist: the file and the variant named.
    let text =
        std::fs::read_to_string(&session)
            .unwrap()
            .replacen("\"target\": 0", "\"target\": 9", 1);
    std::fs::write(&session, text).unwrap();
    let run = cutaway(&["compare"], &session, &["--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("session.json") && stderr.contains("target 9"),
        "{stderr}"
    );
}
