//! End-to-end tests of the window: the real `CutawayApp` driven headless by egui_kittest with its
//! wgpu renderer (the 3D view's paint callback runs too), no display needed.
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (install `mesa-vulkan-drivers`
//! and set `WGPU_BACKEND=vulkan`; CI does).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cutaway::gui::{CutawayApp, Mode, StartOptions};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

/// `Some(reason)` when there is no adapter to run the window on.
fn no_adapter() -> Option<String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    match pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())) {
        Ok(_) => None,
        Err(e) => Some(format!(
            "no wgpu adapter ({e}); install mesa-vulkan-drivers and set WGPU_BACKEND=vulkan"
        )),
    }
}

/// A fresh private folder for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-gui-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn harness(
    state_dir: &Path,
    paths: Vec<PathBuf>,
    offer_recovery: bool,
) -> Harness<'static, CutawayApp> {
    let start = StartOptions {
        paths,
        state_dir: state_dir.to_path_buf(),
        offer_recovery,
    };
    Harness::builder()
        .wgpu()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_max_steps(10_000)
        // The slider value boxes of egui 0.37 carry no accessible name of their own.
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start))
}

/// Steps the app until its background jobs are done (loads, cuts), then a few frames more.
fn settle(h: &mut Harness<'_, CutawayApp>) {
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().busy() {
        assert!(
            Instant::now() < deadline,
            "background jobs did not finish within 120 s"
        );
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(3);
}

/// Clicks the mode button `label` (the toggle button, not a menu of the same name).
fn click_mode(h: &mut Harness<'_, CutawayApp>, label: &str) {
    h.query_all_by_label(label)
        .find(|n| n.accesskit_node().toggled().is_some())
        .unwrap_or_else(|| panic!("no mode button {label}"))
        .click();
    h.run_steps(2);
}

/// Clicks the menu item whose label starts with `text` (a shortcut may follow) and does not
/// contain `not`.
fn click_menu_item(h: &mut Harness<'_, CutawayApp>, text: &str, not: &str) {
    h.query_all_by_label_contains(text)
        .find(|n| {
            let label = n
                .accesskit_node()
                .label()
                .map(|l| l.to_string())
                .unwrap_or_default();
            label.starts_with(text) && !label.contains(not)
        })
        .unwrap_or_else(|| panic!("no menu item {text}"))
        .click();
    h.run_steps(2);
}

#[test]
fn window_loads_the_default_scene_switches_modes_and_saves_a_session() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("smoke");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);

    // The default scene is loaded, framed, and shown.
    let app = h.state();
    assert!(
        !app.scene.models.is_empty(),
        "default scene not loaded: {}",
        app.status.message
    );
    assert!(!app.status.is_error, "status: {}", app.status.message);
    let triangles: usize = app
        .scene
        .models
        .iter()
        .map(|m| m.mesh.triangle_count())
        .sum();
    assert!(
        triangles > 1000,
        "default scene has only {triangles} triangles"
    );
    assert_eq!(app.mode, Mode::Camera);

    // Camera mode: a drag in the viewport orbits the camera.
    let eye_before = h.state().scene.camera.eye;
    h.drag_at(egui::pos2(800.0, 400.0));
    h.step();
    h.hover_at(egui::pos2(900.0, 430.0));
    h.step();
    h.drop_at(egui::pos2(900.0, 430.0));
    h.run_steps(2);
    let eye_after = h.state().scene.camera.eye;
    assert!(
        (eye_after - eye_before).length() > 1e-6,
        "drag did not orbit the camera"
    );
    let distance_before = h.state().scene.camera.distance();

    // The modes switch through their buttons.
    click_mode(&mut h, "Edit");
    assert_eq!(h.state().mode, Mode::Edit);
    h.get_by_label("extrude (Shift: straight)");
    click_mode(&mut h, "Preview");
    assert_eq!(h.state().mode, Mode::Preview);
    click_mode(&mut h, "Camera");
    assert_eq!(h.state().mode, Mode::Camera);
    assert!(
        (h.state().scene.camera.distance() - distance_before).abs() < 1e-9,
        "mode switches moved the camera"
    );

    // The rendered frame is not blank: the 3D view drew something other than the background.
    let image = h.render().expect("render the window");
    let shot = dir.join("gui-smoke.png");
    image.save(&shot).expect("save screenshot");
    let centre = image
        .get_pixel(image.width() * 6 / 10, image.height() / 2)
        .0;
    let corner = image.get_pixel(image.width() - 5, image.height() - 40).0;
    println!(
        "screenshot: {} (centre {centre:?}, corner {corner:?})",
        shot.display()
    );
    assert_ne!(
        centre, corner,
        "the viewport shows only background where the head should be"
    );

    // Save Session through the File menu writes a cutaway-session/2 file (models are structures).
    let session = dir.join("smoke-session.json");
    h.state_mut().session_path = Some(session.clone());
    h.get_by_label("File").click();
    h.run_steps(2);
    click_menu_item(&mut h, "Save Session", "As");
    let text = std::fs::read_to_string(&session).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (status: {})",
            session.display(),
            h.state().status.message
        )
    });
    let json: serde_json::Value = serde_json::from_str(&text).expect("session is JSON");
    assert_eq!(json["format"], "cutaway-session/2");
    assert_eq!(
        json["models"].as_array().map(Vec::len),
        Some(h.state().scene.models.len()),
        "every model is in the session"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn hiding_a_model_is_undone_and_redone_with_the_keyboard() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("undo");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    assert!(
        !h.state().scene.models.is_empty(),
        "default scene not loaded: {}",
        h.state().status.message
    );
    let name = h.state().scene.models[0].name.clone();

    // Select the first model in the Models list, then untick Visible in its properties.
    h.get_by_label(&name).click();
    h.run_steps(2);
    assert_eq!(h.state().selected_model, Some(0));
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "Visible")
        .click();
    h.run_steps(3);
    assert!(
        !h.state().scene.models[0].visible,
        "Visible checkbox did not hide the model"
    );

    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert!(
        h.state().scene.models[0].visible,
        "Ctrl+Z did not undo the hide"
    );
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.run_steps(2);
    assert!(
        !h.state().scene.models[0].visible,
        "Ctrl+Shift+Z did not redo the hide"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_crash_autosave_is_offered_and_can_be_discarded() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("recovery");
    std::fs::write(dir.join("recovery-session.json"), "{}").unwrap();
    let mut h = harness(&dir, Vec::new(), true);
    h.run_steps(2);
    h.get_by_label("Restore the previous session?");
    h.get_by_label("Discard").click();
    h.run_steps(2);
    assert!(h.state().pending_recovery.is_none());
    assert!(
        !dir.join("recovery-session.json").exists(),
        "discard keeps the autosave"
    );
    settle(&mut h);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_file_is_one_line_error_before_any_window() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .args(["open", "/nonexistent/knee.obj"])
        .output()
        .expect("run cutaway");
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: /nonexistent/knee.obj"),
        "{stderr}"
    );
}

/// Steps until `done()` or the deadline; returns the frames stepped.
fn step_until(
    h: &mut Harness<'_, CutawayApp>,
    what: &str,
    mut done: impl FnMut(&Harness<'_, CutawayApp>) -> bool,
) -> usize {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut frames = 0;
    while !done(h) {
        assert!(Instant::now() < deadline, "{what}: not within 120 s");
        h.step();
        frames += 1;
        std::thread::sleep(Duration::from_millis(5));
    }
    frames
}

#[test]
fn painting_in_edit_mode_shows_the_live_cut() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("live");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    assert!(h.state().viewport.live.enabled, "Live cut is on by default");
    click_mode(&mut h, "Edit");
    // Press, drag and release on the knee: the editor initialises a cutter on the model under
    // the pointer.
    let rect = h.state().viewport.rect;
    let (a, b) = (
        rect.center() + egui::vec2(-40.0, 0.0),
        rect.center() + egui::vec2(30.0, 10.0),
    );
    h.drag_at(a);
    h.step();
    for k in 1..=5 {
        h.hover_at(a + (b - a) * (k as f32 / 5.0));
        h.step();
    }
    h.drop_at(b);
    h.run_steps(2);
    assert_eq!(
        h.state().scene.cutters.len(),
        1,
        "no cutter was made (status: {})",
        h.state().status.message
    );
    // Grab the handle (middle of the leading plane's front edge) and paint down the leg: every
    // move extrudes and asks for a new live cut.
    let app = h.state();
    let lead = app.scene.cutters[0].cutter.planes.last().unwrap().corners();
    let handle_px = app
        .scene
        .camera
        .project(app.viewport.size_px, (lead[0] + lead[3]) * 0.5)
        .expect("handle in view");
    let ppp = h.ctx.pixels_per_point();
    let handle = rect.min + egui::vec2(handle_px.x as f32 / ppp, handle_px.y as f32 / ppp);
    let planes_before = app.scene.cutters[0].cutter.planes.len();
    h.drag_at(handle);
    h.step();
    for k in 1..=12 {
        h.hover_at(handle + egui::vec2(2.0 * k as f32, 12.0 * k as f32));
        h.step();
    }
    h.drop_at(handle + egui::vec2(24.0, 144.0));
    h.run_steps(2);
    assert!(
        h.state().scene.cutters[0].cutter.planes.len() > planes_before,
        "the handle drag did not extrude"
    );
    // The live cut arrives in the background and is drawn in Edit mode.
    step_until(&mut h, "live cut", |h| {
        let live = &h.state().viewport.live;
        live.shown().is_some() && !live.pending()
    });
    let app = h.state();
    let shown = app.viewport.live.shown().unwrap();
    let target = app.scene.cutters[0].target;
    assert!(shown.geometry.replaced[target], "the target is not cut");
    assert!(
        shown
            .geometry
            .parts
            .iter()
            .any(|p| p.kind == cutaway::cutting::cut_scene::PartKind::Wall),
        "the live cut has no walls: {:?}",
        shown.geometry.notes
    );
    assert!(!shown.geometry.contours.is_empty(), "no contour");
    let live_walls: usize = shown
        .geometry
        .parts
        .iter()
        .filter(|p| p.kind == cutaway::cutting::cut_scene::PartKind::Wall)
        .map(|p| p.mesh.triangle_count())
        .sum();
    assert_eq!(app.status.last_cut_ms, Some(shown.ms));
    assert!(
        app.viewport.live.finished >= 1,
        "no live cut finished while painting"
    );
    println!(
        "live cut of {} in {:.1} ms",
        app.scene.models[target].name, shown.ms
    );
    let image = h.render().expect("render the window");
    image.save(dir.join("live-cut.png")).unwrap();
    let _ = image.save(Path::new(env!("CARGO_TARGET_TMPDIR")).join("gui-live-cut.png"));

    // Preview cuts the same cutter the same way (kept part and walls alike).
    click_mode(&mut h, "Preview");
    settle(&mut h);
    let preview = h
        .state()
        .viewport
        .preview
        .clone()
        .expect("preview geometry");
    let live = h.state().viewport.live.shown().map(|r| r.geometry.clone());
    assert!(live.is_none(), "the live cut is kept outside Edit mode");
    let walls = |g: &cutaway::cutting::cut_scene::PreviewGeometry| -> usize {
        g.parts
            .iter()
            .filter(|p| p.kind == cutaway::cutting::cut_scene::PartKind::Wall)
            .map(|p| p.mesh.triangle_count())
            .sum()
    };
    assert_eq!(
        walls(&preview),
        live_walls,
        "Preview and the live cut differ"
    );
    click_mode(&mut h, "Edit");
    // Turning Live cut off draws the uncut model again (no live geometry handed to the renderer).
    h.get_by_label("Live cut").click();
    h.run_steps(2);
    assert!(!h.state().viewport.live.enabled);
    let inputs = cutaway::gui::bridge::frame_inputs(h.state(), [64, 48]);
    assert!(inputs.preview.is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

#[path = "image_compare.rs"]
mod image_compare;

#[test]
fn export_image_writes_the_viewport_picture_at_any_size() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("export");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    h.state_mut().viewport.show_marker = false; // a window overlay, not part of the picture
    let ctx = h.ctx.clone();
    let size = h.state().viewport.size_px;
    let (w, h1) = (size.x as u32, size.y as u32);

    // 1× the viewport: the same pixels as the 3D view of the window.
    let one = dir.join("one.png");
    h.state_mut().export_image.width = w;
    h.state_mut().export_image.height = h1;
    h.state_mut().export_image.transparent = false;
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::ExportImageTo(one.clone()));
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let exported = image::open(&one).expect("exported PNG").to_rgba8();
    assert_eq!(exported.dimensions(), (w, h1));
    let window = h.render().expect("render the window");
    let rect = h.state().viewport.rect;
    let ppp = h.ctx.pixels_per_point();
    let view = image::imageops::crop_imm(
        &window,
        (rect.min.x * ppp).round() as u32,
        (rect.min.y * ppp).round() as u32,
        w,
        h1,
    )
    .to_image();
    view.save(dir.join("view.png")).unwrap();
    let d = image_compare::difference(&exported, &view);
    println!("export vs viewport: {d}");
    assert!(
        d.within_tolerance(),
        "export differs from the viewport: {d} ({})",
        dir.display()
    );

    // 2× the viewport, transparent background: the picture `cutaway render` makes of the saved
    // session, with the background cleared.
    let session = dir.join("session.json");
    h.state_mut().apply(
        &ctx,
        cutaway::gui::app::Action::SaveSessionTo(session.clone()),
    );
    let two = dir.join("two.png");
    h.state_mut().export_image.width = 2 * w;
    h.state_mut().export_image.height = 2 * h1;
    h.state_mut().export_image.transparent = true;
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::ExportImageTo(two.clone()));
    settle(&mut h);
    let exported = image::open(&two).expect("exported PNG").to_rgba8();
    assert_eq!(exported.dimensions(), (2 * w, 2 * h1));
    assert_eq!(
        exported.get_pixel(2, 2)[3],
        0,
        "background is not transparent"
    );
    let reference = dir.join("cli.png");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("render")
        .arg(&session)
        .arg("--out")
        .arg(&reference)
        .args(["--width", &(2 * w).to_string()])
        .args(["--height", &(2 * h1).to_string()])
        .output()
        .expect("run cutaway render");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut reference = image::open(&reference).unwrap().to_rgba8();
    // The CLI draws the scene background; composite the export over it to compare.
    let bg = h.state().scene.render.background;
    let bg = [bg[0], bg[1], bg[2]].map(|c| (c * 255.0).round());
    let mut composited = exported.clone();
    for p in composited.pixels_mut() {
        let a = p[3] as f32 / 255.0;
        for k in 0..3 {
            p[k] = (p[k] as f32 * a + bg[k] * (1.0 - a)).round() as u8;
        }
        p[3] = 255;
    }
    for p in reference.pixels_mut() {
        p[3] = 255;
    }
    let d = image_compare::difference(&composited, &reference);
    println!("2x transparent export vs cutaway render: {d}");
    assert!(
        d.within_tolerance(),
        "export differs from `cutaway render`: {d} ({})",
        dir.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_two_million_triangle_load_and_index_never_block_the_window() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("big");
    // 1,997,120 triangles, written as binary PLY.
    let big = std::sync::Arc::new(csg::testkit::geodesic_sphere(316, 40.0));
    assert!(big.triangle_count() > 1_990_000);
    let file = dir.join("big_sphere.ply");
    cutaway::io::write_mesh(&file, &big).expect("write the big mesh");

    let small = dir.join("small.obj");
    cutaway::io::write_mesh(&small, &csg::testkit::icosphere(2, 10.0)).unwrap();
    let mut h = harness(&dir, vec![small], false);
    settle(&mut h);
    let ctx = h.ctx.clone();
    let models_before = h.state().scene.models.len();
    assert_eq!(models_before, 1);

    // The load: `apply` returns at once with the job pending, and frames keep coming; the
    // progress window (shown only to frames drawn while the job runs) offers Cancel.
    h.state_mut()
        .apply(&ctx, cutaway::gui::app::Action::Add(vec![file.clone()]));
    assert!(h.state().busy(), "the load did not start a background job");
    assert_eq!(h.state().scene.models.len(), models_before);
    let frames = step_until(&mut h, "progress window", |h| {
        h.query_by_label("Cancel").is_some()
    });
    assert!(
        h.state().busy(),
        "the job ended before Cancel could be pressed"
    );
    println!("{frames} frames drawn while the 2M-triangle load ran");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert!(!h.state().busy(), "Cancel left the job running");
    assert_eq!(
        h.state().scene.models.len(),
        models_before,
        "cancel changed the scene"
    );
    assert!(
        h.state().status.message.contains("cancelled"),
        "{}",
        h.state().status.message
    );

    // The index build of a 2M-triangle target: same story.
    let mut model = cutaway::scene::SceneModel::new("big", &file, big.clone(), [0.7, 0.7, 0.7]);
    model.visible = false;
    h.state_mut().scene.models.push(model);
    h.state_mut().start_index_job(&ctx, 1);
    assert!(
        h.state().busy(),
        "the index build did not start a background job"
    );
    let scene_before = h.state().scene.models.len();
    // The index build is fast (well under a second in release), so it may finish before its
    // progress window is drawn: then the window kept drawing frames while it ran and the index
    // is stored; otherwise Cancel is pressed and nothing is stored.
    let frames = step_until(&mut h, "progress window or the index", |h| {
        h.query_by_label("Cancel").is_some() || !h.state().busy()
    });
    if h.query_by_label("Cancel").is_some() && h.state().busy() {
        h.get_by_label("Cancel").click();
        h.run_steps(3);
        assert!(!h.state().busy());
        // The build may finish between the frame that showed Cancel and the click: then it
        // was not cancelled and its index is kept.
        let cancelled = h.state().status.message.contains("cancelled");
        assert_eq!(
            h.state().viewport.editor.index_for(&big).is_some(),
            !cancelled,
            "index stored: {}, status: {}",
            h.state().viewport.editor.index_for(&big).is_some(),
            h.state().status.message
        );
    } else {
        println!("the index build finished after {frames} frames, before Cancel showed");
        assert!(frames >= 1, "no frame was drawn while the index was built");
        assert!(
            h.state().viewport.editor.index_for(&big).is_some(),
            "the finished index was not stored"
        );
    }
    assert_eq!(h.state().scene.models.len(), scene_before);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A folder of structure files as an atlas exports them: `atlas/` with two hippocampi (one of
/// them two spheres: a structure with two regions) and `atlas/brainstem/pons`.
fn write_atlas(dir: &Path) -> PathBuf {
    let atlas = dir.join("atlas");
    std::fs::create_dir_all(atlas.join("brainstem")).unwrap();
    let sphere = |x: f64| {
        let mut m = csg::testkit::icosphere(2, 5.0);
        for p in &mut m.positions {
            p.x += x;
        }
        m
    };
    let mut two = sphere(-20.0);
    two.append(&sphere(-35.0));
    cutaway::io::write_mesh(&atlas.join("Model_17_left_hippocampus.obj"), &two).unwrap();
    cutaway::io::write_mesh(&atlas.join("Model_53_right_hippocampus.obj"), &sphere(20.0)).unwrap();
    cutaway::io::write_mesh(&atlas.join("brainstem/Model_35_pons.obj"), &sphere(0.0)).unwrap();
    atlas
}

/// Ticks or unticks the checkbox labelled exactly `label`.
fn click_checkbox(h: &mut Harness<'_, CutawayApp>, label: &str) {
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, label)
        .click();
    h.run_steps(3);
}

#[test]
fn the_models_list_names_structures_groups_folders_and_filters() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("models-list");
    let atlas = write_atlas(&dir);
    let mut h = harness(&dir, vec![atlas], false);
    settle(&mut h);
    let names: Vec<(String, String)> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| (m.name.clone(), m.group.clone()))
        .collect();
    let expect = |n: &str, g: &str| (n.to_string(), g.to_string());
    assert_eq!(
        names,
        [
            expect("left hippocampus", "atlas"),
            expect("right hippocampus", "atlas"),
            expect("pons", "atlas/brainstem"),
        ],
        "one model per file, named from the file, grouped by folder (status: {})",
        h.state().status.message
    );
    // The two-sphere file is one structure with both regions.
    assert_eq!(
        csg::regions::split_regions(&h.state().scene.models[0].mesh).len(),
        2
    );
    // Colours come from the anatomy table: both hippocampi alike, the pons different.
    let colours: Vec<[f32; 3]> = h.state().scene.models.iter().map(|m| m.color).collect();
    assert_eq!(colours[0], colours[1]);
    assert_ne!(colours[0], colours[2]);
    // Rows and group headers are in the list.
    h.get_by_label("left hippocampus");
    h.get_by_label("pons");
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "atlas (3)");
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "brainstem (1)");

    // A group's box hides everything in it, and one undo brings it back.
    click_checkbox(&mut h, "brainstem (1)");
    assert!(
        !h.state().scene.models[2].visible,
        "the group box hid the pons"
    );
    assert!(h.state().scene.models[0].visible);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert!(
        h.state().scene.models[2].visible,
        "undo showed the pons again"
    );

    // The filter keeps the matching rows; Hide listed hides only those.
    h.get_by_role(egui::accesskit::Role::TextInput).click();
    h.run_steps(1);
    h.get_by_role(egui::accesskit::Role::TextInput)
        .type_text("hippo");
    h.run_steps(3);
    assert!(
        h.query_by_label("pons").is_none(),
        "the filter hides the pons row"
    );
    h.get_by_label("left hippocampus");
    h.get_by_label("Hide listed").click();
    h.run_steps(3);
    let visible: Vec<bool> = h.state().scene.models.iter().map(|m| m.visible).collect();
    assert_eq!(visible, [false, false, true]);

    // Cleared filter: every row is back, and Show all shows everything.
    h.get_by_label("Clear").click();
    h.run_steps(3);
    h.get_by_label("pons");
    h.get_by_label("Show all").click();
    h.run_steps(3);
    assert!(h.state().scene.models.iter().all(|m| m.visible));

    // The two-sphere hippocampus split on request: its regions become a folder of their own in
    // its place, and one undo makes it one model again.
    h.get_by_label("left hippocampus").click();
    h.run_steps(3);
    assert_eq!(h.state().selected_model, Some(0));
    h.get_by_label("Split").click();
    h.run_steps(3);
    let names: Vec<(String, String)> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| (m.name.clone(), m.group.clone()))
        .collect();
    assert_eq!(
        names,
        [
            expect("left hippocampus 1", "atlas/left hippocampus"),
            expect("right hippocampus", "atlas"),
            expect("pons", "atlas/brainstem"),
            expect("left hippocampus 2", "atlas/left hippocampus"),
        ],
        "{}",
        h.state().status.message
    );
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "left hippocampus (2)");
    h.get_by_label("left hippocampus 2");
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gui-models-list-split.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(3);
    assert_eq!(h.state().scene.models.len(), 3, "undo joined the regions");
    assert_eq!(h.state().scene.models[0].name, "left hippocampus");
    let shot = dir.join("models-list.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_brain_atlas_folder_lists_one_named_coloured_model_per_file() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let anatomy = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("../shared/anatomy"));
    let atlas = anatomy.join("head_brain_spl_atlas");
    if !atlas.is_dir() {
        println!(
            "skipped: {} not found (set CUTAWAY_ANATOMY)",
            atlas.display()
        );
        return;
    }
    let dir = temp_dir("brain-atlas");
    let mut h = harness(&dir, vec![atlas], false);
    settle(&mut h);
    let app = h.state();
    assert_eq!(
        app.scene.models.len(),
        38,
        "one model per file (status: {})",
        app.status.message
    );
    let model = |name: &str| {
        app.scene
            .models
            .iter()
            .find(|m| m.name == name)
            .unwrap_or_else(|| panic!("no model named {name}"))
    };
    let srgb = |c: [f32; 3]| c.map(|v| (v * 255.0).round() as u8);
    assert_eq!(srgb(model("left hippocampus").color), [220, 216, 20]);
    assert_eq!(srgb(model("right lateral ventricle").color), [88, 106, 215]);
    assert_eq!(model("corpus callosum").group, "head_brain_spl_atlas");
    h.get_by_label("left hippocampus");
    let shot = dir.join("brain-atlas-list.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
}

#[test]
fn the_default_scene_is_the_head_atlas_seen_from_the_front() {
    if let Some(reason) = no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let dir = temp_dir("default-head");
    let mut h = harness(&dir, Vec::new(), false);
    settle(&mut h);
    let app = h.state();
    let names: Vec<&str> = app.scene.models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names.first(), Some(&"skin"), "{names:?}");
    for deep in [
        "left lateral ventricle",
        "left hippocampus",
        "right putamen",
        "pons",
    ] {
        assert!(names.contains(&deep), "{deep} missing from {names:?}");
    }
    // RAS anatomy: the face looks toward +Y, so the camera stands on the +Y side, Z up.
    let camera = app.scene.camera;
    assert!(camera.eye.y > camera.target.y + 100.0, "{camera:?}");
    assert_eq!(camera.up, glam::DVec3::Z);
    let shot = dir.join("default-scene.png");
    h.render().expect("render").save(&shot).expect("save");
    println!("screenshot: {}", shot.display());
}
