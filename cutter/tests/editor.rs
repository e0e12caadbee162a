//! Gesture replays through the cutter editor (thesis 3.3): every cut type and edit, with the
//! validator ([`editor_support::validate`]) after every event that changed the cutter.

mod editor_support;

use glam::{DVec2, DVec3};

use cutter::edits::intersecting_groups;
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
    c.planes
        .iter()
        .map(|p| scene.distance(p.front_mid()))
        .fold(0.0, f64::max)
        / editor.delta()
}

/// A pixel on plane `i`'s projected front edge, 30% of the way from front-top (away from the
/// vertex pick radius and from the leading plane's handle).
fn on_plane(editor: &Editor, i: usize) -> DVec2 {
    let p = editor.cutter().unwrap().planes[i];
    let a = editor
        .camera()
        .project(editor.viewport(), p.front_top)
        .unwrap();
    let d = editor
        .camera()
        .project(editor.viewport(), p.front_bottom)
        .unwrap();
    a.lerp(d, 0.3)
}

/// A cutter painted along an S on the sphere (used by several edit tests).
fn painted_sphere(scene: &Scene) -> Editor {
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    init(&mut editor, DVec2::new(620.0, 430.0));
    extrude(&mut editor, &s_path(220.0, 40.0, 80), false);
    editor
}

#[test]
fn s_path_on_sphere_sticks_to_surface() {
    let scene = Scene::sphere();
    let editor = painted_sphere(&scene);
    let c = editor.cutter().unwrap();
    assert!(
        c.planes.len() >= 8,
        "a 220-pixel drag with ω = 20 makes many boxes: {}",
        c.planes.len()
    );
    let gap = max_gap_in_delta(&scene, &editor);
    assert!(
        gap <= 3.0,
        "front edges must stay within 3δ of the sphere, got {gap}δ"
    );
    // No front edge midpoint is buried inside the sphere.
    for p in &c.planes {
        assert!(
            p.front_mid().length() > 50.0 - editor.delta(),
            "{}",
            p.front_mid().length()
        );
    }
    // The path really swings: midpoints move both up and down in z.
    let zs: Vec<f64> = c.path().iter().map(|p| p.z).collect();
    let (lo, hi) = zs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &z| (a.min(z), b.max(z)));
    assert!(hi - lo > 5.0, "S swing {lo}..{hi}");
    // The leading plane ends under the pointer (the roller follows the mouse).
    let end = editor
        .camera()
        .project(editor.viewport(), c.leading().front_mid())
        .unwrap();
    let mouse = DVec2::new(620.0, 400.0) + DVec2::new(220.0, 0.0);
    assert!(
        (end - mouse).length() < 25.0,
        "roller at {end}, mouse at {mouse}"
    );
}

#[test]
fn s_path_on_bumpy_surface_sticks_over_hills_and_valleys() {
    let scene = Scene::bumpy();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    init(&mut editor, DVec2::new(450.0, 430.0));
    extrude(&mut editor, &s_path(320.0, 15.0, 120), false);
    let c = editor.cutter().unwrap();
    assert!(c.planes.len() >= 10, "{} planes", c.planes.len());
    let gap = max_gap_in_delta(&scene, &editor);
    assert!(
        gap <= 3.0,
        "front edges must stay within 3δ of the bumpy top, got {gap}δ"
    );
    // Heights follow the hills: the path's z range spans most of the surface's relief.
    let zs: Vec<f64> = c.path().iter().map(|p| p.z).collect();
    let (lo, hi) = zs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &z| (a.min(z), b.max(z)));
    assert!(
        hi - lo > 3.0,
        "path heights {lo}..{hi} do not follow the relief"
    );
}

#[test]
fn shift_gives_a_straight_path() {
    let scene = Scene::slab();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    init(&mut editor, DVec2::new(450.0, 430.0));
    // The mouse wiggles ±30 px sideways; Shift keeps the path straight.
    let path: Vec<DVec2> = (1..=60)
        .map(|k| DVec2::new(4.0 * k as f64, 30.0 * (k as f64 * 0.4).sin()))
        .collect();
    extrude(&mut editor, &path, true);
    let c = editor.cutter().unwrap();
    assert!(c.planes.len() >= 6);
    let pts = c.path();
    let dir = (pts[pts.len() - 1] - pts[0]).normalize();
    for p in &pts {
        let off = (*p - pts[0]) - dir * (*p - pts[0]).dot(dir);
        assert!(
            off.length() < 0.05 * editor.delta(),
            "midpoint {p} off the line by {}",
            off.length()
        );
    }
    // Without Shift the same wiggle bends the path.
    let mut free = scene.editor(scene.settings(CutKind::Curving));
    init(&mut free, DVec2::new(450.0, 430.0));
    extrude(&mut free, &path, false);
    let pts = free.cutter().unwrap().path();
    let dir = (pts[pts.len() - 1] - pts[0]).normalize();
    let worst = pts
        .iter()
        .map(|p| ((*p - pts[0]) - dir * (*p - pts[0]).dot(dir)).length())
        .fold(0.0, f64::max);
    assert!(worst > 0.5, "free path should bend, max offset {worst}");
}

#[test]
fn straight_kind_is_shift_always_on() {
    let scene = Scene::slab();
    let mut editor = scene.editor(scene.settings(CutKind::Straight));
    init(&mut editor, DVec2::new(450.0, 430.0));
    extrude(&mut editor, &s_path(200.0, 30.0, 50), false);
    let pts = editor.cutter().unwrap().path();
    let dir = (pts[pts.len() - 1] - pts[0]).normalize();
    for p in &pts {
        assert!(((*p - pts[0]) - dir * (*p - pts[0]).dot(dir)).length() < 0.05 * editor.delta());
    }
}

#[test]
fn wedge_planes_share_the_axis() {
    let scene = Scene::slab();
    let mut editor = scene.editor(scene.settings(CutKind::Wedge).with_spacing(10.0));
    // The press is the pie's centre; drag out the radius.
    init(&mut editor, DVec2::new(640.0, 460.0));
    let h = handle_px(&editor);
    // Sweep the pointer around the centre, on past plane 1 (clockwise on screen).
    let centre = DVec2::new(640.0, 460.0);
    let r = (h - centre).length();
    let start = (h - centre).y.atan2((h - centre).x);
    let path: Vec<DVec2> = (1..=40)
        .map(|k| {
            let a = start + 1.8 * k as f64 / 40.0;
            centre + DVec2::new(a.cos(), a.sin()) * r - h
        })
        .collect();
    extrude(&mut editor, &path, false);
    let c = editor.cutter().unwrap();
    assert_eq!(c.kind, CutKind::Wedge);
    assert!(c.planes.len() >= 5, "{} planes", c.planes.len());
    for p in &c.planes {
        assert_eq!(p.front_top, c.planes[0].front_top);
        assert_eq!(p.back_top, c.planes[0].back_top);
    }
    let sweep = c.wedge_sweep().to_degrees();
    assert!(sweep > 60.0, "wedge swept only {sweep} degrees");
    let q = c.quad_mesh();
    assert!(
        q.faces.iter().any(|f| f.len() == 3),
        "prism fan has triangular front faces"
    );
}

#[test]
fn rounded_cutter_interpolates_original_vertices() {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.settings(CutKind::Curving).with_smooth(true));
    init(&mut editor, DVec2::new(620.0, 430.0));
    extrude(&mut editor, &s_path(150.0, 30.0, 40), false);
    let c = editor.cutter().unwrap();
    assert!(c.smooth);
    let boxes = c.quad_mesh();
    let smooth = c.display_mesh();
    smooth.check_closed().expect("smooth cutter stays closed");
    assert!(smooth.volume() > 0.0);
    // Two levels (16 quads per face), more where planes were inserted in a tight turn.
    assert!(smooth.faces.len() >= boxes.faces.len() * 16);
    c.validate().expect("the exact boolean takes it");
    for p in &boxes.positions {
        assert!(
            smooth.positions.contains(p),
            "original vertex {p} not interpolated"
        );
    }
    // It follows edits: deepen everything, the smooth mesh still holds the new vertices.
    feed(&mut editor, [EditorEvent::wheel(40.0, 40.0, 2.0, false)]);
    let c = editor.cutter().unwrap();
    let smooth = c.display_mesh();
    for p in &c.quad_mesh().positions {
        assert!(smooth.positions.contains(p));
    }
    // Turning smoothing off is one undoable step.
    assert!(editor.set_smooth(false));
    assert!(!editor.cutter().unwrap().smooth);
    assert!(editor.undo());
    assert!(editor.cutter().unwrap().smooth);
}

#[test]
fn depth_increase_on_a_tight_curve_resolves_plane_collisions() {
    let scene = Scene::sphere();
    let mut editor = painted_sphere(&scene);
    let before = editor.cutter().unwrap().clone();
    // Planes point at the sphere's centre 50 units down: 170 notches (2δ each, about 57 units)
    // push every plane past it, so without resolution neighbours would cross.
    let notches = 170.0;
    let naive: Vec<_> = before
        .planes
        .iter()
        .map(|p| p.with_depth(p.depth() + notches * 2.0 * editor.delta()))
        .collect();
    assert!(
        !intersecting_groups(&naive).is_empty(),
        "the test must force collisions"
    );
    feed(
        &mut editor,
        [EditorEvent::wheel(20.0, 20.0, notches, false)],
    );
    let c = editor.cutter().unwrap().clone();
    assert_ne!(c, before, "the depth edit must be applied");
    assert!(
        intersecting_groups(&c.planes).is_empty(),
        "planes still intersect"
    );
    for p in &c.planes {
        assert!(p.depth() > 50.0, "depth {}", p.depth());
    }
    // Resolution rotated planes about their front edges: front edges unchanged.
    for (a, b) in c.planes.iter().zip(&before.planes) {
        assert_eq!(a.front_top, b.front_top);
        assert_eq!(a.front_bottom, b.front_bottom);
    }
    // And shallower again.
    feed(&mut editor, [EditorEvent::wheel(20.0, 20.0, -5.0, false)]);
    assert!(editor.cutter().unwrap().planes[0].depth() < c.planes[0].depth());
}

#[test]
fn wheel_over_a_selected_plane_changes_only_its_depth() {
    let scene = Scene::sphere();
    let mut editor = painted_sphere(&scene);
    let before = editor.cutter().unwrap().clone();
    let px = on_plane(&editor, 3);
    feed(
        &mut editor,
        [
            EditorEvent::press(px.x, px.y),
            EditorEvent::release(px.x, px.y),
        ],
    );
    assert_eq!(editor.selected_plane(), Some(3));
    feed(&mut editor, [EditorEvent::wheel(px.x, px.y, 3.0, false)]);
    let c = editor.cutter().unwrap();
    for (i, (a, b)) in c.planes.iter().zip(&before.planes).enumerate() {
        if i == 3 {
            assert!((a.depth() - b.depth() - 6.0 * editor.delta()).abs() < 1e-9);
        } else {
            assert_eq!(a, b, "plane {i} must not change");
        }
    }
}

#[test]
fn ctrl_wheel_rotates_the_selected_plane_about_its_front_edge() {
    let scene = Scene::sphere();
    let mut editor = painted_sphere(&scene);
    let before = editor.cutter().unwrap().clone();
    let px = on_plane(&editor, 4);
    feed(
        &mut editor,
        [
            EditorEvent::press(px.x, px.y),
            EditorEvent::release(px.x, px.y),
        ],
    );
    feed(&mut editor, [EditorEvent::wheel(px.x, px.y, 2.0, true)]);
    let c = editor.cutter().unwrap();
    let (a, b) = (c.planes[4], before.planes[4]);
    assert_eq!(a.front_top, b.front_top);
    assert_eq!(a.front_bottom, b.front_bottom);
    let angle = a
        .back_direction()
        .angle_between(b.back_direction())
        .to_degrees();
    assert!((angle - 10.0).abs() < 1e-6, "rotated {angle} degrees");
    assert!(a.planarity_error() < 1e-9);
    for i in (0..c.planes.len()).filter(|&i| i != 4) {
        assert_eq!(c.planes[i], before.planes[i]);
    }
}

#[test]
fn dragging_a_front_vertex_moves_its_edge_in_the_plane_normal_to_it() {
    let scene = Scene::sphere();
    let mut editor = painted_sphere(&scene);
    let before = editor.cutter().unwrap().clone();
    let p = before.planes[2];
    let v = editor
        .camera()
        .project(editor.viewport(), p.front_top)
        .unwrap();
    feed(&mut editor, drag(v, v + DVec2::new(6.0, 8.0), 4));
    let c = editor.cutter().unwrap();
    let q = c.planes[2];
    let moved = q.front_top - p.front_top;
    assert!(
        moved.length() > 0.5,
        "the vertex must move, moved {}",
        moved.length()
    );
    let edge = (p.front_top - p.back_top).normalize();
    assert!(
        moved.dot(edge).abs() < 1e-9,
        "the move leaves the plane normal to the edge"
    );
    assert!(((q.back_top - q.front_top) - (p.back_top - p.front_top)).length() < 1e-9);
    assert_eq!(q.front_bottom, p.front_bottom);
    assert!(q.planarity_error() < 1e-9);
}

#[test]
fn delete_removes_the_last_box_down_to_one() {
    let scene = Scene::sphere();
    let mut editor = painted_sphere(&scene);
    let n = editor.cutter().unwrap().planes.len();
    // Off the cutter: nothing happens.
    feed(&mut editor, [EditorEvent::key(Key::Delete, 20.0, 20.0)]);
    assert_eq!(editor.cutter().unwrap().planes.len(), n);
    for k in 1..n + 3 {
        let px = on_plane(&editor, 0);
        feed(&mut editor, [EditorEvent::key(Key::Delete, px.x, px.y)]);
        assert_eq!(
            editor.cutter().unwrap().planes.len(),
            n.saturating_sub(k).max(2)
        );
    }
}

#[test]
fn undo_redo_round_trip_restores_every_state() {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    let mut states = vec![editor.cutter().cloned()];
    init(&mut editor, DVec2::new(620.0, 430.0));
    states.push(editor.cutter().cloned());
    extrude(&mut editor, &s_path(120.0, 20.0, 30), false);
    states.push(editor.cutter().cloned());
    feed(&mut editor, [EditorEvent::wheel(20.0, 20.0, 3.0, false)]);
    states.push(editor.cutter().cloned());
    let px = on_plane(&editor, 1);
    feed(&mut editor, [EditorEvent::key(Key::Delete, px.x, px.y)]);
    states.push(editor.cutter().cloned());
    extrude(&mut editor, &s_path(60.0, 0.0, 10), true);
    states.push(editor.cutter().cloned());
    for w in states.windows(2) {
        assert_ne!(w[0], w[1], "every action must change the cutter");
    }
    for k in (0..states.len() - 1).rev() {
        assert!(editor.undo());
        assert_eq!(editor.cutter().cloned(), states[k], "undo to state {k}");
        if let Some(c) = editor.cutter() {
            validate(c);
        }
    }
    assert!(!editor.undo());
    for k in 1..states.len() {
        assert!(editor.redo());
        assert_eq!(editor.cutter().cloned(), states[k], "redo to state {k}");
    }
    assert!(!editor.redo());
    // A new action after an undo drops the redo branch but keeps the history before it.
    assert!(editor.undo());
    feed(&mut editor, [EditorEvent::wheel(20.0, 20.0, 1.0, false)]);
    assert!(!editor.can_redo());
    assert!(editor.undo());
    assert_eq!(editor.cutter().cloned(), states[states.len() - 2]);
}

#[test]
fn init_off_the_object_surrounds_it() {
    // A is above the sphere (off it); the strip crosses the top of the silhouette.
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    let a = DVec2::new(640.0, 60.0);
    feed(&mut editor, drag(a, DVec2::new(640.0, 200.0), 5));
    let c = editor
        .cutter()
        .expect("a cutter even though A is off the object");
    validate(c);
    // Pushed onto the closest point seen through the strip: the front is near the sphere's front.
    let depth_front = c.planes[0].front_mid().y;
    assert!(
        depth_front < 0.0 && depth_front > -55.0,
        "front at y = {depth_front}"
    );
}

#[test]
fn handle_press_snaps_the_cursor_and_short_drags_do_nothing() {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    // A 1-pixel drag makes no cutter.
    feed(
        &mut editor,
        drag(DVec2::new(500.0, 400.0), DVec2::new(501.0, 400.0), 1),
    );
    assert!(editor.cutter().is_none());
    init(&mut editor, DVec2::new(620.0, 430.0));
    let h = handle_px(&editor);
    // 10 px to the side of the handle's middle still grabs it; the response warps to the handle.
    let r = editor.handle(EditorEvent::press(h.x + 10.0, h.y));
    assert_eq!(r.warp_cursor, Some(h));
    assert_eq!(r.cursor, cutter::CursorHint::Grabbing);
    // Releasing where pressed changes nothing (the virtual cursor sits on the handle).
    let r = editor.handle(EditorEvent::release(h.x + 10.0, h.y));
    assert!(editor.cutter().unwrap().planes.len() == 2);
    let _ = r;
    assert_eq!(editor.recorded_events().len(), 3 + 8 + 2);
    let _ = DVec3::ZERO;
}

#[test]
fn an_edge_dragged_across_its_neighbour_is_refused_in_place_with_a_note() {
    let scene = Scene::sphere();
    for smooth in [false, true] {
        let mut editor = painted_sphere(&scene);
        assert!(editor.set_smooth(smooth) || !smooth);
        let before = editor.cutter().unwrap().clone();
        let p = before.planes[2];
        let v = editor
            .camera()
            .project(editor.viewport(), p.front_top)
            .unwrap();
        // Far along the path, across planes 3, 4, ...: every move that would cross is refused,
        // so the cutter holds the last valid position and the note says why.
        feed(&mut editor, drag(v, v + DVec2::new(240.0, 0.0), 12));
        let c = editor.cutter().unwrap();
        validate(c);
        assert_eq!(c.planes.len(), before.planes.len());
        let note = editor.note().expect("a refused move leaves a note");
        assert!(note.contains("edge"), "{note}");
        // The edge moved at most to just before its neighbour, never past it.
        let next = before.planes[3].front_top;
        let along = (next - p.front_top).normalize();
        assert!(
            (c.planes[2].front_top - p.front_top).dot(along) < (next - p.front_top).length(),
            "smooth={smooth}"
        );
        // One undo step brings the cutter back.
        if c != &before {
            assert!(editor.undo());
            assert_eq!(editor.cutter().unwrap(), &before);
        }
    }
}
