//! The window builds the pick trees of a loaded scene on a worker as soon as the scene is there,
//! so the first press on a model after a load finds its tree (or waits for that worker) instead
//! of building one on the UI thread.

use super::{CutawayApp, StartOptions};
use crate::gui::app::{Action, Mode};

/// One primary press and release at the centre of the view, nothing else.
fn press_centre(h: &mut egui_kittest::Harness<'_, CutawayApp>) {
    let centre = h.state().viewport.rect.center();
    h.hover_at(centre);
    h.step();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: centre,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
        h.step();
    }
    h.run_steps(2);
}

#[test]
fn the_first_press_after_a_load_builds_no_pick_tree_on_the_ui_thread() {
    let dir = std::env::temp_dir().join(format!("cutaway-first-press-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let sphere = dir.join("sphere.ply");
    crate::io::write_mesh(&sphere, &csg::testkit::geodesic_sphere(60, 50.0)).unwrap();
    let start = StartOptions {
        paths: vec![sphere],
        state_dir: dir.join("state"),
        offer_recovery: false,
    };
    let mut h = crate::gui::test_window::open(start, 1024.0, 800.0);
    assert_eq!(
        h.state().scene.models.len(),
        1,
        "{}",
        h.state().status.message
    );
    // In Edit mode with nothing selected, the first press picks the model under the pointer as
    // the target: the first pick of the session.
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, Action::SelectModel(None));
    h.state_mut().apply(&ctx, Action::SetMode(Mode::Edit));
    h.run_steps(2);
    press_centre(&mut h);
    let app = h.state();
    assert_eq!(
        app.selected_model,
        Some(0),
        "the sphere under the centre is not selected ({})",
        app.status.message
    );
    assert_eq!(
        app.viewport.picks.built_by_caller(),
        0,
        "the first press built a pick tree on the UI thread"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
