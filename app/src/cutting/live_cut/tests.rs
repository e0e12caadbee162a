//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::cutting::cut_scene::PartKind;
use crate::test_support::scene_with_cube_cut;

/// Everything the live cut draws as one mesh: the parts, and the kept deltas composed.
fn drawn(r: &LiveResult) -> Mesh {
    let mut closed = Mesh::default();
    for p in &r.geometry.parts {
        closed.append(&p.mesh);
    }
    for d in &r.deltas {
        closed.append(&d.compose());
    }
    closed
}

#[test]
fn a_live_request_produces_the_normal_cut_off_the_calling_thread() {
    // Transparency only in the scene: the live cut still shows kept part, walls and contour.
    let views = CutterViews {
        cut: false,
        transparency: Some(0.3),
        ribbons: None,
        slices: None,
    };
    let scene = scene_with_cube_cut(views);
    let mut live = LiveCut::default();
    assert!(live.request(&scene, None));
    assert!(!live.request(&scene, None), "the same state is cut once");
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    let shown = live.shown().unwrap();
    let g = &shown.geometry;
    assert_eq!(g.replaced, vec![true]);
    assert!(g.parts.iter().any(|p| p.kind == PartKind::Wall));
    assert!(g.parts.iter().all(|p| p.kind != PartKind::Removed));
    assert_eq!(g.contours.len(), 1);
    assert_eq!(shown.deltas.len(), 1, "the kept part is a delta");
    let closed = drawn(shown);
    assert!((closed.volume() - 7.0).abs() < 1e-9, "{}", closed.volume());
}

#[test]
fn stale_requests_are_dropped_and_the_newest_wins() {
    let mut scene = scene_with_cube_cut(CutterViews::default());
    let mut live = LiveCut::default();
    // Many states in a row, faster than the worker cuts: the newest is the one shown last.
    let mut last_x = 0.0;
    for k in 0..40 {
        let x = 1.0 + 0.01 * k as f64;
        scene.cutters[0].cutter.planes =
            crate::test_support::box_cutter(x, 3.0, -1.0, 1.0, 1.0, 3.0);
        live.request(&scene, None);
        last_x = x;
    }
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    assert_eq!(live.shown().unwrap().key, LiveKey::of(&live_scene(&scene)));
    // Every request was either cut (in order, so all arrived before the newest) or dropped.
    assert_eq!(live.finished + live.dropped(), 40);
    // The newest state's cut: the corner box from x = last_x removes (2 - x) · 1 · 1.
    let closed = drawn(live.shown().unwrap());
    let expected = 8.0 - (2.0 - last_x);
    assert!(
        (closed.volume() - expected).abs() < 1e-9,
        "{} vs {expected}",
        closed.volume()
    );
}

/// Waits until the worker's caches read `want` (the worker updates them after a request, or when
/// it wakes to forget them).
fn census_becomes(live: &LiveCut, want: impl Fn(&LiveCensus) -> bool) -> LiveCensus {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let census = live.census();
        if want(&census) || Instant::now() > deadline {
            return census;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn the_worker_keeps_an_index_only_while_its_cutter_changes_and_forgets_all_when_cleared() {
    let mut scene = crate::test_support::cubes_each_cut(3, 1);
    let mut live = LiveCut::default();
    assert!(live.request(&scene, None));
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    let census = live.census();
    assert_eq!(census.model_cuts, 3, "{census:?}");
    assert_eq!(census.cuts.indexes, 3, "every model was cut: {census:?}");
    // A drag on model 1's cutter: only its index is kept, the others' cuts stay.
    for step in 1..=3 {
        scene.cutters[1].cutter.planes =
            crate::test_support::box_cutter(11.0 + 0.1 * step as f64, 13.0, -1.0, 1.0, 1.0, 3.0);
        assert!(live.request(&scene, None));
        assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
        assert_eq!(live.shown().unwrap().deltas.len(), 3);
        let census = live.census();
        assert_eq!(census.model_cuts, 3, "step {step}: {census:?}");
        assert_eq!(census.cuts.indexes, 1, "step {step}: {census:?}");
        assert_eq!(census.face_tables, 1, "step {step}: {census:?}");
    }
    // Leaving Edit mode: the worker drops everything.
    live.clear();
    let census = census_becomes(&live, |c| *c == LiveCensus::default());
    assert_eq!(census, LiveCensus::default());
    // Coming back cuts again from scratch.
    assert!(live.request(&scene, None));
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    assert_eq!(live.census().model_cuts, 3);
}

#[test]
fn a_cut_model_turned_wireframe_and_back_is_cut_again_for_how_it_is_drawn() {
    let mut scene = crate::test_support::cubes_each_cut(2, 1);
    let mut live = LiveCut::default();
    assert!(live.request(&scene, None));
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    assert_eq!(live.shown().unwrap().deltas.len(), 2);
    // A wireframe is drawn from whole cut parts: the style is part of the state.
    scene.models[1].style = crate::scene::ModelStyle::Wireframe;
    assert!(live.request(&scene, None), "the style change was not cut");
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    let shown = live.shown().unwrap();
    assert_eq!(shown.deltas.len(), 1, "the wireframe model is not a delta");
    assert!(
        shown
            .geometry
            .parts
            .iter()
            .any(|p| p.model == 1 && p.kind == PartKind::Kept),
        "the wireframe model's kept part is drawn whole"
    );
    // Back to solid: a delta again, and the worker no longer holds the whole-part cut.
    scene.models[1].style = crate::scene::ModelStyle::Solid;
    assert!(live.request(&scene, None), "the style change was not cut");
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    assert_eq!(live.shown().unwrap().deltas.len(), 2);
    let census = live.census();
    assert_eq!(census.cuts.previews, 0, "{census:?}");
    assert_eq!(census.model_cuts, 2, "{census:?}");
}
