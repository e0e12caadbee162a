//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::cutting::cut_scene::PartKind;
use crate::cutting::cut_scene::tests::scene_with_cube_cut;

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
            crate::cutting::cut_scene::tests::box_cutter(x, 3.0, -1.0, 1.0, 1.0, 3.0);
        live.request(&scene, None);
        last_x = x;
    }
    assert!(live.wait(Duration::from_secs(60)), "no live cut arrived");
    assert_eq!(
        live.shown().unwrap().key,
        PreviewKey::of(&live_scene(&scene))
    );
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
