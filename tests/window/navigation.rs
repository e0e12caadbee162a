//! Navigating the window the way a radiologist does, driven headless by egui_kittest on the real
//! wgpu renderer (lavapipe without a GPU): orbit, pan and zoom with the same buttons in every
//! mode, a structure deep in the list found by double-clicking it in the view (the list scrolls
//! to it) and framed with "." (zoom to selection), and the window at 1600×1000 with the panel
//! widened. Screenshots go to the test's temporary folder (`CARGO_TARGET_TMPDIR`).
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with
//! Mesa's lavapipe installed); the real-data test reads `CUTAWAY_ANATOMY` (default
//! `../shared/anatomy`) and runs on the default scene without it.

use crate::harness::{apply, harness, harness_sized, no_adapter, shot};
use crate::input::{anatomy, click_mode, count_colour, drag, settle, temp_dir, view_px, wheel_at};
use csg::testkit::{Resource, skip};
use cutaway::gui::app::Action;
use cutaway::gui::{CutawayApp, Mode};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::DVec3;

/// Double-clicks at `at` (points) with real frame times between the clicks.
fn double_click(h: &mut Harness<'_, CutawayApp>, at: egui::Pos2) {
    h.hover_at(at);
    h.step();
    for pressed in [true, false, true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
    }
    h.step();
    h.run_steps(3);
}

#[test]
fn a_double_click_on_a_deep_structure_scrolls_the_list_to_it_and_zoom_to_selection_frames_it() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("reveal");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    // The skin hidden, an eyeball (the last group of the list, far below its first rows) is the
    // front-most structure at its own centre in the anterior view.
    apply(&mut h, Action::SelectModel(None));
    h.state_mut().scene.models[0].visible = false;
    let app = h.state();
    let (eye, name) = app
        .scene
        .models
        .iter()
        .enumerate()
        .filter(|(_, m)| m.model.name.contains("eyeball"))
        .map(|(i, m)| (i, m.model.name.clone()))
        .next_back()
        .expect("an eyeball in the default scene");
    let centre = app.scene.models[eye].model.mesh.bbox().center();
    let px = app
        .scene
        .camera
        .project(app.viewport.size_px, centre)
        .expect("in view");
    let ppp = h.ctx.pixels_per_point();
    let at = app.viewport.rect.min + egui::vec2(px.x as f32 / ppp, px.y as f32 / ppp);
    let list_bottom = app.viewport.rect.center().y;
    let row = h.get_by_label(&name).rect();
    assert!(
        row.min.y > list_bottom,
        "{name}'s row {row:?} is already in the list's first rows"
    );
    h.run_steps(40);
    double_click(&mut h, at);
    assert_eq!(
        h.state().selected_model,
        Some(eye),
        "the double-click did not select {name} ({})",
        h.state().status.message
    );
    // The list opened its group and scrolled: the row is in the list, above the properties.
    h.run_steps(20);
    // (The name is also the properties' heading, below the list.)
    let row = h
        .query_all_by_label(&name)
        .map(|n| n.rect())
        .min_by(|a, b| a.min.y.total_cmp(&b.min.y))
        .expect("the row");
    let properties = h.get_by_label("Opacity").rect();
    assert!(
        row.min.y > 150.0 && row.max.y < properties.min.y,
        "{name}'s row {row:?} is not in view above the properties at {properties:?}"
    );
    shot(&mut h, "deep-structure-revealed-in-list");
    // "." frames the selection: the eyeball fills the view's middle, whole.
    let before = h.state().scene.camera;
    h.hover_at(h.state().viewport.rect.center());
    h.key_press(egui::Key::Period);
    h.run_steps(2);
    let app = h.state();
    let camera = app.scene.camera;
    assert!(
        (camera.target - centre).length() < 1e-6,
        "not centred on {name}"
    );
    assert!(camera.distance() < before.distance() * 0.5, "not zoomed in");
    assert!((camera.forward() - before.forward()).length() < 1e-9);
    let bbox = app.scene.models[eye].model.mesh.bbox();
    let vp = app.viewport.size_px;
    for k in 0..8 {
        let corner = DVec3::new(
            if k & 1 == 0 { bbox.min.x } else { bbox.max.x },
            if k & 2 == 0 { bbox.min.y } else { bbox.max.y },
            if k & 4 == 0 { bbox.min.z } else { bbox.max.z },
        );
        let p = camera.project(vp, corner).expect("in front");
        assert!(
            p.x >= 0.0 && p.y >= 0.0 && p.x <= vp.x && p.y <= vp.y,
            "{name} cut off by the frame: {p:?} in {vp:?}"
        );
    }
    shot(&mut h, "zoom-to-selection");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn at_1600_by_1000_the_view_grows_and_the_marker_and_status_stay_in_place() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("large");
    let mut paths = Vec::new();
    if let Some(brain) = anatomy("head_brain_spl_atlas") {
        paths.push(brain);
    }
    let mut h = harness_sized(&dir, paths.clone(), egui::vec2(1600.0, 1000.0));
    settle(&mut h);
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    // The panels (models left, tools right) keep their width: the view takes the extra room.
    let view = app.viewport.rect;
    let panels = app.layout.models.width() + app.layout.tools.width();
    assert!(
        panels < 600.0 && view.width() > 1600.0 - panels - 40.0 && view.height() > 850.0,
        "the view did not grow: {view:?} beside panels {panels} wide"
    );
    let image = shot(
        &mut h,
        if paths.is_empty() {
            "large-default"
        } else {
            "large-brain-folder"
        },
    );
    // The marker is in the view's lower-left corner at this size too.
    let view = view_px(&h);
    let corner = egui::Rect::from_min_size(
        egui::pos2(view.min.x, view.max.y - 120.0),
        egui::vec2(120.0, 120.0),
    );
    assert!(
        count_colour(&image, corner, [230, 70, 60]) >= 15,
        "no marker in the corner"
    );
    // The status line sits under the view.
    let message = h.state().status.message.clone();
    let label = h.get_by_label(&message).rect();
    assert!(
        label.min.y >= h.state().viewport.rect.max.y - 0.5 && label.max.y <= 1000.0,
        "the status text {label:?} is not under the view"
    );
    // The side panel is resizable: dragging its edge widens the list, the view gives way.
    let before = h.state().viewport.rect;
    let edge = egui::pos2(before.min.x - 1.0, 500.0);
    drag(&mut h, edge, edge + egui::vec2(120.0, 0.0));
    h.run_steps(3);
    let after = h.state().viewport.rect;
    assert!(
        after.min.x > before.min.x + 80.0,
        "the panel did not widen: view {before:?} → {after:?}"
    );
    shot(&mut h, "large-panel-widened");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Presses `button` at `a`, moves in four steps and releases at `b` (points).
fn button_drag(
    h: &mut Harness<'_, CutawayApp>,
    button: egui::PointerButton,
    a: egui::Pos2,
    b: egui::Pos2,
) {
    h.hover_at(a);
    h.step();
    h.event(egui::Event::PointerButton {
        pos: a,
        button,
        pressed: true,
        modifiers: Default::default(),
    });
    h.step();
    for k in 1..=4 {
        h.hover_at(a + (b - a) * (k as f32 / 4.0));
        h.step();
    }
    h.event(egui::Event::PointerButton {
        pos: b,
        button,
        pressed: false,
        modifiers: Default::default(),
    });
    h.step();
    h.run_steps(2);
}

#[test]
fn right_drag_orbits_middle_drag_pans_and_the_wheel_zooms_in_every_mode() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("every-mode");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    let c = h.state().viewport.rect.center();
    for mode in [Mode::Camera, Mode::Edit, Mode::Preview, Mode::Scalpel] {
        click_mode(&mut h, mode);
        h.run_steps(30);
        let before = h.state().scene.camera;
        button_drag(
            &mut h,
            egui::PointerButton::Secondary,
            c,
            c + egui::vec2(80.0, 10.0),
        );
        let orbited = h.state().scene.camera;
        assert!(
            (orbited.eye - before.eye).length() > 1.0
                && (orbited.target - before.target).length() < 1e-6,
            "{mode:?}: right-drag did not orbit"
        );
        button_drag(
            &mut h,
            egui::PointerButton::Middle,
            c,
            c + egui::vec2(60.0, -30.0),
        );
        let panned = h.state().scene.camera;
        assert!(
            (panned.target - orbited.target).length() > 1.0
                && (panned.distance() - orbited.distance()).abs() < 1e-6,
            "{mode:?}: middle-drag did not pan"
        );
        // The wheel over empty background, away from any cutter.
        let corner = h.state().viewport.rect.right_top() + egui::vec2(-60.0, 60.0);
        wheel_at(&mut h, corner, 2.0);
        assert!(
            h.state().scene.camera.distance() < panned.distance() * 0.95,
            "{mode:?}: the wheel did not zoom"
        );
        let app = h.state();
        assert!(
            app.scene.cutters.is_empty(),
            "{mode:?}: navigating made a cutter"
        );
        assert!(!app.status.is_error, "{mode:?}: {}", app.status.message);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
