//! Property tests: random drag paths and edits through the editor never leave an invalid cutter.

mod editor_support;

use glam::DVec2;
use proptest::prelude::*;

use cutter::{CutKind, EditorEvent, EditorSettings, Key};
use editor_support::*;

/// Pointer steps of a handle drag: (dx, dy, shift held), in pixels.
type Walk = Vec<(f64, f64, bool)>;

/// A random gesture: an initial drag, then a handle drag along a random walk, then a few random
/// edits (codes 0..7, see `run`).
fn gesture() -> impl Strategy<Value = (DVec2, DVec2, Walk, Vec<u8>)> {
    (
        (540.0..740.0f64, 340.0..460.0f64),
        (-80.0..80.0f64, -80.0..80.0f64),
        prop::collection::vec((-12.0..16.0f64, -12.0..12.0f64, any::<bool>()), 5..60),
        prop::collection::vec(0u8..7, 0..6),
    )
        .prop_map(|((ax, ay), (bx, by), walk, edits)| {
            (
                DVec2::new(ax, ay),
                DVec2::new(ax + bx, ay + by),
                walk,
                edits,
            )
        })
}

fn run(
    scene: &Scene,
    kind: CutKind,
    smooth: bool,
    a: DVec2,
    b: DVec2,
    walk: &[(f64, f64, bool)],
    edits: &[u8],
) {
    run_with(scene, scene.settings(kind), smooth, a, b, walk, edits);
}

fn run_with(
    scene: &Scene,
    settings: EditorSettings,
    smooth: bool,
    a: DVec2,
    b: DVec2,
    walk: &[(f64, f64, bool)],
    edits: &[u8],
) {
    let mut editor = scene.editor(settings.with_spacing(12.0).with_smooth(smooth));
    feed(&mut editor, drag(a, b, 3));
    let Some(c) = editor.cutter() else {
        // A drag too short to make a cutter (fewer than 3 pixels): nothing to check.
        assert!((b - a).length() < 3.0 + 1e-9);
        return;
    };
    validate(c);
    let h = handle_px(&editor);
    let mut p = h;
    let mut events = vec![EditorEvent::press(h.x, h.y)];
    for &(dx, dy, shift) in walk {
        p += DVec2::new(dx, dy);
        events.push(EditorEvent::Move {
            x: p.x,
            y: p.y,
            shift,
            ctrl: false,
        });
    }
    events.push(EditorEvent::release(p.x, p.y));
    feed(&mut editor, events);
    let n = editor.cutter().unwrap().planes.len();
    for &e in edits {
        let c = editor.cutter().unwrap().clone();
        let i = (e as usize * 7) % c.planes.len();
        let px = editor
            .camera()
            .project(
                editor.viewport(),
                c.planes[i].front_top.lerp(c.planes[i].front_bottom, 0.3),
            )
            .unwrap();
        let event = match e {
            0 => EditorEvent::wheel(10.0, 10.0, 4.0, false),
            1 => EditorEvent::wheel(px.x, px.y, 3.0, false),
            2 => EditorEvent::wheel(px.x, px.y, 1.0, true),
            3 => EditorEvent::key(Key::Delete, px.x, px.y),
            4 => EditorEvent::wheel(10.0, 10.0, -2.0, false),
            5 => EditorEvent::alt_wheel(px.x, px.y, -3.0),
            _ => EditorEvent::press(px.x, px.y),
        };
        feed(&mut editor, [event, EditorEvent::release(px.x, px.y)]);
    }
    // Undo everything, then redo: every state on the way is valid.
    while editor.undo() {
        if let Some(c) = editor.cutter() {
            validate(c);
        }
    }
    assert!(editor.cutter().is_none());
    while editor.redo() {
        validate(editor.cutter().unwrap());
    }
    assert!(editor.cutter().unwrap().planes.len() >= 2.min(n));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn random_paths_on_sphere_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::sphere();
        run(&scene, CutKind::Curving, false, a, b, &walk, &edits);
    }

    #[test]
    fn random_paths_on_bumpy_surface_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::bumpy();
        run(&scene, CutKind::Curving, false, a, b, &walk, &edits);
    }

    #[test]
    fn random_wedges_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::slab();
        run(&scene, CutKind::Wedge, false, a, b, &walk, &edits);
    }

    #[test]
    fn random_deep_paths_along_the_view_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::sphere();
        run_with(&scene, scene.current_settings(CutKind::Curving), false, a, b, &walk, &edits);
    }

    #[test]
    fn random_deep_paths_along_the_normal_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::bumpy();
        let settings = scene
            .current_settings(CutKind::Curving)
            .with_direction(cutter::CutDirection::Normal);
        run_with(&scene, settings, false, a, b, &walk, &edits);
    }
}

proptest! {
    // Rounded and freeform: every move of every drag and every edit leaves a smooth cutter whose
    // subdivided surface the exact boolean takes (`validate` runs the exact check).
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn random_smooth_paths_on_sphere_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::sphere();
        run(&scene, CutKind::Curving, true, a, b, &walk, &edits);
    }

    #[test]
    fn random_smooth_paths_on_bumpy_surface_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::bumpy();
        run(&scene, CutKind::Curving, true, a, b, &walk, &edits);
    }

    #[test]
    fn random_smooth_wedges_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::slab();
        run(&scene, CutKind::Wedge, true, a, b, &walk, &edits);
    }

    #[test]
    fn random_smooth_deep_paths_keep_the_cutter_valid((a, b, walk, edits) in gesture()) {
        let scene = Scene::sphere();
        run_with(&scene, scene.current_settings(CutKind::Curving), true, a, b, &walk, &edits);
    }
}
