//! End-to-end tests of `cutaway expose`: the JSON it prints, the session it writes (read back by
//! `metrics`, exposing again adds nothing), its refusals; and, ignored by default, the whole
//! table of the default head's deep structures from the six standard views.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::scene_files::{box_obj, scratch, sphere_obj};

fn cutaway(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(args)
        .output()
        .unwrap()
}

fn json_of(output: &Output) -> serde_json::Value {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let stdout = String::from_utf8(output.stdout.clone()).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

fn f(value: &serde_json::Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("not a number: {value}"))
}

/// A focus (ball of radius 8 at the origin) inside a head (ball of radius 40), behind a plate that
/// covers its left half, and a small ball beside it that hides nothing; seen from the front at
/// 200 mm. A `cutaway-session/2` file with named structures.
fn head_scene(dir: &Path) -> PathBuf {
    let files = [
        ("focus.obj", sphere_obj([0.0; 3], 8.0, 48, 24)),
        ("head.obj", sphere_obj([0.0; 3], 40.0, 96, 48)),
        (
            "plate.obj",
            box_obj([-30.0, -25.0, -15.0], [-2.0, -20.0, 15.0]),
        ),
        ("beside.obj", sphere_obj([25.0, 0.0, 0.0], 4.0, 24, 12)),
    ];
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let model = |path: &str, name: &str| {
        serde_json::json!({"path": path, "structure": 0, "name": name, "color": [0.8, 0.7, 0.6],
                           "opacity": 1.0, "style": "solid", "visible": true})
    };
    let session = serde_json::json!({
        "format": "cutaway-session/2",
        "models": [model("focus.obj", "focus"), model("head.obj", "head"),
                   model("plate.obj", "plate"), model("beside.obj", "beside")],
        "cutters": [],
        "camera": {"eye": [0, -200, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
    });
    let path = dir.join("session.json");
    std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
    path
}

#[test]
fn expose_prints_the_exposures_and_writes_the_session_with_one_cutter_per_occluder() {
    let dir = scratch("expose-cli");
    let session = head_scene(&dir);
    let out = dir.join("exposed.json");
    let (s, o) = (session.to_str().unwrap(), out.to_str().unwrap());
    let json = json_of(&cutaway(&[
        "expose", s, "--focus", "focus", "--out", o, "--json",
    ]));
    let mut keys: Vec<&str> = json
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "cutters",
            "expose_ms",
            "exposure_after",
            "exposure_before",
            "exposure_unoccluded",
            "focus",
            "opened",
            "removed_volume"
        ]
    );
    assert_eq!(json["focus"], "focus");
    assert_eq!(json["cutters"], 2);
    assert_eq!(json["opened"], serde_json::json!(["head", "plate"]));
    let (before, after, free) = (
        f(&json["exposure_before"]),
        f(&json["exposure_after"]),
        f(&json["exposure_unoccluded"]),
    );
    assert_eq!(before, 0.0, "inside the head nothing is seen");
    assert!(
        (0.45..0.5).contains(&free),
        "a ball shows a little under half: {free}"
    );
    assert!(after >= 0.9 * free, "{after} of {free}");
    // The head loses at most the cone of the focus's silhouette and margin from its surface to
    // the focus's far side (radius 11 at 200 mm, 40 deep): π·11²·40 ≈ 15 200 mm³, and the
    // plate a share of its 4 200 mm³.
    let removed = f(&json["removed_volume"]);
    assert!((2000.0..19_000.0).contains(&removed), "{removed} mm³");
    assert!(f(&json["expose_ms"]) > 0.0);

    // The written session holds the two cutters, aimed at the head and the plate, and measures
    // the same exposure with `metrics`.
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let targets: Vec<u64> = written["cutters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["target"].as_u64().unwrap())
        .collect();
    assert_eq!(targets, [1, 2]);
    let metrics = json_of(&cutaway(&["metrics", o, "--focus", "focus", "--json"]));
    assert_eq!(f(&metrics["focus"]["exposure_after"]), after);
    assert_eq!(
        f(&metrics["structures"][3]["removed_volume"]),
        0.0,
        "beside"
    );
    assert_eq!(
        f(&metrics["structures"][0]["removed_volume"]),
        0.0,
        "the focus is not cut"
    );

    // `compare` draws and measures the exposed cutters as the session's one variant.
    let compared = cutaway(&[
        "compare",
        o,
        "--out",
        dir.join("compare").to_str().unwrap(),
        "--width",
        "96",
        "--height",
        "72",
        "--focus",
        "focus",
        "--json",
    ]);
    let stderr = String::from_utf8_lossy(&compared.stderr);
    if !compared.status.success() && stderr.contains("no GPU adapter") {
        println!("compare skipped: {stderr}");
    } else {
        let json = json_of(&compared);
        let variants = json["variants"].as_array().unwrap();
        assert_eq!(variants.len(), 1, "{json}");
        assert_eq!(f(&variants[0]["metrics"]["focus"]["exposure_after"]), after);
        assert!(dir.join("compare/compare.png").exists());
    }

    // Exposing again from the same view finds nothing left to open, and the sentence says so.
    let again = dir.join("again.json");
    let json = json_of(&cutaway(&[
        "expose",
        o,
        "--focus",
        "focus",
        "--out",
        again.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(json["cutters"], 0, "{json}");
    assert_eq!(f(&json["exposure_before"]), after);
    let sentence = cutaway(&[
        "expose",
        o,
        "--focus",
        "focus",
        "--out",
        again.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&sentence.stdout);
    assert!(text.starts_with("focus is in full view"), "{text}");
}

#[test]
fn expose_refuses_an_unknown_focus_a_bad_margin_and_an_output_that_is_no_session() {
    let dir = scratch("expose-refusals");
    let session = head_scene(&dir);
    let s = session.to_str().unwrap();
    let out = dir.join("out.json");
    let o = out.to_str().unwrap();
    let refused = |args: &[&str], says: &[&str]| {
        let output = cutaway(args);
        assert!(!output.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.starts_with("error: "), "{stderr}");
        for word in says {
            assert!(stderr.contains(word), "{stderr} lacks {word}");
        }
    };
    refused(
        &["expose", s, "--focus", "liver", "--out", o, "--json"],
        &[
            "session.json",
            "no structure named 'liver'",
            "focus, head, plate, beside",
        ],
    );
    refused(
        &[
            "expose", s, "--focus", "focus", "--margin", "-2", "--out", o,
        ],
        &["--margin", "outside"],
    );
    refused(
        &[
            "expose",
            s,
            "--focus",
            "focus",
            "--out",
            dir.join("out.obj").to_str().unwrap(),
        ],
        &["out.obj", ".json"],
    );
    refused(
        &[
            "expose",
            dir.join("none.json").to_str().unwrap(),
            "--focus",
            "focus",
            "--out",
            o,
        ],
        &["none.json"],
    );
    assert!(!out.exists(), "nothing is written on an error");
}

/// The default head's deep structures from the six standard views: exposure before, after and
/// unoccluded, removed volume and time of each exposure; fails where the goal (after ≥ 0.9 ×
/// unoccluded) is missed. Run it in release:
/// `cargo test --release -p cutaway --test cli expose -- --ignored --nocapture`.
#[test]
#[ignore = "the whole table takes minutes; run it in release"]
fn every_deep_structure_of_the_default_head_from_the_six_views() {
    use cutaway::expose::{ExposeSettings, apply, plan, report::report};
    use cutaway::platform::jobs::Progress;
    use cutaway::scene::{LengthUnit, Orientation, ViewPreset};
    use cutaway::scene::{Scene, SceneModel};

    let models = cutaway::anatomy::default_scene::load().unwrap();
    let mut head = Scene::default();
    for (i, model) in models.into_iter().enumerate() {
        let color = cutaway::anatomy::colors::structure_color(&model.name, model.color, i);
        head.models.push(SceneModel::structure(model, color));
    }
    head.orientation = Orientation::RAS;
    head.unit = LengthUnit::guess(&head.bbox(), true);
    let samples = 20_000;
    println!(
        "| structure | view | cutters | before | after | unoccluded | after/unoccluded | removed mm³ | expose ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut misses = Vec::new();
    let mut times = Vec::new();
    for focus in 1..head.models.len() {
        for preset in ViewPreset::ALL {
            let mut before = head.clone();
            before.camera = before.preset_camera(preset);
            let exposed = plan(
                &before,
                focus,
                &ExposeSettings::default(),
                &Progress::default(),
            )
            .unwrap();
            let mut after = before.clone();
            apply(&mut after, &exposed);
            let r = report(&before, &after, &exposed, samples).unwrap();
            let ratio = if r.exposure_unoccluded > 0.0 {
                r.exposure_after / r.exposure_unoccluded
            } else {
                1.0
            };
            println!(
                "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} | {:.0} |",
                r.focus,
                preset.label(),
                r.cutters,
                r.exposure_before,
                r.exposure_after,
                r.exposure_unoccluded,
                ratio,
                r.removed_volume.unwrap_or(0.0),
                r.expose_ms
            );
            times.push(r.expose_ms);
            if ratio < 0.9 || !exposed.notes.is_empty() {
                misses.push(format!(
                    "{} from {}: {ratio:.3} {:?}",
                    r.focus,
                    preset.label(),
                    exposed.notes
                ));
            }
        }
    }
    times.sort_by(f64::total_cmp);
    println!(
        "expose_ms: median {:.0}, max {:.0} over {} exposures",
        times[times.len() / 2],
        times[times.len() - 1],
        times.len()
    );
    assert!(misses.is_empty(), "goal missed:\n{}", misses.join("\n"));
}
