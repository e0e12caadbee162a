//! Sessions: the round trip, hand-written files, corrupt files, and `cutaway render` of a session.

use super::*;
use cutaway::session;

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("session-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `cutaway render <session> --out <out>` at `size` pixels, not yet run.
fn cli_render(session: &Path, out: &Path, size: [u32; 2]) -> std::process::Command {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"));
    command
        .arg("render")
        .arg(session)
        .arg("--out")
        .arg(out)
        .args([
            "--width",
            &size[0].to_string(),
            "--height",
            &size[1].to_string(),
        ]);
    command
}

/// Runs `command` on the software adapter unless `WGPU_BACKEND` names another.
fn software_render(mut command: std::process::Command) -> std::process::Output {
    command
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .output()
        .unwrap()
}

/// The picture `run` wrote to `out`; `None` after printing why when there is no adapter. Fails
/// the test when the render failed otherwise.
fn rendered(run: &std::process::Output, out: &Path) -> Option<image::RgbaImage> {
    let stderr = String::from_utf8_lossy(&run.stderr);
    if !run.status.success() && stderr.contains("no GPU adapter") {
        skip(Resource::Gpu, stderr);
        return None;
    }
    assert!(run.status.success(), "{stderr}");
    Some(image::open(out).unwrap().to_rgba8())
}

/// Writes two disconnected spheres into one OBJ (two regions).
fn write_two_region_obj(path: &Path) {
    let mut mesh = icosphere(DVec3::ZERO, 1.0, 1);
    mesh.append(&icosphere(DVec3::new(3.0, 0.0, 0.0), 0.5, 1));
    cutaway::io::write_mesh(path, &mesh).unwrap();
}

fn scene_for(dir: &Path) -> Scene {
    let path = dir.join("models").join("pair.obj");
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    write_two_region_obj(&path);
    let mut scene = Scene::default();
    for (region, m) in cutaway::io::load_models(&path)
        .unwrap()
        .into_iter()
        .enumerate()
    {
        let mut sm = SceneModel::new(m.name, m.source, m.mesh, [0.1 * region as f32, 0.5, 0.9]);
        sm.model.index = region;
        scene.models.push(sm);
    }
    scene.models[1].opacity = 0.5;
    scene.models[1].style = ModelStyle::Wireframe;
    scene.models[1].visible = false;
    scene.cutters.push(SceneCutter {
        target: 1,
        cutter: cutter::Cutter {
            kind: CutKind::Wedge,
            smooth: true,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes: corner_planes(),
        },
        views: CutterViews {
            cut: false,
            transparency: Some(0.25),
            ribbons: Some(even_sub_cutters(5, 2.0)),
            slices: None,
        },
    });
    scene.camera = camera();
    scene.render.background = [0.1, 0.2, 0.3, 1.0];
    scene.render.antialias = false;
    scene.render.stereo = Stereo::Anaglyph;
    scene
}

#[test]
fn session_round_trip_is_exact_and_relative() {
    let dir = temp_dir("round-trip");
    let scene = scene_for(&dir);
    let file = dir.join("s.json");
    session::save(&file, &scene).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("\"cutaway-session/1\""));
    assert!(
        text.contains("models/pair.obj"),
        "paths must be relative: {text}"
    );
    let back = session::load(&file).unwrap();
    assert_eq!(back.models.len(), 2);
    for (a, b) in scene.models.iter().zip(&back.models) {
        assert_eq!(
            (a.color, a.opacity, a.style, a.visible, a.model.index),
            (b.color, b.opacity, b.style, b.visible, b.model.index)
        );
        assert_eq!(a.model.mesh.triangles, b.model.mesh.triangles);
    }
    assert_eq!(scene.cutters, back.cutters);
    assert_eq!(scene.camera, back.camera);
    assert_eq!(scene.render, back.render);
    // Saving again gives the same bytes, and leaves no temporary file behind.
    session::save(&file, &back).unwrap();
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn hand_written_session_expands_regions_and_ignores_unknown_fields() {
    let dir = temp_dir("hand-written");
    write_two_region_obj(&dir.join("pair.obj"));
    let file = dir.join("s.json");
    std::fs::write(
        &file,
        r#"{"format": "cutaway-session/1", "future": [1, 2],
            "models": [{"path": "pair.obj", "color": [0.9, 0.7, 0.6], "opacity": 1.0, "style": "solid", "visible": true, "note": "x"}],
            "cutters": [{"target": 1, "kind": "curving", "smooth": false, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                         "views": {"cut": true, "transparency": null, "ribbons": null, "slices": null}}],
            "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
            "render": {"background": [1, 1, 1, 1], "antialias": true, "stereo": "none"}}"#,
    )
    .unwrap();
    let scene = session::load(&file).unwrap();
    assert_eq!(scene.models.len(), 2, "both regions of pair.obj are models");
    assert_eq!(scene.models[1].model.index, 1);
    assert_eq!(scene.models[1].color, [0.9, 0.7, 0.6]);
    assert_eq!(scene.cutters[0].target, 1);
}

#[test]
fn corrupt_session_is_a_one_line_error_naming_the_file_and_nothing_is_lost() {
    let dir = temp_dir("corrupt");
    let scene = scene_for(&dir);
    let good = dir.join("good.json");
    session::save(&good, &scene).unwrap();
    let before = std::fs::read(&good).unwrap();
    let bad = dir.join("bad.json");
    for (text, expect) in [
        (&before[..before.len() / 2], "line"),
        (&b"{\"format\": \"something-else/2\", \"models\": []}"[..], "something-else/2"),
        (&b"{\"format\": \"cutaway-session/1\", \"models\": [], \"cutters\": [{\"target\": 4, \"planes\": [[[0,0,0],[0,1,0],[0,1,1],[0,0,1]]]}]}"[..], "target 4"),
        (&b"{\"format\": \"cutaway-session/1\", \"models\": [{\"path\": \"missing.obj\"}]}"[..], "missing.obj"),
    ] {
        std::fs::write(&bad, text).unwrap();
        let err = session::load(&bad).unwrap_err();
        let line = cutaway::cli::error_line(&err);
        assert!(!line.contains('\n'));
        assert!(line.contains("bad.json") || expect == "missing.obj", "{line}");
        assert!(line.contains(expect), "{line}");
    }
    // A failed save (folder does not exist) leaves the old session untouched.
    assert!(session::save(&dir.join("no/such/dir/s.json"), &scene).is_err());
    assert_eq!(std::fs::read(&good).unwrap(), before);
}

#[test]
fn cli_render_writes_the_png_headless() {
    let dir = temp_dir("cli");
    let mut scene = scene_for(&dir);
    scene.models[1].visible = true;
    scene.render.stereo = Stereo::None;
    let file = dir.join("s.json");
    session::save(&file, &scene).unwrap();
    let out = dir.join("out.png");
    let run = software_render(cli_render(&file, &out, [96, 64]));
    let Some(image) = rendered(&run, &out) else {
        return;
    };
    assert_eq!(image.dimensions(), (96, 64));
    // The picture is the session's: its dark blue background in the four corners, its first
    // sphere (blue, [0, 0.5, 0.9]) in the middle, and the spheres covering a plausible share of
    // the image (the unit sphere alone is about a fifth of it from this camera). A blank or
    // black PNG fails here.
    let corner = pixel(&image, 0, 0);
    for (x, y) in [(95, 0), (0, 63), (95, 63)] {
        assert_eq!(pixel(&image, x, y), corner, "corner ({x}, {y})");
    }
    assert!(
        corner[2] > corner[1] && corner[1] > corner[0] && corner[2] < 140,
        "background {corner:?} is not the session's [0.1, 0.2, 0.3]"
    );
    let [r, g, b, _] = pixel(&image, 48, 32);
    assert!(
        b > r + 60 && b > g && (b as i32 - corner[2] as i32).abs() > 40,
        "centre pixel {r} {g} {b} is not the blue sphere"
    );
    let covered = coverage(&image, [corner[0], corner[1], corner[2]]);
    assert!(
        covered > 0.12 && covered < 0.6,
        "the models cover {covered:.3} of the image"
    );
    // Bad session: one line on stderr naming the file, non-zero exit.
    std::fs::write(&file, "{not json").unwrap();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(["render"])
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ") && stderr.contains("s.json"),
        "{stderr}"
    );
}

/// A model edited since it was loaded (here: its mesh replaced by a sphere elsewhere) is
/// saved next to the session, so `cutaway render` shows the edited mesh even after the file
/// it was loaded from is gone.
#[test]
fn cli_render_shows_an_edited_mesh_saved_with_the_session() {
    let dir = temp_dir("edited");
    let source = dir.join("small.ply");
    cutaway::io::write_mesh(&source, &icosphere(DVec3::new(0.0, 0.0, 3.0), 0.1, 1)).unwrap();
    let loaded = cutaway::io::load_models(&source).unwrap().remove(0);
    let mut model = SceneModel::new(loaded.name, loaded.source, loaded.mesh, [0.8, 0.2, 0.2]);
    model.replace_mesh(Arc::new(icosphere(DVec3::ZERO, 1.0, 2)));
    let mut scene = Scene::default();
    scene.models.push(model);
    scene.camera = camera();
    scene.render.antialias = false;
    let file = dir.join("edited.json");
    session::save(&file, &scene).unwrap();
    std::fs::remove_file(&source).unwrap();
    let out = dir.join("edited.png");
    let run = software_render(cli_render(&file, &out, [64, 48]));
    let Some(image) = rendered(&run, &out) else {
        return;
    };
    // The unit sphere at the origin fills the middle of the view (the loaded sphere was
    // small and above it).
    assert!(coverage(&image, [255, 255, 255]) > 0.05);
    let [r, g, b, _] = pixel(&image, 32, 24);
    assert!(
        r > g && r > b,
        "centre pixel {r} {g} {b} is not the model's red"
    );
}

/// A successful render prints nothing, also without `XDG_RUNTIME_DIR` and without
/// `WGPU_BACKEND` (then wgpu also probes OpenGL, whose window-system libraries complain
/// about the missing runtime folder unless `cutaway` gives them one).
#[test]
fn cli_render_success_prints_nothing_without_a_runtime_dir() {
    let dir = temp_dir("quiet");
    let scene = scene_for(&dir);
    let file = dir.join("s.json");
    session::save(&file, &scene).unwrap();
    let out = dir.join("out.png");
    let run = cli_render(&file, &out, [32, 32])
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WGPU_BACKEND")
        .output()
        .unwrap();
    if rendered(&run, &out).is_none() {
        return;
    }
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(
        stderr, "",
        "a successful render must print nothing on stderr"
    );
    assert!(out.is_file());
}
