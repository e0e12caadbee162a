//! The Initialization tab's Smoothness slider in the window: it changes the edited smooth
//! cutter's subdivision levels, so the surface it cuts with changes, as one undo step.

use super::{CutawayApp, StartOptions};
use crate::gui::app::Action;
use egui_kittest::kittest::Queryable;

/// The surface the scene's first cutter cuts with, in triangles.
fn cutter_triangles(h: &egui_kittest::Harness<'_, CutawayApp>) -> usize {
    crate::cutting::cut_parts::cutter_surface(&h.state().scene.cutters[0].cutter).triangle_count()
}

#[test]
fn the_smoothness_slider_changes_the_edited_cutters_surface_and_undoes() {
    let dir = std::env::temp_dir().join(format!("cutaway-smoothness-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let sphere = dir.join("sphere.ply");
    crate::io::write_mesh(&sphere, &csg::testkit::geodesic_sphere(30, 50.0)).unwrap();
    let start = StartOptions {
        paths: vec![sphere],
        state_dir: dir.join("state"),
        offer_recovery: false,
    };
    let mut h = crate::gui::test_window::open(start, 1280.0, 800.0);
    assert_eq!(
        h.state().scene.models.len(),
        1,
        "{}",
        h.state().status.message
    );
    // A smooth cutter over the sphere's top, with the default levels, opened for editing.
    h.state_mut()
        .scene
        .cutters
        .push(crate::scene::SceneCutter::new(
            0,
            cutter::Cutter {
                kind: cutter::CutKind::Straight,
                smooth: true,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: crate::test_support::box_cutter(-20.0, 20.0, -10.0, 10.0, 35.0, 60.0),
            },
        ));
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, Action::EditCutter(0));
    crate::gui::test_window::settle(&mut h);
    assert_eq!(
        h.state().viewport.editor.active_cutter(),
        Some(0),
        "{}",
        h.state().status.message
    );
    let before = cutter_triangles(&h);
    let undo_before = h.state().history.undo_label().map(str::to_owned);

    // The slider shows for a smooth cutter; moving it to 3 re-subdivides the cutter.
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "Smoothness")
        .set_value_accesskit(3.0);
    h.run_steps(3);
    let app = h.state();
    assert_eq!(
        app.scene.cutters[0].cutter.levels, 3,
        "{}",
        app.status.message
    );
    assert_eq!(app.cutter_init.levels, 3);
    let after = cutter_triangles(&h);
    assert!(after > before, "{before} → {after} triangles");
    assert_eq!(h.state().history.undo_label(), Some("smoothing change"));

    // Undo brings the cutter's levels and surface back.
    h.state_mut().apply(&ctx, Action::Undo);
    h.run_steps(2);
    assert_eq!(
        h.state().scene.cutters[0].cutter.levels,
        cutter::subdivision::DEFAULT_LEVELS
    );
    assert_eq!(cutter_triangles(&h), before);
    assert_eq!(
        h.state().history.undo_label().map(str::to_owned),
        undo_before
    );
}
