//! Gesture replays through the cutter editor (thesis 3.3): every cut type and edit, with the
//! validator after every edit.

mod editor_support;

use glam::{DVec2, DVec3};

use cutter::{CutKind, Editor, EditorEvent, Key};
use editor_support::*;

/// Initialises a cutter with a 60-pixel upward drag at `at` (so it extends to screen-right).
fn init(editor: &mut Editor, at: DVec2) {
    feed(editor, drag(at, at + DVec2::new(0.0, -60.0), 6));
    let c = editor.cutter().expect("initialisation made a cutter");
    assert_eq!(c.planes.len(), 2);
}

/// Largest front-edge-midpoint gap to the surface, in units of δ.
fn max_gap_in_delta(scene: &Scene, editor: &Editor) -> f64 {
    let c = editor.cutter().unwrap();
    c.planes.iter().map(|p| scene.distance(p.front_mid())).fold(0.0, f64::max) / editor.delta()
}

#[test]
fn s_path_on_sphere_sticks_to_surface() {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    init(&mut editor, DVec2::new(560.0, 430.0));
    let initial = editor.cutter().unwrap().clone();
    // The initial strip touches the sphere: its front edge is on or just above the surface.
    let gap0 = initial.planes.iter().map(|p| scene.distance(p.front_mid())).fold(0.0, f64::max);
    assert!(gap0 < 3.0 * editor.delta(), "initial gap {gap0}");
    extrude(&mut editor, &s_path(220.0, 60.0, 80), false);
    let c = editor.cutter().unwrap();
    eprintln!("planes {} delta {}", c.planes.len(), editor.delta());
    assert!(c.planes.len() >= 8, "a 220-pixel drag with ω = 20 makes many boxes: {}", c.planes.len());
    let gap = max_gap_in_delta(&scene, &editor);
    eprintln!("max gap {gap} δ");
    assert!(gap <= 3.0, "front edges must stay within 3δ of the sphere, got {gap}δ");
    // No front edge midpoint is buried inside the sphere.
    for p in &c.planes {
        assert!(p.front_mid().length() > 50.0 - 3.0 * editor.delta(), "{}", p.front_mid().length());
    }
    // The path really swings: midpoints move both up and down in z.
    let zs: Vec<f64> = c.path().iter().map(|p| p.z).collect();
    let (lo, hi) = zs.iter().fold((f64::MAX, f64::MIN), |(a, b), &z| (a.min(z), b.max(z)));
    assert!(hi - lo > 10.0, "S swing {lo}..{hi}");
}
