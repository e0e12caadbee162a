//! Sizes follow the target: the window driven headless (egui_kittest on the real wgpu renderer,
//! lavapipe without a GPU) at 1280×800 on the HuBMAP body (metres, 1.8 m tall) and on the knee
//! phantom (millimetres).
//!
//! - A cutter painted on a small structure of the body seen whole reaches far past it; the cut
//!   is made (not refused as "too far from the target"), and `cutaway render` of the session
//!   the window saves renders it.
//! - Zoomed to that structure, a new cutter's δ, first box and the scalpel's depth and opening
//!   come from the structure, a small fraction of it, not from the body.
//! - On the knee the same steps give millimetre lengths of the same proportions.
//!
//! Screenshots of each first cut go to the test's temporary folder (`CARGO_TARGET_TMPDIR`).
//! Skipped, with the reason printed, without a wgpu adapter; the body is read from
//! `CUTAWAY_ANATOMY` (default `../shared/anatomy`).

use csg::testkit::{Resource, skip};
use std::path::Path;

use crate::harness::{apply, harness, no_adapter, shot};
use crate::input::{anatomy, drag_steps as drag, settle, temp_dir};
use cutaway::cutting::cut_scene::PartKind;
use cutaway::gui::app::Action;
use cutaway::gui::bridge::shown_cut;
use cutaway::gui::viewport::view_menu::ViewCommand;
use cutaway::gui::{CutawayApp, Mode};
use cutter::EditorSettings;
use egui_kittest::Harness;

/// The index of the model loaded from a file whose name contains `name`.
fn model(h: &Harness<'_, CutawayApp>, name: &str) -> usize {
    let models = &h.state().scene.models;
    models
        .iter()
        .position(|m| m.model.source.to_string_lossy().contains(name))
        .unwrap_or_else(|| {
            let names: Vec<_> = models.iter().map(|m| m.model.source.display()).collect();
            panic!("no model from a file named like {name}: {names:?}")
        })
}

/// A point in the window (egui points) of world point `p`.
fn to_screen(h: &Harness<'_, CutawayApp>, p: glam::DVec3) -> egui::Pos2 {
    let app = h.state();
    let px = app
        .scene
        .camera
        .project(app.viewport.size_px, p)
        .expect("in front of the camera");
    let ppp = h.ctx.pixels_per_point();
    app.viewport.rect.min + egui::vec2(px.x as f32 / ppp, px.y as f32 / ppp)
}

/// Paints a new cutter on the selected model `target` in Edit mode as a user does: a 70-point
/// drag across its centre, then the leading plane's handle dragged `length` points down.
/// Returns the new cutter's index.
fn paint_cutter(h: &mut Harness<'_, CutawayApp>, target: usize, length: f32) -> usize {
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, Action::NewCutter);
    h.state_mut().selected_model = Some(target);
    let before = h.state().scene.cutters.len();
    let centre = to_screen(h, h.state().scene.models[target].model.mesh.bbox().center());
    let (a, b) = (
        centre + egui::vec2(-35.0, 0.0),
        centre + egui::vec2(35.0, 0.0),
    );
    drag(h, a, b, 5);
    assert_eq!(
        h.state().scene.cutters.len(),
        before + 1,
        "no cutter: {}",
        h.state().status.message
    );
    let lead = h.state().scene.cutters[before]
        .cutter
        .planes
        .last()
        .unwrap()
        .corners();
    let handle = to_screen(h, (lead[0] + lead[3]) * 0.5);
    drag(h, handle, handle + egui::vec2(0.0, length), 30);
    assert!(
        h.state().scene.cutters[before].cutter.planes.len() > 2,
        "the roller did not move"
    );
    before
}

/// The scene cut in Camera mode: every cutter cuts (no note says why one could not) and the
/// cutter `k` made walls on its target.
fn assert_cut(h: &mut Harness<'_, CutawayApp>, k: usize) {
    apply(h, Action::SetMode(Mode::Camera));
    settle(h);
    let cut = shown_cut(h.state()).expect("Camera mode draws the cut");
    assert!(
        cut.notes.is_empty(),
        "a cutter was refused: {:?}",
        cut.notes
    );
    let target = h.state().scene.cutters[k].target;
    assert!(
        cut.parts
            .iter()
            .any(|p| p.kind == PartKind::Wall && p.model == target),
        "no walls on the target"
    );
}

/// The δ a new cutter on the active editor's target started with.
fn editor_delta(h: &Harness<'_, CutawayApp>) -> f64 {
    h.state()
        .viewport
        .editor
        .editor_settings()
        .expect("an active editor")
        .delta
}

#[test]
fn a_small_hubmap_structure_is_cut_with_its_own_sizes_and_its_session_renders() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let Some(body) = anatomy("hubmap_vhf_body") else {
        return;
    };
    let dir = temp_dir("scale-hubmap");
    let mut h = harness(&dir, vec![body]);
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let scene_box = h.state().scene.bbox();
    let fov = h.state().scene.camera.fov_y_deg;
    // The coccyx: 30 × 30 × 40 mm in a body 1.67 m tall. The skin is hidden to see it.
    let skin = model(&h, "VH_F_skin");
    let coccyx = model(&h, "VH_F_coccyx");
    h.state_mut().scene.models[skin].visible = false;
    let size = h.state().scene.models[coccyx].model.mesh.bbox();

    // Zoomed to the coccyx, a new cutter and the scalpel are sized from it.
    h.state_mut().selected_model = Some(coccyx);
    apply(&mut h, Action::View(ViewCommand::ZoomToSelection));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let near = paint_cutter(&mut h, coccyx, 90.0);
    let delta = editor_delta(&h);
    let framed = EditorSettings::delta_for_scene(&size, fov);
    let whole = EditorSettings::delta_for_scene(&scene_box, fov);
    // Zoom to selection leaves a margin, so the camera is a little farther than framing.
    assert!(
        delta >= framed * (1.0 - 1e-9) && delta < 1.5 * framed,
        "δ {delta} m, the coccyx framed gives {framed} m"
    );
    assert!(
        delta < whole / 10.0,
        "δ {delta} m is the body's ({whole} m)"
    );
    // Nothing else visible lies behind it: the cutter goes half the coccyx's thickness in (the
    // default depth), a share of the coccyx, not of the body.
    let first = h.state().scene.cutters[near].cutter.planes[0];
    let extent = size.size().max_element();
    assert!(
        first.depth() < 0.6 * extent && first.depth() > 1e-2 * extent,
        "first box {} m deep on a {extent} m structure",
        first.depth()
    );
    assert_cut(&mut h, near);
    shot(&mut h, "scale-hubmap-coccyx-first-cut");

    apply(&mut h, Action::SetMode(Mode::Scalpel));
    h.run_steps(2);
    let scalpel = h.state().viewport.scalpel.settings;
    let diagonal = size.diagonal();
    assert!(
        (scalpel.depth - 0.03 * diagonal).abs() < 1e-9,
        "scalpel depth {} m on a {diagonal} m structure",
        scalpel.depth
    );
    assert!((scalpel.opening - 0.02 * diagonal).abs() < 1e-9);

    // Seen with the whole body, a point is 2.4 mm: a stroke 200 points long reaches far past
    // the structure (beyond the lattice of its own index), and is cut.
    h.state_mut().scene.models[skin].visible = true;
    apply(&mut h, Action::View(ViewCommand::ZoomToFit));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let far = paint_cutter(&mut h, coccyx, 200.0);
    let planes = &h.state().scene.cutters[far].cutter.planes;
    let reach = planes
        .iter()
        .flat_map(|p| p.corners())
        .map(|c| (c - size.center()).abs().max_element())
        .fold(0.0, f64::max);
    assert!(
        reach > 4.0 * size.size().max_element(),
        "the stroke should reach far past the coccyx ({reach} m)"
    );
    assert_cut(&mut h, far);

    // The saved session renders: no cutter is refused by `cutaway render` either.
    let session = dir.join("coccyx.json");
    apply(&mut h, Action::SaveSessionTo(session.clone()));
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let png = dir.join("coccyx.png");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cutaway"))
        .arg("render")
        .arg(&session)
        .arg("--out")
        .arg(&png)
        .args(["--width", "320", "--height", "200", "--json"])
        .output()
        .expect("run cutaway render");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "cutaway render failed: {stderr}");
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("render --json");
    let cutters = json["cutters"].as_array().expect("cutters");
    assert_eq!(cutters.len(), 2);
    assert!(cutters.iter().all(|c| c["exact"] == true), "{json}");
    assert!(png.is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn on_the_knee_in_millimetres_the_same_steps_give_proportionate_lengths() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let knee = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/knee");
    let dir = temp_dir("knee");
    let mut h = harness(&dir, vec![knee]);
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let scene_box = h.state().scene.bbox();
    let fov = h.state().scene.camera.fov_y_deg;
    let patella = model(&h, "patella");
    let size = h.state().scene.models[patella].model.mesh.bbox();
    // Only the patella shows (the others cover it from the camera).
    for (m, model) in h.state_mut().scene.models.iter_mut().enumerate() {
        model.visible = m == patella;
    }
    // Zoomed to the patella: its own δ, in the same proportion as the HuBMAP coccyx's.
    h.state_mut().selected_model = Some(patella);
    apply(&mut h, Action::View(ViewCommand::ZoomToSelection));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let near = paint_cutter(&mut h, patella, 90.0);
    let delta = editor_delta(&h);
    let framed = EditorSettings::delta_for_scene(&size, fov);
    assert!(
        delta >= framed * (1.0 - 1e-9) && delta < 1.5 * framed,
        "δ {delta} mm, the patella framed gives {framed} mm"
    );
    let first = h.state().scene.cutters[near].cutter.planes[0];
    let extent = size.size().max_element();
    assert!(
        first.depth() < 0.6 * extent && first.depth() > 1e-2 * extent,
        "first box {} mm deep on a {extent} mm patella",
        first.depth()
    );
    assert_cut(&mut h, near);
    shot(&mut h, "scale-knee-patella-first-cut");
    apply(&mut h, Action::SetMode(Mode::Scalpel));
    h.run_steps(2);
    let depth = h.state().viewport.scalpel.settings.depth;
    assert!(
        (depth - 0.03 * size.diagonal()).abs() < 1e-9,
        "scalpel depth {depth} mm on the patella"
    );
    // Seen whole, a cutter on the patella keeps the view's step: the knee's δ as before.
    for model in &mut h.state_mut().scene.models {
        model.visible = true;
    }
    apply(&mut h, Action::View(ViewCommand::ZoomToFit));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let whole_view = paint_cutter(&mut h, patella, 90.0);
    let whole = EditorSettings::delta_for_scene(&scene_box, fov);
    let delta = editor_delta(&h);
    assert!(
        delta > 0.5 * whole && delta < 2.0 * whole,
        "δ {delta} mm, the knee's is {whole} mm"
    );
    assert_cut(&mut h, whole_view);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn on_the_default_head_atlas_a_small_structure_gets_its_own_lengths() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let dir = temp_dir("head");
    let mut h = harness(&dir, Vec::new());
    settle(&mut h);
    assert!(!h.state().status.is_error, "{}", h.state().status.message);
    let fov = h.state().scene.camera.fov_y_deg;
    // The scene opens with the head's lengths, in millimetres.
    let head = h.state().scene.bbox().diagonal();
    let depth = h.state().viewport.scalpel.settings.depth;
    assert!(
        (depth - 0.03 * head).abs() < 1e-9,
        "scalpel depth {depth} mm"
    );
    // The smallest structure of some size (a deep nucleus, a nerve), alone in view.
    let models = &h.state().scene.models;
    let small = (0..models.len())
        .filter(|&m| models[m].model.mesh.triangle_count() >= 500)
        .min_by(|&a, &b| {
            let d = |m: usize| models[m].model.mesh.bbox().diagonal();
            d(a).total_cmp(&d(b))
        })
        .expect("a structure");
    let size = models[small].model.mesh.bbox();
    let name = models[small].model.name.clone();
    assert!(size.diagonal() < 0.3 * head, "{name} is not small");
    for (m, model) in h.state_mut().scene.models.iter_mut().enumerate() {
        model.visible = m == small;
    }
    h.state_mut().selected_model = Some(small);
    apply(&mut h, Action::View(ViewCommand::ZoomToSelection));
    apply(&mut h, Action::SetMode(Mode::Edit));
    let k = paint_cutter(&mut h, small, 90.0);
    let delta = editor_delta(&h);
    let framed = EditorSettings::delta_for_scene(&size, fov);
    assert!(
        delta >= framed * (1.0 - 1e-9) && delta < 1.5 * framed,
        "δ {delta} mm, {name} framed gives {framed} mm"
    );
    assert_cut(&mut h, k);
    shot(&mut h, "scale-head-small-structure-first-cut");
    apply(&mut h, Action::SetMode(Mode::Scalpel));
    h.run_steps(2);
    let depth = h.state().viewport.scalpel.settings.depth;
    assert!(
        (depth - 0.03 * size.diagonal()).abs() < 1e-9,
        "scalpel depth {depth} mm on {name}"
    );
    println!(
        "{name}: {:.1} mm across; δ {delta:.4} mm; scalpel depth {depth:.2} mm",
        size.diagonal()
    );
    // Nothing selected, every structure shown: the blade has the head's lengths again (the
    // scene's box is that of the models shown).
    for model in &mut h.state_mut().scene.models {
        model.visible = true;
    }
    h.state_mut().selected_model = None;
    h.run_steps(2);
    let depth = h.state().viewport.scalpel.settings.depth;
    assert!(
        (depth - 0.03 * head).abs() < 1e-9,
        "scalpel depth {depth} mm"
    );
    // A stroke that starts on the structure (alone in view again) selects it and is cut with
    // its lengths.
    for (m, model) in h.state_mut().scene.models.iter_mut().enumerate() {
        model.visible = m == small;
    }
    h.run_steps(2);
    let centre = to_screen(&h, size.center());
    drag(
        &mut h,
        centre + egui::vec2(-30.0, 0.0),
        centre + egui::vec2(30.0, 0.0),
        10,
    );
    assert_eq!(h.state().selected_model, Some(small));
    // Sized from the structure as it now is: the incision moved its box by a hair, the head's
    // lengths would be 20 times these.
    let depth = h.state().viewport.scalpel.settings.depth;
    assert!(
        (depth / (0.03 * size.diagonal()) - 1.0).abs() < 0.02,
        "scalpel depth {depth} mm after a stroke on {name}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
