//! End-to-end tests of `cutaway export SESSION.json --out scene.html`: the cut scene as one
//! self-contained web page.
//!
//! Without a browser: the page carries, per variant, exactly the `.glb` that `cutaway export`
//! writes (and the Khronos validator passes it when `CUTAWAY_GLTF_VALIDATOR` names the npm
//! package), loads nothing from outside, and the default head with one cut stays under 15 MB;
//! errors are one line and write nothing.
//!
//! With a browser (`CUTAWAY_PLAYWRIGHT`: the playwright-core package folder, `CUTAWAY_CHROMIUM`:
//! the Chromium binary, default `/usr/bin/chromium`; `.ci/run` installs both and sets them): the
//! page is opened from `file://` with the network off by `render/webpage/browser.js`, must log no error
//! or warning and request nothing, and its screenshots at 1280×800 are compared with `cutaway
//! render` of the same session ([`same_picture`]); a structure's checkbox hides it, the variant
//! choice shows the other variant's cut, the removed piece's slider hides it. Without the
//! variables these tests print why they skip; in CI they run. Screenshots and renders are kept in
//! `target/test-output/webpage/` to be looked at.

use crate::gltf_validator::{validate, validator_package};
use crate::scene_files;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use cutaway::cutting::cut_scene::preview_geometry;
use image::RgbaImage;
use scene_files::{
    box_obj, box_planes, cut_view, cutter, model, scratch, sphere_obj, write_session,
};

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/test-output/webpage");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `cutaway` with `args`; returns its JSON line, failing the test on an error.
fn run_json(args: &[&std::ffi::OsStr]) -> serde_json::Value {
    let output = cutaway().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "cutaway {args:?}: {stderr}");
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    serde_json::from_str(&stdout).unwrap()
}

fn export(session: &Path, out: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "export".as_ref(),
        session.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ];
    args.extend(extra.iter().map(|a| std::ffi::OsStr::new(*a)));
    run_json(&args)
}

fn render(session: &Path, out: &Path) -> RgbaImage {
    let output = cutaway()
        .arg("render")
        .arg(session)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "cutaway render: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    image::open(out).unwrap().to_rgba8()
}

/// The page's data and, per variant, the `.glb` bytes it carries (its payloads decoded as the
/// page's loader decodes them: base64, then gzip).
fn read_page(html: &str) -> (serde_json::Value, Vec<Vec<u8>>) {
    let element = |id: &str| {
        let open = format!("id=\"{id}\">");
        let start = html.find(&open)? + open.len();
        let end = start + html[start..].find("</script>")?;
        Some(&html[start..end])
    };
    let data: serde_json::Value =
        serde_json::from_str(element("cutaway-data").expect("the page's data")).unwrap();
    let mut scenes = Vec::new();
    while let Some(text) = element(&format!("cutaway-scene-{}", scenes.len())) {
        let zipped = base64_decode(text);
        let mut glb = Vec::new();
        std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&zipped[..]), &mut glb)
            .unwrap();
        scenes.push(glb);
    }
    (data, scenes)
}

fn base64_decode(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let bytes: Vec<u8> = text.bytes().filter(|&c| c != b'=').collect();
    let mut out = Vec::with_capacity(bytes.len() * 3 / 4);
    for chunk in bytes.chunks(4) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (k, &c)| n | (value(c) as u32) << (18 - 6 * k));
        out.extend(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

/// A skin box cut by a box with every view on and a sphere inside, in two variants: a window
/// from the front (active) and a slot from the side.
fn box_session(dir: &Path) -> PathBuf {
    let all_views = serde_json::json!({"cut": true, "transparency": 0.3,
        "ribbons": {"count": 3, "width": 0.5}, "slices": {"count": 2, "width": 0.5}});
    let front = vec![cutter(
        0,
        box_planes(-10.0, 10.0, -30.0, -5.0, -10.0, 30.0),
        all_views,
    )];
    let side = vec![cutter(
        0,
        box_planes(5.0, 30.0, -12.0, 12.0, -8.0, 30.0),
        serde_json::json!({"cut": true, "transparency": null}),
    )];
    let path = write_session(
        dir,
        &[
            (
                "skin.obj",
                box_obj([-20.0, -20.0, -20.0], [20.0, 20.0, 20.0]),
            ),
            ("organ.obj", sphere_obj([0.0, 0.0, 0.0], 8.0, 32, 16)),
        ],
        vec![
            model("skin.obj", [0.9, 0.75, 0.65]),
            model("organ.obj", [0.8, 0.2, 0.2]),
        ],
        front.clone(),
        [60.0, -160.0, 70.0],
    );
    let mut session: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    session["variants"] = serde_json::json!([
        {"name": "front window", "cutters": front},
        {"name": "side slot", "cutters": side},
    ]);
    std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
    path
}

/// The page holds, per variant, byte for byte what `cutaway export … .glb` writes for that
/// variant, valid under the Khronos validator; its data names the variants and the structures;
/// it references nothing outside itself.
#[test]
fn the_page_carries_the_glb_export_of_every_variant() {
    let dir = scratch("webpage-glb");
    let session = box_session(&dir);
    let page = dir.join("scene.html");
    let summary = export(&session, &page, &["--title", "Box <demo> & co"]);
    let html = std::fs::read_to_string(&page).unwrap();
    assert_eq!(summary["bytes"], html.len());
    assert_eq!(summary["structures"], 2);
    assert_eq!(summary["variants"], 2);
    assert!(summary["export_ms"].as_f64().unwrap() > 0.0);
    let mut keys: Vec<&str> = summary
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    assert_eq!(keys, ["bytes", "export_ms", "structures", "variants"]);

    let (data, scenes) = read_page(&html);
    assert_eq!(data["format"], "cutaway-webpage/1");
    assert_eq!(data["title"], "Box <demo> & co");
    assert!(html.contains("<title>Box &lt;demo&gt; &amp; co</title>"));
    assert_eq!(scenes.len(), 2);
    let names: Vec<&str> = data["variants"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["front window", "side slot"]);
    let structures: Vec<&str> = data["structures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(structures, ["skin", "organ"]);

    // Variant k's scene is `cutaway export` of the session with variant k active.
    let mut file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&session).unwrap()).unwrap();
    for (k, scene) in scenes.iter().enumerate() {
        file["active_variant"] = k.into();
        file["cutters"] = file["variants"][k]["cutters"].clone();
        let variant_session = dir.join(format!("variant-{k}.json"));
        std::fs::write(&variant_session, file.to_string()).unwrap();
        let glb = dir.join(format!("variant-{k}.glb"));
        export(&variant_session, &glb, &[]);
        assert!(
            std::fs::read(&glb).unwrap() == *scene,
            "variant {k}'s scene is not the .glb export"
        );
        // What each glTF material draws.
        let gltf = gltf::Gltf::from_slice(scene).unwrap();
        let roles = data["variants"][k]["materials"].as_array().unwrap();
        assert_eq!(roles.len(), gltf.materials().count());
        for (material, role) in gltf.materials().zip(roles) {
            let name = material.name().unwrap();
            let part = role["part"].as_str().unwrap();
            let expected = match name.rsplit(' ').next().unwrap() {
                "wall" => "wall",
                "removed" => "removed",
                "ribbon" => "ribbon",
                "contour" => "contour",
                _ => "surface",
            };
            assert_eq!(part, expected, "{name}");
        }
        if let Some(package) = validator_package() {
            let path = dir.join(format!("page-variant-{k}.glb"));
            std::fs::write(&path, scene).unwrap();
            let report = validate(&package, &path);
            assert_eq!(report["issues"]["numErrors"], 0, "{:#}", report["issues"]);
            assert!(report["info"]["totalTriangleCount"].as_u64().unwrap() > 0);
        }
    }
    if validator_package().is_none() {
        println!("validator skipped: CUTAWAY_GLTF_VALIDATOR is not set (.ci/run sets it)");
    }
    // The front window shows the removed piece at the session's 30 %; the side slot shows none.
    assert_eq!(data["variants"][0]["removed_opacity"].as_f64(), Some(0.3));
    assert!(data["variants"][1]["removed_opacity"].is_null());
    // Self-contained: no script, style, image or frame from elsewhere.
    for outside in ["src=", "<link", "@import", "url(", "<iframe", "<img"] {
        assert!(!html.contains(outside), "the page references {outside}…");
    }
}

#[test]
fn export_errors_are_one_line_and_write_nothing() {
    let dir = scratch("webpage-errors");
    let session = box_session(&dir);
    let fails = |args: &[&std::ffi::OsStr], names: &Path, says: &str| {
        let output = cutaway().args(args).output().unwrap();
        assert!(!output.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.starts_with(&format!("error: {}: ", names.display())),
            "{stderr}"
        );
        assert!(stderr.contains(says), "{stderr}");
    };
    let page = dir.join("scene.html");
    let s = session.as_os_str();
    let out = |p: &Path| p.as_os_str().to_owned();
    let o = out(&page);
    fails(
        &[
            "export".as_ref(),
            s,
            "--out".as_ref(),
            &o,
            "--title".as_ref(),
            " ".as_ref(),
        ],
        &page,
        "the title is empty",
    );
    let gltf = dir.join("scene.gltf");
    fails(
        &["export".as_ref(), s, "--out".as_ref(), &out(&gltf)],
        &gltf,
        "cannot write '.gltf'",
    );
    let glb = dir.join("scene.glb");
    fails(
        &[
            "export".as_ref(),
            s,
            "--out".as_ref(),
            &out(&glb),
            "--title".as_ref(),
            "x".as_ref(),
        ],
        &glb,
        "--title applies to a web page",
    );
    fails(
        &[
            "export".as_ref(),
            s,
            "--out".as_ref(),
            &o,
            "--focus".as_ref(),
            "liver".as_ref(),
        ],
        &page,
        "no structure named 'liver'",
    );
    // A cutter reaching a million target sizes away: the exact boolean refuses it.
    let far = write_session(
        &dir,
        &[("a.obj", box_obj([0.0; 3], [1.0; 3]))],
        vec![model("a.obj", [0.5, 0.5, 0.5])],
        vec![cutter(
            0,
            box_planes(0.2, 0.8, -1e6, 0.5, 0.2, 0.8),
            cut_view(),
        )],
        [0.0, -10.0, 0.0],
    );
    fails(
        &["export".as_ref(), far.as_os_str(), "--out".as_ref(), &o],
        &page,
        "variant 'current'",
    );
    assert!(!page.exists());
    let left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("scene"))
        .collect();
    assert!(left.is_empty(), "no partial or temporary files: {left:?}");
}

// ---------------------------------------------------------------------------------------------
// The default head.

/// Sessions of the embedded default head (as the window opens it) seen from the front, right
/// and above: `one_cut.json` with one box cut into the skin showing the removed piece at 30 %,
/// and `variants.json` with that cut and a second variant taking the crown off the skin, the
/// first active. Written once per test run.
fn head_sessions() -> &'static (PathBuf, PathBuf) {
    static SESSIONS: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    SESSIONS.get_or_init(|| {
        let dir = scratch("webpage-head");
        let models = cutaway::anatomy::default_scene::load().expect("the embedded head");
        let mut scene = cutaway::scene::Scene::default();
        for (i, model) in models.into_iter().enumerate() {
            let color = cutaway::anatomy::colors::structure_color(&model.name, model.color, i);
            scene
                .models
                .push(cutaway::scene::SceneModel::structure(model, color));
        }
        let bbox = scene.bbox();
        let centre = bbox.center();
        let direction = glam::DVec3::new(-0.55, 1.0, 0.5).normalize();
        scene.camera = cutter::Camera::framing(&bbox, direction, glam::DVec3::Z, 30.0);
        scene.camera.eye = centre + (scene.camera.eye - centre) * 0.8;
        let plain = dir.join("plain.json");
        cutaway::session::save(&plain, &scene).unwrap();
        let mut file: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&plain).unwrap()).unwrap();
        // The skin's front, upper right quarter (RAS: x to the patient's left is negative).
        let (min, max) = (bbox.min, bbox.max);
        let window = cutter(
            0,
            box_planes(
                min.x - 5.0,
                centre.x + 5.0,
                max.y + 5.0,
                centre.y - 10.0,
                centre.z - 5.0,
                max.z + 5.0,
            ),
            serde_json::json!({"cut": true, "transparency": 0.3}),
        );
        let crown = cutter(
            0,
            box_planes(
                min.x - 5.0,
                max.x + 5.0,
                max.y + 5.0,
                min.y - 5.0,
                centre.z + 30.0,
                max.z + 5.0,
            ),
            serde_json::json!({"cut": true}),
        );
        file["cutters"] = serde_json::json!([window]);
        let one_cut = dir.join("one_cut.json");
        std::fs::write(&one_cut, file.to_string()).unwrap();
        file["variants"] = serde_json::json!([
            {"name": "front window", "cutters": [window]},
            {"name": "crown", "cutters": [crown]},
        ]);
        let variants = dir.join("variants.json");
        std::fs::write(&variants, file.to_string()).unwrap();
        (one_cut, variants)
    })
}

/// The default head with one cut fits the page budget of 15 MB.
#[test]
fn the_default_head_with_one_cut_is_at_most_15_mb() {
    let (one_cut, _) = head_sessions();
    let page = out_dir().join("head.html");
    let summary = export(one_cut, &page, &["--title", "Head atlas, one cut"]);
    let bytes = summary["bytes"].as_u64().unwrap();
    println!("default head with one cut: {summary}");
    assert!(bytes <= 15 * 1024 * 1024, "{bytes} bytes");
    assert_eq!(summary["variants"], 1);
    let scene = cutaway::session::load(one_cut).unwrap();
    assert_eq!(
        summary["structures"].as_u64().unwrap() as usize,
        scene.models.iter().filter(|m| m.visible).count()
    );
    let html = std::fs::read_to_string(&page).unwrap();
    let (data, _) = read_page(&html);
    assert!(
        data["attribution"]["text"]
            .as_str()
            .is_some_and(|t| t.contains("SPL-PNL Brain Atlas")),
        "the embedded atlas is attributed"
    );
}

mod in_browser;
