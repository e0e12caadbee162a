//! Painting in Edit mode shows the live cut under the cutter, and it goes when turned off.

use super::*;

#[test]
fn painting_in_edit_mode_shows_the_live_cut() {
    if let Some(reason) = no_adapter() {
        return skip(Resource::Gpu, reason);
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
        app.scene.models[target].model.name, shown.ms
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
    assert!(inputs.cut.is_none());
    let _ = std::fs::remove_dir_all(&dir);
}
