//! The editor's depth under the current rules ([`cutter::Rules::Reach`]): a new cutter reaches
//! the first structure behind its target, the wheel over the cutter changes its whole depth and
//! Alt+wheel the plane under the pointer, rolling keeps the depth, the boxes go along the view,
//! and the opening is as large as what was painted.

mod editor_support;

use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::PickIndex;
use cutter::reach::{MeshObstacles, Obstacle, ReachRule};
use cutter::{CutDirection, CutKind, Editor, EditorEvent, Rules};
use editor_support::*;

/// A ball of radius `r` at `centre`, as a structure behind the target.
fn ball(structure: usize, name: &str, r: f64, centre: DVec3) -> Obstacle {
    let mut mesh = csg::testkit::icosphere(3, r);
    for p in &mut mesh.positions {
        *p += centre;
    }
    let tree = Arc::new(PickIndex::build(&mesh));
    Obstacle {
        structure,
        name: name.to_string(),
        mesh: Arc::new(mesh),
        tree,
    }
}

/// The sphere scene with a "ventricle" of radius 8 whose front is 30 behind the sphere's front.
fn sphere_with_ventricle() -> (Scene, Editor) {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.current_settings(CutKind::Curving));
    let obstacles = MeshObstacles {
        structures: vec![ball(3, "ventricle", 8.0, DVec3::new(0.0, -12.0, 0.0))],
    };
    editor.set_obstacles(Some(Arc::new(obstacles)));
    (scene, editor)
}

/// A horizontal 120-pixel stroke across the sphere's front (so the box extends downward).
fn paint(editor: &mut Editor) {
    let a = DVec2::new(580.0, 380.0);
    feed(editor, drag(a, a + DVec2::new(120.0, 0.0), 8));
}

/// A pixel on plane `i`'s projected front edge, 30 % of the way from front-top.
fn on_plane(editor: &Editor, i: usize) -> DVec2 {
    let p = editor.cutter().unwrap().planes[i];
    let project = |q| editor.camera().project(editor.viewport(), q).unwrap();
    project(p.front_top).lerp(project(p.front_bottom), 0.3)
}

/// Rolls the cutter `pixels` straight down the screen from its handle.
fn roll_down(editor: &mut Editor, pixels: f64) {
    let h = handle_px(editor);
    let path: Vec<DVec2> = (1..=30)
        .map(|k| h + DVec2::new(0.0, pixels * k as f64 / 30.0))
        .collect();
    let mut events = vec![EditorEvent::press(h.x, h.y)];
    events.extend(path.iter().map(|p| EditorEvent::move_to(p.x, p.y)));
    let end = path[path.len() - 1];
    events.push(EditorEvent::release(end.x, end.y));
    feed(editor, events);
}

#[test]
fn a_new_cutter_reaches_the_structure_behind_its_target() {
    let (_, mut editor) = sphere_with_ventricle();
    paint(&mut editor);
    let c = editor.cutter().expect("a cutter").clone();
    validate(&c);
    let reach = *editor.reach().expect("the default depth's reason");
    let ReachRule::Structure(hit) = reach.rule else {
        panic!("{reach:?}");
    };
    assert_eq!(hit.structure, 3);
    // The ventricle's front is at y = -20, the front edge just outside y = -50: about 30 from
    // the front edge, reached plus half of that from the surface.
    assert!((hit.t - 30.0).abs() < 1.5, "{hit:?}");
    assert!(
        c.depth() > hit.t + 10.0 && c.depth() < hit.t + 20.0,
        "{}",
        c.depth()
    );
    for p in &c.planes {
        assert!((p.depth() - c.depth()).abs() < 1e-9);
    }
    let reached = editor.reached();
    assert_eq!(reached.len(), 1, "{reached:?}");
    assert_eq!(editor.obstacle_name(3).as_deref(), Some("ventricle"));

    // Under the first rules the same stroke is 5δ deep and reaches nothing.
    let scene = Scene::sphere();
    let mut first = scene.editor(scene.settings(CutKind::Curving));
    paint(&mut first);
    let depth = first.cutter().unwrap().depth();
    assert!((depth - 5.0 * first.delta()).abs() < 1e-9, "{depth}");
}

#[test]
fn without_anything_behind_a_new_cutter_goes_half_through_its_target() {
    let scene = Scene::sphere();
    let mut editor = scene.editor(scene.current_settings(CutKind::Curving));
    paint(&mut editor);
    let reach = *editor.reach().unwrap();
    assert_eq!(reach.rule, ReachRule::Thickness);
    // The sphere is 100 thick at its middle, a little less under the stroke's ends.
    let depth = editor.cutter().unwrap().depth();
    assert!(depth > 40.0 && depth < 52.0, "{depth}");
}

#[test]
fn the_wheel_changes_the_whole_cutter_and_alt_wheel_the_plane_under_the_pointer() {
    let (_, mut editor) = sphere_with_ventricle();
    paint(&mut editor);
    roll_down(&mut editor, 90.0);
    let before = editor.cutter().unwrap().clone();
    assert!(before.planes.len() >= 4, "{} planes", before.planes.len());
    // Off the cutter: nothing (the window zooms there).
    let response = editor.handle(EditorEvent::wheel(20.0, 20.0, 3.0, false));
    assert!(!response.changed);
    assert_eq!(editor.cutter().unwrap(), &before);
    // Over the cutter: every plane, 5 % a notch.
    let px = on_plane(&editor, 1);
    assert!(editor.is_over_cutter(px));
    feed(&mut editor, [EditorEvent::wheel(px.x, px.y, 2.0, false)]);
    let deeper = editor.cutter().unwrap().clone();
    validate(&deeper);
    for (a, b) in before.planes.iter().zip(&deeper.planes) {
        assert!((b.depth() / a.depth() - 1.05f64.powi(2)).abs() < 1e-9);
        assert_eq!(a.front_top, b.front_top);
    }
    // Alt: the plane under the pointer alone.
    let px = on_plane(&editor, 2);
    feed(&mut editor, [EditorEvent::alt_wheel(px.x, px.y, -4.0)]);
    let one = editor.cutter().unwrap().clone();
    validate(&one);
    for (i, (a, b)) in deeper.planes.iter().zip(&one.planes).enumerate() {
        if i == 2 {
            assert!((b.depth() / a.depth() - 1.05f64.powi(-4)).abs() < 1e-9);
        } else {
            assert_eq!(a, b, "plane {i}");
        }
    }
    // One undo step each.
    assert!(editor.undo());
    assert_eq!(editor.cutter().unwrap(), &deeper);
    assert!(editor.undo());
    assert_eq!(editor.cutter().unwrap(), &before);
}

#[test]
fn rolling_keeps_a_deepened_roller_deep() {
    for rules in [Rules::Reach, Rules::Delta] {
        let (scene, _) = sphere_with_ventricle();
        let mut editor = scene.editor(
            scene
                .current_settings(CutKind::Curving)
                .with_rules(rules)
                .with_direction(CutDirection::View),
        );
        paint(&mut editor);
        let lead = editor.cutter().unwrap().planes.len() - 1;
        let px = on_plane(&editor, lead);
        // Deepen the leading plane alone (Alt under the current rules; the first rules deepen
        // the hovered plane when none is selected).
        let wheel = match rules {
            Rules::Reach => EditorEvent::alt_wheel(px.x, px.y, 10.0),
            Rules::Delta => EditorEvent::wheel(px.x, px.y, 10.0, false),
        };
        feed(&mut editor, [EditorEvent::move_to(px.x, px.y), wheel]);
        let c = editor.cutter().unwrap().clone();
        let (first, deep) = (c.planes[0].depth(), c.leading().depth());
        assert!(deep > first * 1.5, "{rules:?}: {first} → {deep}");
        roll_down(&mut editor, 80.0);
        let rolled = editor.cutter().unwrap().clone();
        validate(&rolled);
        assert!(rolled.planes.len() > c.planes.len() + 1);
        match rules {
            // The roller stays deep and the planes it locked took its depth.
            Rules::Reach => {
                for p in &rolled.planes[1..] {
                    assert!((p.depth() - deep).abs() < 1e-6 * deep, "{}", p.depth());
                }
                assert!((rolled.planes[0].depth() - first).abs() < 1e-9);
            }
            // The first rules give the rolled plane the depth of the plane before it.
            Rules::Delta => {
                assert!((rolled.leading().depth() - first).abs() < 1e-6 * first);
            }
        }
    }
}

#[test]
fn the_boxes_go_along_the_view_or_the_normal() {
    let scene = Scene::sphere();
    let forward = scene.camera.forward();
    for direction in [CutDirection::View, CutDirection::Normal] {
        let mut editor = scene.editor(
            scene
                .current_settings(CutKind::Curving)
                .with_direction(direction),
        );
        paint(&mut editor);
        roll_down(&mut editor, 150.0);
        let c = editor.cutter().unwrap().clone();
        validate(&c);
        assert!(c.planes.len() >= 6, "{} planes", c.planes.len());
        let along_view = c
            .planes
            .iter()
            .all(|p| p.back_direction().dot(forward) > 1.0 - 1e-9);
        assert_eq!(along_view, direction == CutDirection::View, "{direction:?}");
        assert_eq!(c.direction, direction);
        // The depth is the same all along.
        for p in &c.planes {
            assert!((p.depth() - c.depth()).abs() < 1e-6 * c.depth());
        }
    }
}

#[test]
fn the_depth_field_gives_every_plane_one_depth() {
    let (_, mut editor) = sphere_with_ventricle();
    paint(&mut editor);
    roll_down(&mut editor, 60.0);
    let px = on_plane(&editor, 1);
    feed(&mut editor, [EditorEvent::alt_wheel(px.x, px.y, 5.0)]);
    assert!(editor.set_depth(22.5));
    let c = editor.cutter().unwrap();
    validate(c);
    for p in &c.planes {
        assert!((p.depth() - 22.5).abs() < 1e-9, "{}", p.depth());
    }
    assert_eq!(editor.depth(), Some(c.depth()));
    assert!(!editor.set_depth(22.5), "nothing changes");
    assert!(!editor.set_depth(f64::NAN));
}
