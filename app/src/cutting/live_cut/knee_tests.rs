//! Tests of [`super`] (`live_cut.rs`), kept in their own file.

use super::*;
use crate::cutting::cut_scene::PartKind;
use crate::cutting::editing::CutterInit;
use crate::cutting::editing::EditorSlot;
use cutter::EditorEvent;
use glam::DVec2;

#[test]
fn live_cut_follows_the_editor_on_the_knee() {
    let knee = crate::anatomy::assets::scene("knee").expect("embedded knee");
    let mut scene = Scene::default();
    for model in crate::anatomy::assets::load_scene(knee).expect("load the knee") {
        let color = crate::anatomy::colors::class_color(&model.name);
        scene.models.push(crate::scene::SceneModel::new(
            model.name,
            model.source,
            model.mesh,
            color,
        ));
    }
    scene.camera = scene.framing_camera();
    let viewport = DVec2::new(1280.0, 800.0);
    let press = viewport * 0.5 + DVec2::new(-60.0, 0.0);
    let ray = scene.camera.ray_through_pixel(viewport, press);
    let mut picks = crate::cutting::pick::ScenePicks::default();
    let (target, _) = picks.pick(&scene, &ray).expect("the knee is in view");
    let mut slot = EditorSlot::default();
    assert!(slot.ensure(&scene, target, viewport, &CutterInit::default(), &mut picks));
    for event in [
        EditorEvent::press(press.x, press.y),
        EditorEvent::move_to(press.x + 40.0, press.y + 4.0),
        EditorEvent::move_to(press.x + 80.0, press.y + 8.0),
        EditorEvent::release(press.x + 80.0, press.y + 8.0),
    ] {
        slot.handle(&mut scene, viewport, event);
    }
    assert_eq!(scene.cutters.len(), 1, "the init drag made no cutter");
    let mut live = LiveCut::default();
    let mut times = Vec::new();
    let request = |scene: &Scene, live: &mut LiveCut| {
        assert!(live.request(scene, None));
        assert!(live.wait(Duration::from_secs(120)), "no live cut");
        let shown = live.shown().unwrap();
        assert!(
            shown
                .geometry
                .parts
                .iter()
                .any(|p| p.kind == PartKind::Wall),
            "no walls: {:?}",
            shown.geometry.notes
        );
        assert!(
            shown.geometry.notes.is_empty(),
            "{:?}",
            shown.geometry.notes
        );
        shown.ms
    };
    let first = request(&scene, &mut live);
    // Grab the handle (the middle of the leading plane's front edge) and paint downwards.
    let lead = scene.cutters[0].cutter.planes.last().unwrap().corners();
    let handle = scene
        .camera
        .project(viewport, (lead[0] + lead[3]) * 0.5)
        .expect("handle in view");
    slot.handle(&mut scene, viewport, EditorEvent::press(handle.x, handle.y));
    let planes_before = scene.cutters[0].cutter.planes.clone();
    for k in 1..=12 {
        let p = handle + DVec2::new(3.0 * k as f64, 6.0 * k as f64);
        if slot.handle(&mut scene, viewport, EditorEvent::move_to(p.x, p.y)) {
            times.push(request(&scene, &mut live));
        }
    }
    slot.handle(
        &mut scene,
        viewport,
        EditorEvent::release(handle.x, handle.y),
    );
    assert_ne!(
        scene.cutters[0].cutter.planes, planes_before,
        "the drag did not extrude"
    );
    assert!(!times.is_empty());
    // Leaving Edit mode drops the worker's caches; coming back builds the index again.
    live.clear();
    let rebuilt = request(&scene, &mut live);
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    println!(
        "live re-cut of {} ({} triangles): first cut (index build included) {first:.1} ms; \
         {} re-cuts while painting: median {:.1} ms, max {:.1} ms; back in Edit mode after \
         leaving it (index built again) {rebuilt:.1} ms",
        scene.models[target].model.name,
        scene.models[target].model.mesh.triangle_count(),
        times.len(),
        sorted[sorted.len() / 2],
        sorted[sorted.len() - 1],
    );
}
