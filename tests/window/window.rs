//! The window a radiologist expects, driven headless by egui_kittest on the real wgpu renderer
//! (lavapipe without a GPU) at 1280×800: the orientation marker and the view presets, the up axis
//! and units of real data, selection and its highlight in every mode, the cut visible in Camera
//! mode, the cutter overlay on a live cut, new cutters by dragging, Hide Current Cutters, and the
//! Help menu. Screenshots go to the test's temporary folder (`CARGO_TARGET_TMPDIR`), one per
//! state, for a person to look at.
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with
//! Mesa's lavapipe installed); the real-data test reads `CUTAWAY_ANATOMY` (default `../shared/anatomy`).

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::harness::{apply, harness, no_adapter, shot};
use crate::input::{anatomy, click_mode, count_colour, drag, settle, temp_dir, view_px, wheel_at};
use cutaway::gui::app::Action;
use cutaway::gui::bridge::{frame_inputs, shown_cut};
use cutaway::gui::viewport::view_menu::ViewCommand;
use cutaway::gui::{CutawayApp, Mode, StartOptions};
use cutaway::scene::{LengthUnit, Orientation, ViewPreset};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::DVec3;

/// Mean absolute channel difference of two equally sized images inside `rect` (pixels).
fn difference_in(a: &image::RgbaImage, b: &image::RgbaImage, rect: egui::Rect) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0.0f64);
    for y in rect.min.y as u32..rect.max.y as u32 {
        for x in rect.min.x as u32..rect.max.x as u32 {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            for k in 0..3 {
                sum += (p[k] as f64 - q[k] as f64).abs();
            }
            n += 3.0;
        }
    }
    sum / n.max(1.0)
}

#[test]
fn the_first_frame_has_the_orientation_marker_and_every_preset_turns_the_view() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("presets");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    assert_eq!(h.state().scene.orientation, Orientation::RAS);
    let first = shot(&mut h, "default-first-frame");
    // The marker sits in the view's lower-left corner: its red (R/L), green (A/P) and blue (S/I)
    // axes are there, and not in the lower-right corner.
    let view = view_px(&h);
    let corner = egui::Rect::from_min_size(
        egui::pos2(view.min.x, view.max.y - 120.0),
        egui::vec2(120.0, 120.0),
    );
    let other = corner.translate(egui::vec2(view.width() - 120.0, 0.0));
    for (name, rgb) in [
        ("red", [230, 70, 60]),
        ("green", [80, 200, 90]),
        ("blue", [90, 140, 250]),
    ] {
        let n = count_colour(&first, corner, rgb);
        assert!(n >= 15, "only {n} {name} marker pixels in the corner");
        assert!(
            count_colour(&first, other, rgb) < n / 4,
            "{name} elsewhere too"
        );
    }
    let mut previous = first;
    for preset in ViewPreset::ALL {
        apply(&mut h, Action::View(ViewCommand::Preset(preset)));
        let camera = h.state().scene.camera;
        let (toward_eye, up) = Orientation::RAS.preset_axes(preset);
        assert!(
            ((camera.eye - camera.target).normalize() - toward_eye).length() < 1e-9,
            "{preset:?}: {camera:?}"
        );
        assert!(
            camera.basis().1.dot(up) > 0.999,
            "{preset:?}: up {:?}",
            camera.up
        );
        let image = shot(&mut h, &format!("preset-{}", preset.label().to_lowercase()));
        let d = difference_in(&image, &previous, view);
        assert!(d > 1.0, "{preset:?} looks like the view before it ({d})");
        previous = image;
    }
    // The number keys choose the same presets.
    h.key_press(egui::Key::Num3);
    h.run_steps(2);
    let c = h.state().scene.camera;
    assert!(
        (c.eye - c.target).normalize().dot(DVec3::X) > 0.999,
        "3: right view"
    );
    // Zoom to fit keeps the direction.
    apply(&mut h, Action::View(ViewCommand::ZoomToFit));
    let d = h.state().scene.camera;
    assert!((d.forward() - c.forward()).length() < 1e-9);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_double_click_selects_and_highlights_in_every_mode() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("select");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    let plain = shot(&mut h, "unselected");
    let centre = h.state().viewport.rect.center();
    for mode in [
        Mode::Camera,
        Mode::Preview,
        Mode::Edit,
        Mode::Scalpel,
        Mode::Camera,
    ] {
        click_mode(&mut h, mode);
        apply(&mut h, Action::SelectModel(None));
        // Long enough after the last mode's clicks that these two are a double-click of their own.
        h.run_steps(40);
        h.hover_at(centre);
        h.step();
        for pressed in [true, false, true, false] {
            h.event(egui::Event::PointerButton {
                pos: centre,
                button: egui::PointerButton::Primary,
                pressed,
                modifiers: Default::default(),
            });
        }
        h.step();
        h.run_steps(3);
        let app = h.state();
        assert_eq!(
            app.selected_model,
            Some(0),
            "{mode:?}: the skin under the centre is not selected ({})",
            app.status.message
        );
        assert_eq!(app.scene.cutters.len(), 0, "{mode:?}: a double-click cut");
        // Edit mode paints the selection: no tint there, so the live cut looks like the
        // committed one; every other mode tints it.
        let drawn = frame_inputs(app, [64, 48]).models[0].color;
        assert_eq!(
            drawn == app.scene.models[0].color,
            mode == Mode::Edit,
            "{mode:?}: tint {drawn:?}"
        );
    }
    // Camera mode centres on it; the list shows it selected; the view tints it.
    let selected = shot(&mut h, "selected-highlighted");
    let d = difference_in(&selected, &plain, view_px(&h));
    assert!(d > 1.5, "the selected skin is not highlighted ({d})");
    let inputs = frame_inputs(h.state(), [64, 48]);
    assert_ne!(inputs.models[0].color, h.state().scene.models[0].color);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dragging_outside_the_cutter_starts_another_and_hide_hides_only_the_current_ones() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("cutters");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    click_mode(&mut h, Mode::Edit);
    let c = h.state().viewport.rect.center();
    drag(
        &mut h,
        c + egui::vec2(-40.0, 40.0),
        c + egui::vec2(30.0, 50.0),
    );
    assert_eq!(
        h.state().scene.cutters.len(),
        1,
        "no first cutter ({})",
        h.state().status.message
    );
    // Extrude it down the face by its handle (the middle of the leading plane's front edge):
    // the live cut arrives under the translucent cutter.
    let app = h.state();
    let lead = app.scene.cutters[0].cutter.planes.last().unwrap().corners();
    let px = app
        .scene
        .camera
        .project(app.viewport.size_px, (lead[0] + lead[3]) * 0.5)
        .expect("handle in view");
    let ppp = h.ctx.pixels_per_point();
    let handle = app.viewport.rect.min + egui::vec2(px.x as f32 / ppp, px.y as f32 / ppp);
    drag(&mut h, handle, handle + egui::vec2(10.0, 90.0));
    assert!(
        h.state().scene.cutters[0].cutter.planes.len() > 1,
        "no extrusion"
    );
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().viewport.live.shown().is_none() || h.state().viewport.live.pending() {
        assert!(Instant::now() < deadline, "no live cut");
        h.step();
    }
    settle(&mut h);
    shot(&mut h, "edit-overlay-live-cut");
    // Hide the current cutter: its overlay goes, the next drag makes a visible one.
    apply(&mut h, Action::ToggleCutters);
    assert!(frame_inputs(h.state(), [64, 48]).overlays.is_empty());
    drag(
        &mut h,
        c + egui::vec2(-40.0, -120.0),
        c + egui::vec2(30.0, -110.0),
    );
    let app = h.state();
    assert_eq!(
        app.scene.cutters.len(),
        2,
        "the second drag did not start a new cutter ({})",
        app.status.message
    );
    assert_eq!(app.scene.cutters[0].target, app.scene.cutters[1].target);
    let overlays = frame_inputs(app, [64, 48]).overlays;
    assert_eq!(overlays.len(), 1, "only the new cutter shows");
    assert_eq!(
        overlays[0].planes,
        app.scene.cutters[1]
            .cutter
            .planes
            .iter()
            .map(|p| p.corners())
            .collect::<Vec<_>>()
    );
    // The cut stays visible in Camera mode: the preview is computed and drawn there too.
    click_mode(&mut h, Mode::Camera);
    settle(&mut h);
    let cut = shown_cut(h.state()).expect("Camera mode draws the cut");
    assert!(
        cut.parts
            .iter()
            .any(|p| p.kind == cutaway::cutting::cut_scene::PartKind::Wall),
        "no walls in Camera mode"
    );
    shot(&mut h, "camera-mode-shows-cut");
    // Scalpel mode draws the same cut; Preview adds the removed pieces' views to it.
    for mode in [Mode::Scalpel, Mode::Preview] {
        click_mode(&mut h, mode);
        settle(&mut h);
        let cut = shown_cut(h.state()).unwrap_or_else(|| panic!("{mode:?} mode draws no cut"));
        assert!(
            cut.parts
                .iter()
                .any(|p| p.kind == cutaway::cutting::cut_scene::PartKind::Wall),
            "no walls in {mode:?} mode"
        );
    }
    shot(&mut h, "preview-mode-shows-cut");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_help_menu_opens_the_keyboard_and_mouse_reference() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("help");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    assert!(
        h.query_by_label("Debug").is_none(),
        "the Debug menu shows without being asked for"
    );
    h.get_by_label("Help").click();
    h.run_steps(2);
    h.get_by_label("Keyboard and Mouse…").click();
    h.run_steps(3);
    h.get_by_label("Every mode");
    h.get_by_label("cut along the path");
    h.get_by_label("superior / inferior view");
    shot(&mut h, "help-keyboard-and-mouse");
    // The reference opens below the menu bar, not over it.
    let title = h.get_by_label("Keyboard and Mouse").rect();
    let menu = h.get_by_label("Help").rect();
    assert!(
        title.min.y > menu.max.y,
        "the window {title:?} covers the menu bar {menu:?}"
    );
    // About names the embedded anatomy and its licence.
    h.key_press(egui::Key::Escape);
    h.get_by_label("Help").click();
    h.run_steps(2);
    h.get_by_label("About Cutaway…").click();
    h.run_steps(3);
    h.get_by_label("3D Slicer License");
    h.get_by_label("SPL-PNL Brain Atlas");
    shot(&mut h, "help-about");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_hubmap_body_opens_upright_in_metres_and_the_knee_in_millimetres() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let (Some(body), Some(knee)) = (anatomy("hubmap_vhf_body"), anatomy("knee_vhf_left_denver"))
    else {
        return;
    };
    let dir = temp_dir("hubmap");
    let mut h = harness(&dir, vec![body]);
    settle(&mut h);
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(app.scene.orientation, Orientation::Y_UP);
    assert_eq!(app.scene.unit, LengthUnit::Metre);
    let camera = app.scene.camera;
    assert!(
        camera.basis().1.dot(DVec3::Y) > 0.999,
        "not upright: {camera:?}"
    );
    assert!(
        camera.eye.z > camera.target.z,
        "not facing the body: {camera:?}"
    );
    let depth = app.viewport.scalpel.settings.depth;
    assert!(depth > 0.01 && depth < 0.2, "scalpel depth {depth} m");
    // Upright: the view's top third holds the head, so more of the body shows in the middle
    // columns than at the sides, and the body is taller than wide on screen.
    let bbox = app.scene.bbox();
    let vp = app.viewport.size_px;
    let top = camera.project(vp, DVec3::new(bbox.center().x, bbox.max.y, bbox.center().z));
    let bottom = camera.project(vp, DVec3::new(bbox.center().x, bbox.min.y, bbox.center().z));
    assert!(top.unwrap().y < bottom.unwrap().y, "head below the feet");
    shot(&mut h, "hubmap-upright");

    apply(&mut h, Action::Open(vec![knee]));
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.scene.unit, LengthUnit::Millimetre);
    assert_eq!(app.scene.orientation, Orientation::RAS);
    let depth = app.viewport.scalpel.settings.depth;
    assert!(depth > 5.0 && depth < 50.0, "scalpel depth {depth} mm");
    shot(&mut h, "knee-mm");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn without_a_native_dialog_the_in_window_browser_opens_and_cancels() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("browser");
    let start = StartOptions {
        paths: Vec::new(),
        state_dir: dir.clone(),
        offer_recovery: false,
    };
    // The browser crate marks folders and files with emoji glyphs: the harness fails on any
    // glyph the window's fonts lack (drawn as an empty box).
    let mut h = Harness::builder()
        .wgpu()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_step_dt(1.0 / 60.0)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start));
    settle(&mut h);
    // As on a machine without a desktop portal or zenity.
    h.state_mut().native_dialogs = false;
    apply(&mut h, Action::Dialog(cutaway::gui::app::Purpose::Open));
    assert!(h.state().browser.is_some(), "no in-window browser");
    assert!(!h.state().busy(), "a native dialog job was started");
    // In a folder with a subfolder and a session: both listed with their glyph markers.
    let listed = dir.join("listed");
    std::fs::create_dir_all(listed.join("models")).unwrap();
    std::fs::write(listed.join("one.json"), "{}").unwrap();
    h.state_mut().browser = Some(cutaway::gui::panels::file_browser::FileBrowser::new(
        cutaway::gui::app::Purpose::Open,
        Some(listed),
    ));
    h.run_steps(3);
    h.get_by_label("\u{1F5C0} models");
    h.get_by_label("\u{1F5CB} one.json");
    shot(&mut h, "file-browser-fallback");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert!(
        h.state().browser.is_none(),
        "Cancel did not close the browser"
    );
    // A native dialog believed available that closes at once (a D-Bus session without a file
    // portal) brings the browser too. Only where nothing could really open, so the test never
    // waits on a person.
    if cutaway::gui::panels::file_browser::native_dialogs_available() {
        println!("a native dialog may open here: the closes-at-once fallback is not tried");
    } else {
        h.state_mut().native_dialogs = true;
        apply(&mut h, Action::Dialog(cutaway::gui::app::Purpose::Open));
        settle(&mut h);
        assert!(
            h.state().browser.is_some(),
            "a native dialog that never opened left nothing ({})",
            h.state().status.message
        );
        assert!(h.state().status.message.contains("browser"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn edit_mode_orbits_with_the_right_button_and_zooms_off_the_cutter() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("navigate");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    click_mode(&mut h, Mode::Edit);
    let c = h.state().viewport.rect.center();
    let before = h.state().scene.camera;
    // Right-drag: the camera orbits, no cutter is made, no context menu stays open.
    h.hover_at(c);
    h.step();
    for (pressed, at) in [(true, c), (false, c + egui::vec2(80.0, 10.0))] {
        if !pressed {
            for k in 1..=4 {
                h.hover_at(c + egui::vec2(20.0 * k as f32, 2.5 * k as f32));
                h.step();
            }
        }
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Secondary,
            pressed,
            modifiers: Default::default(),
        });
        h.step();
    }
    h.run_steps(2);
    let after = h.state().scene.camera;
    assert!(
        (after.eye - before.eye).length() > 1.0,
        "right-drag did not orbit in Edit mode"
    );
    assert!((after.distance() - before.distance()).abs() < 1e-6);
    assert!(
        h.state().scene.cutters.is_empty(),
        "right-drag made a cutter"
    );
    // The wheel off any cutter zooms.
    wheel_at(&mut h, c + egui::vec2(0.0, -200.0), 2.0);
    assert!(
        h.state().scene.camera.distance() < after.distance() * 0.95,
        "the wheel did not zoom in Edit mode"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A file the windowing system reports as dropped on the window.
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

/// Drops `paths` on the window as the windowing system does (one frame's `dropped_files`).
fn drop_files(h: &mut Harness<'_, CutawayApp>, paths: Vec<PathBuf>) {
    for path in paths {
        h.input_mut()
            .dropped_files
            .push(std::sync::Arc::new(Dropped(path)));
    }
    h.step();
}

#[test]
fn dropped_folders_and_sessions_open_and_messages_stay_in_the_status_bar() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("drop");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    let before = h.state().scene.models.len();
    // A folder of two meshes, dropped on a scene with models: added, one model per file.
    let folder = dir.join("parts");
    std::fs::create_dir_all(&folder).unwrap();
    let small = |x: f64| {
        cutaway::gui::app::box_mesh(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 10.0, 10.0, 10.0))
    };
    cutaway::io::write_mesh(&folder.join("left_block.obj"), &small(0.0)).unwrap();
    cutaway::io::write_mesh(&folder.join("right_block.stl"), &small(20.0)).unwrap();
    drop_files(&mut h, vec![folder.clone()]);
    settle(&mut h);
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(
        app.scene.models.len(),
        before + 2,
        "the folder's two files were not added ({})",
        app.status.message
    );
    let names: Vec<&str> = app
        .scene
        .models
        .iter()
        .map(|m| m.model.name.as_str())
        .collect();
    assert!(names.iter().any(|n| n.contains("left block")), "{names:?}");
    // The message that says so sits in the status bar under the view, not on the model.
    let message = app.status.message.clone();
    assert!(!message.is_empty());
    let view = app.viewport.rect;
    let label = h.get_by_label(&message).rect();
    assert!(
        label.min.y >= view.max.y - 0.5 && label.max.y <= 800.0,
        "the status text {label:?} is not under the view {view:?}"
    );
    shot(&mut h, "dropped-folder-status-bar");
    // A session dropped with a mesh: the session opens (its one model replaces the scene).
    let mut one = cutaway::scene::Scene::default();
    let model = cutaway::io::load_models(&folder.join("left_block.obj"))
        .unwrap()
        .remove(0);
    one.models.push(cutaway::scene::SceneModel::new(
        model.name,
        model.source,
        model.mesh,
        [0.8, 0.3, 0.3],
    ));
    let session = dir.join("one.json");
    cutaway::session::save(&session, &one).unwrap();
    drop_files(
        &mut h,
        vec![folder.join("right_block.stl"), session.clone()],
    );
    // The folder added is unsaved work: opening the session over it asks first.
    assert!(
        h.state().unsaved_prompt.is_some(),
        "the session replaced unsaved work without asking"
    );
    apply(
        &mut h,
        Action::Unsaved(cutaway::gui::app::UnsavedAnswer::Discard),
    );
    settle(&mut h);
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(
        app.scene.models.len(),
        1,
        "the dropped session did not open"
    );
    assert_eq!(app.session_path.as_deref(), Some(session.as_path()));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn files_given_skip_the_recovery_prompt_and_an_undo_keeps_anaglyph_off() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("prompt");
    // An autosave left by a crash, and two meshes named on the command line.
    std::fs::write(dir.join("recovery-session.json"), "{}").unwrap();
    let folder = dir.join("blocks");
    std::fs::create_dir_all(&folder).unwrap();
    for (name, x) in [("a_block.obj", 0.0), ("b_block.obj", 20.0)] {
        let mesh =
            cutaway::gui::app::box_mesh(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 10.0, 10.0, 10.0));
        cutaway::io::write_mesh(&folder.join(name), &mesh).unwrap();
    }
    assert!(StartOptions::new(Vec::new()).offer_recovery);
    let mut start = StartOptions::new(vec![folder]);
    assert!(!start.offer_recovery, "files given, yet recovery offered");
    start.state_dir = dir.clone();
    let mut h = Harness::builder()
        .wgpu()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_max_steps(10_000)
        .with_step_dt(1.0 / 60.0)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start));
    settle(&mut h);
    assert!(h.state().pending_recovery.is_none());
    assert!(h.query_by_label("Restore the previous session?").is_none());
    assert_eq!(
        h.state().scene.models.len(),
        2,
        "{}",
        h.state().status.message
    );

    // Anaglyph on from the Rendering menu, an edit, anaglyph off, undo: the view stays plain.
    let toggle = |h: &mut Harness<'_, CutawayApp>| {
        h.get_by_label("Rendering").click();
        h.run_steps(2);
        h.get_by_label("Red/Blue Stereoscopic 3D").click();
        h.run_steps(2);
        h.key_press(egui::Key::Escape);
        h.run_steps(2);
    };
    toggle(&mut h);
    assert_eq!(
        h.state().scene.render.stereo,
        cutaway::scene::Stereo::Anaglyph
    );
    apply(&mut h, Action::RemoveModel(1));
    assert_eq!(h.state().scene.models.len(), 1);
    toggle(&mut h);
    assert_eq!(h.state().scene.render.stereo, cutaway::scene::Stereo::None);
    apply(&mut h, Action::Undo);
    assert_eq!(
        h.state().scene.models.len(),
        2,
        "the removal was not undone"
    );
    assert_eq!(
        h.state().scene.render.stereo,
        cutaway::scene::Stereo::None,
        "the undo turned anaglyph back on"
    );
    let plain = shot(&mut h, "anaglyph-off-after-undo");
    // No red/blue fringes: the view has no pixel whose green is far below both red and blue.
    let view = view_px(&h);
    let mut fringe = 0;
    for y in view.min.y as u32..view.max.y as u32 {
        for x in view.min.x as u32..view.max.x as u32 {
            let p = plain.get_pixel(x, y);
            if p[1] == 0 && (p[0] > 60 || p[2] > 60) {
                fringe += 1;
            }
        }
    }
    assert!(fringe < 50, "{fringe} anaglyph pixels after turning it off");
    let _ = std::fs::remove_dir_all(&dir);
}
