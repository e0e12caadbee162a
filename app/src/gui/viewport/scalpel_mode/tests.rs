//! Scalpel mode in the real window (egui_kittest, headless) and the view of a stroke in
//! progress on the GPU renderer (lavapipe).

use std::sync::Arc;

use glam::{DVec2, DVec3};

use crate::scalpel_session::Released;
use crate::scalpel_session::tests::{assert_closed_and_manifold, position_bits};
use crate::scene::{MeshOrigin, Scene};

fn session_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-scalpel-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Remove All Cut Geometry in the window replaces the cut model's mesh: the model is marked
/// edited, and Save Session writes the cut mesh, which the session then reopens.
#[test]
fn the_window_saves_the_mesh_left_by_remove_all_cut_geometry() {
    let dir = session_dir("remove-all");
    let cube = dir.join("cube.ply");
    crate::io::write_mesh(
        &cube,
        &crate::gui::app::box_mesh(DVec3::ZERO, DVec3::splat(2.0)),
    )
    .unwrap();
    let start = crate::gui::StartOptions {
        paths: vec![cube],
        state_dir: dir.join("state"),
        offer_recovery: false,
    };
    let mut h = crate::gui::test_window::open(start, 1024.0, 700.0);
    assert_eq!(h.state().scene.models.len(), 1);
    assert_eq!(h.state().scene.models[0].origin, MeshOrigin::Region);
    let cutter = crate::test_support::scene_with_cube_cut(Default::default())
        .cutters
        .remove(0);
    h.state_mut().scene.cutters.push(cutter);
    let ctx = h.ctx.clone();
    h.state_mut()
        .apply(&ctx, crate::gui::app::Action::RemoveAllCutGeometry);
    crate::gui::test_window::settle(&mut h);
    let state = h.state();
    assert!(state.scene.cutters.is_empty(), "{}", state.status.message);
    assert_eq!(state.scene.models[0].origin, MeshOrigin::Edited);
    let cut = state.scene.models[0].model.mesh.clone();
    assert!((cut.volume() - 7.0).abs() < 1e-9, "{}", cut.volume());

    let path = dir.join("applied.json");
    h.state_mut()
        .apply(&ctx, crate::gui::app::Action::SaveSessionTo(path.clone()));
    let back = crate::session::load(&path).unwrap();
    assert_eq!(back.models.len(), 1);
    assert!(back.models[0].model.mesh.triangles == cut.triangles);
    assert!(position_bits(&back.models[0].model.mesh) == position_bits(&cut));
    // The window reopens it the same way.
    h.state_mut().scene = crate::gui::app::new_scene();
    h.state_mut()
        .apply(&ctx, crate::gui::app::Action::Open(vec![path.clone()]));
    crate::gui::test_window::settle(&mut h);
    let reopened = &h.state().scene.models;
    assert_eq!(reopened.len(), 1, "{}", h.state().status.message);
    assert_eq!(reopened[0].origin, MeshOrigin::Exact);
    assert!(reopened[0].model.mesh.triangles == cut.triangles);
    assert!(position_bits(&reopened[0].model.mesh) == position_bits(&cut));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The real window: two files with nested spheres open as two models; a groove across
/// the outer one cuts both, Ctrl+Z brings both back bit for bit in one step, Ctrl+Shift+Z
/// redoes both; with "Cut layers below" unticked only the outer one is cut.
#[test]
fn the_window_cuts_the_layer_below_and_undoes_both_in_one_step() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    let dir = session_dir("layers-gui");
    let (outer_file, inner_file) = (dir.join("outer.obj"), dir.join("inner.obj"));
    crate::io::write_mesh(&outer_file, &csg::testkit::icosphere(4, 10.0)).unwrap();
    crate::io::write_mesh(&inner_file, &csg::testkit::icosphere(3, 9.7)).unwrap();
    let start = crate::gui::StartOptions {
        paths: vec![outer_file, inner_file],
        state_dir: dir.join("state"),
        offer_recovery: false,
    };
    // Tall enough that the Scalpel panel's "Cut layers below" is in view below the Cutter panel
    // (at 800 it is below the left column's fold; where the tools sit is the panels' layout).
    let mut h = crate::gui::test_window::open(start, 1280.0, 1000.0);
    h.run_steps(1);
    let models = &h.state().scene.models;
    assert_eq!(models.len(), 2, "{}", h.state().status.message);
    let outer_i = if models[0].model.mesh.bbox().diagonal() > models[1].model.mesh.bbox().diagonal()
    {
        0
    } else {
        1
    };
    let inner_i = 1 - outer_i;
    let (outer, inner) = (
        models[outer_i].model.mesh.clone(),
        models[inner_i].model.mesh.clone(),
    );
    h.query_all_by_label("Scalpel")
        .find(|n| {
            use egui_kittest::kittest::NodeT;
            n.accesskit_node().toggled().is_some()
        })
        .expect("the Scalpel mode button")
        .click();
    h.run_steps(3);
    h.state_mut().viewport.scalpel.settings.depth = 0.6;
    h.run_steps(1);
    let app = h.state();
    let rect = app.viewport.scalpel.rect;
    let ppp = h.ctx.pixels_per_point() as f64;
    let centre = app
        .scene
        .camera
        .project(app.viewport.size_px, DVec3::ZERO)
        .unwrap();
    let edge = app
        .scene
        .camera
        .project(app.viewport.size_px, DVec3::new(10.0, 0.0, 0.0))
        .unwrap();
    let radius_px = (edge - centre).length();
    let at = |dx: f64, dy: f64| {
        let px = centre + DVec2::new(dx, dy) * radius_px;
        rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
    };
    let drag = |h: &mut Harness<'_, crate::gui::CutawayApp>, dy: f64| {
        h.hover_at(at(-0.4, dy));
        h.step();
        h.drag_at(at(-0.4, dy));
        h.step();
        for k in 1..=16 {
            h.hover_at(at(-0.4 + 0.8 * k as f64 / 16.0, dy));
            h.step();
        }
        h.drop_at(at(0.4, dy));
        h.run_steps(2);
    };
    drag(&mut h, 0.0);
    let state = h.state();
    assert!(!state.status.is_error, "{}", state.status.message);
    let (outer_cut, inner_cut) = (
        state.scene.models[outer_i].model.mesh.clone(),
        state.scene.models[inner_i].model.mesh.clone(),
    );
    assert!(outer_cut.triangle_count() > outer.triangle_count());
    assert!(
        inner_cut.triangle_count() > inner.triangle_count(),
        "the inner sphere was not cut (status: {})",
        state.status.message
    );
    assert_closed_and_manifold(&inner_cut, "inner");
    assert_eq!(state.scene.models[inner_i].origin, MeshOrigin::Edited);

    // One Ctrl+Z: both models as they were, bit for bit.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    for (i, original) in [(outer_i, &outer), (inner_i, &inner)] {
        let m = &h.state().scene.models[i].model.mesh;
        assert_eq!(m.triangles, original.triangles, "model {i}");
        assert_eq!(position_bits(m), position_bits(original), "model {i}");
    }
    // Ctrl+Shift+Z: both cuts again.
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.run_steps(2);
    assert!(Arc::ptr_eq(
        &h.state().scene.models[outer_i].model.mesh,
        &outer_cut
    ));
    assert!(Arc::ptr_eq(
        &h.state().scene.models[inner_i].model.mesh,
        &inner_cut
    ));

    // Untick "Cut layers below": a second groove cuts the outer sphere only.
    h.get_by_label("Cut layers below").click();
    h.run_steps(2);
    assert!(!h.state().viewport.scalpel.settings.layers);
    drag(&mut h, 0.3);
    let state = h.state();
    assert!(
        state.scene.models[outer_i].model.mesh.triangle_count() > outer_cut.triangle_count(),
        "the second groove did not cut (status: {})",
        state.status.message
    );
    assert!(Arc::ptr_eq(
        &state.scene.models[inner_i].model.mesh,
        &inner_cut
    ));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The real window, headless (egui_kittest, no GPU needed: the viewport falls back to its
/// CPU preview): the Scalpel button, a drag across a sphere, Ctrl+Z and Ctrl+Shift+Z.
#[test]
fn the_window_cuts_with_the_scalpel_and_undoes_the_stroke() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::{NodeT, Queryable};

    let dir = std::env::temp_dir().join(format!("cutaway-scalpel-gui-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let sphere = dir.join("sphere.obj");
    crate::io::write_mesh(&sphere, &csg::testkit::icosphere(4, 10.0)).unwrap();
    let start = crate::gui::StartOptions {
        paths: vec![sphere],
        state_dir: dir.clone(),
        offer_recovery: false,
    };
    let mut h = crate::gui::test_window::open(start, 1280.0, 800.0);
    h.run_steps(1);
    assert_eq!(
        h.state().scene.models.len(),
        1,
        "{}",
        h.state().status.message
    );
    // A cutter on the model: a scalpel stroke and its undo must never lose it.
    let cutter = crate::scene::SceneCutter::new(
        0,
        cutter::Cutter {
            kind: cutter::CutKind::Curving,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes: [
                [
                    DVec3::new(0.0, -11.0, 1.0),
                    DVec3::new(0.0, -9.0, 1.0),
                    DVec3::new(0.0, -9.0, -1.0),
                    DVec3::new(0.0, -11.0, -1.0),
                ],
                [
                    DVec3::new(1.0, -11.0, 1.0),
                    DVec3::new(1.0, -9.0, 1.0),
                    DVec3::new(1.0, -9.0, -1.0),
                    DVec3::new(1.0, -11.0, -1.0),
                ],
            ]
            .map(cutter::BoundedPlane::from_corners)
            .to_vec(),
        },
    );
    h.state_mut().scene.cutters.push(cutter.clone());

    h.query_all_by_label("Scalpel")
        .find(|n| n.accesskit_node().toggled().is_some())
        .expect("the Scalpel mode button")
        .click();
    h.run_steps(3);
    assert_eq!(h.state().mode, crate::gui::Mode::Scalpel);
    let original = h.state().scene.models[0].model.mesh.clone();

    // Aim: a horizontal drag across the middle of the sphere as the window shows it.
    let app = h.state();
    let rect = app.viewport.scalpel.rect;
    assert!(rect.width() > 100.0, "viewport {rect:?}");
    let ppp = h.ctx.pixels_per_point() as f64;
    let centre = app
        .scene
        .camera
        .project(app.viewport.size_px, DVec3::ZERO)
        .unwrap();
    let edge = app
        .scene
        .camera
        .project(app.viewport.size_px, DVec3::new(10.0, 0.0, 0.0))
        .unwrap();
    let radius_px = (edge - centre).length();
    let at = |dx: f64| {
        let px = centre + DVec2::new(dx * radius_px, 0.0);
        rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
    };
    let drag = |h: &mut Harness<'_, crate::gui::CutawayApp>, from: f64, to: f64| {
        h.hover_at(at(from));
        h.step();
        h.drag_at(at(from));
        h.step();
        for k in 1..=16 {
            h.hover_at(at(from + (to - from) * k as f64 / 16.0));
            h.step();
        }
        h.drop_at(at(to));
        h.run_steps(2);
    };
    drag(&mut h, -0.5, 0.5);
    let cut = h.state().scene.models[0].model.mesh.clone();
    assert!(
        cut.triangle_count() > original.triangle_count(),
        "no cut: {} (status: {})",
        cut.triangle_count(),
        h.state().status.message
    );
    let report = cut.report();
    assert!(report.closed && report.manifold, "{report:?}");
    let topo = h
        .state()
        .viewport
        .scalpel
        .validate()
        .unwrap()
        .expect("scalpel invariants");
    assert!(topo.closed && topo.manifold, "{topo:?}");
    assert!(!h.state().status.is_error, "{}", h.state().status.message);

    // Ctrl+Z: the exact mesh comes back, the cutter is still there.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    let undone = h.state().scene.models[0].model.mesh.clone();
    assert_eq!(undone.positions, original.positions);
    assert_eq!(undone.triangles, original.triangles);
    assert_eq!(h.state().scene.cutters, vec![cutter.clone()]);
    // Ctrl+Shift+Z: the cut again.
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.run_steps(2);
    assert!(Arc::ptr_eq(&h.state().scene.models[0].model.mesh, &cut));
    // Undo again and cut elsewhere: the scalpel follows the undone scene.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    drag(&mut h, -0.3, 0.4);
    let again = h.state().scene.models[0].model.mesh.clone();
    assert!(again.triangle_count() > original.triangle_count());
    assert!(again.report().closed);
    assert_eq!(h.state().scene.cutters, vec![cutter]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A stroke in progress drawn from its delta looks exactly as the whole cut mesh did, and a
/// step uploads only what changed.
#[cfg(test)]
mod view {
    use super::*;
    use crate::cutting::delta::MeshDelta;
    use crate::render::ViewMode;
    use crate::test_support::{
        deterministic_frame, differing_pixels, renderer_or_skip, with_sphere,
    };

    #[test]
    fn a_stroke_drawn_from_its_delta_looks_as_the_whole_mesh_and_uploads_little() {
        let Some(mut renderer) = renderer_or_skip() else {
            return;
        };
        let sphere = Arc::new(csg::testkit::icosphere(6, 10.0));
        let mut scene = with_sphere(crate::gui::app::new_scene(), sphere, "sphere.obj");
        let viewport = DVec2::new(320.0, 240.0);
        let frame = |scene: &Scene, delta: Option<Arc<MeshDelta>>| {
            let mut f = deterministic_frame(scene, [320, 240], ViewMode::Camera);
            f.deltas.extend(delta);
            f
        };
        let uncut = renderer.render(&frame(&scene, None)).expect("render");
        let model_bytes = renderer.last_frame_uploads().bytes;
        let mut slot = crate::scalpel_session::ScalpelSession::default();
        slot.settings.depth = 0.6;
        let at = |s: f64| DVec2::new(viewport.x * s, viewport.y * 0.45);
        assert_eq!(slot.press(&scene, viewport, at(0.4)), Ok(Some(0)));
        let mut drawn = 0;
        for k in 1..=10 {
            if !slot
                .drag(&mut scene, viewport, at(0.4 + 0.02 * k as f64))
                .expect("step")
            {
                continue;
            }
            let delta = slot.delta().expect("a delta");
            let got = renderer
                .render(&frame(&scene, Some(delta)))
                .expect("render");
            let uploads = renderer.last_frame_uploads();
            // The way before: the whole mesh in the scene.
            let mut whole = scene.clone();
            let session = slot.session.as_ref().unwrap();
            whole.models[0].replace_mesh_with_walls(
                session.display(&slot.settings.open()),
                session.scalpel.wall_faces(),
            );
            let expected = renderer.render(&frame(&whole, None)).expect("render");
            assert_ne!(differing_pixels(&got, &uncut), 0, "step {k}: nothing cut");
            assert_eq!(
                differing_pixels(&got, &expected),
                0,
                "step {k}: the view differs"
            );
            assert!(
                uploads.bytes * 10 < model_bytes,
                "step {k}: {} bytes uploaded, the model is {model_bytes}",
                uploads.bytes
            );
            drawn += 1;
            if k == 6 {
                let _ = got.save(std::env::temp_dir().join("scalpel-delta.png"));
            }
        }
        assert!(drawn > 3, "{drawn} steps drawn");
        let drawn_last = {
            let session = slot.session.as_ref().unwrap();
            session.display(&slot.settings.open())
        };
        assert!(matches!(
            slot.release(&mut scene),
            Released::Committed { .. }
        ));
        let cut = {
            let session = slot.session.as_ref().unwrap();
            session.display(&slot.settings.open())
        };
        assert_eq!(
            *scene.models[0].model.mesh, *cut,
            "the release puts the cut mesh in the scene"
        );
        // Ending the stroke only moves its end tip onto the drawn end (with the groove floor
        // and the opening that taper toward it): the mesh last drawn, a few vertices moved.
        assert_eq!(cut.triangles, drawn_last.triangles);
        let moved = (cut.positions.iter().zip(&drawn_last.positions))
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            moved * 100 < cut.positions.len(),
            "the release moved {moved} vertices"
        );
    }
}

/// The UI thread's cost of a scalpel step on a 2M-triangle model: the step itself, what the
/// scene and the view get from it, and the renderer's frame. Prints figures; no timing
/// assertion, so it is ignored in `cargo test`; run it with
/// `WGPU_BACKEND=vulkan cargo test -p cutaway --lib ui_thread_cost -- --ignored --nocapture`.
#[cfg(test)]
mod timings {
    use super::*;
    use crate::cutting::delta::MeshDelta;
    use crate::render::ViewMode;
    use crate::test_support::{
        deterministic_frame, median_and_max, two_renderers_or_skip, with_sphere,
    };
    use std::time::Instant;

    /// Per step, the window's way (the stroke drawn as a delta over the uploaded model) and the
    /// way before it (the whole mesh copied into the scene and uploaded), each with a renderer
    /// of its own, in the same run.
    #[test]
    #[ignore = "a benchmark: prints figures and checks none; run it with `--ignored --nocapture`"]
    fn scalpel_step_ui_thread_cost_on_two_million_triangles() {
        let Some((mut renderer, mut whole)) = two_renderers_or_skip() else {
            return;
        };
        let sphere = Arc::new(csg::testkit::geodesic_sphere(316, 100.0));
        let mut scene = with_sphere(crate::gui::app::new_scene(), sphere.clone(), "sphere.ply");
        let viewport = DVec2::new(640.0, 400.0);
        let frame_of = |scene: &Scene, delta: Option<Arc<MeshDelta>>| {
            let mut frame = deterministic_frame(scene, [640, 400], ViewMode::Camera);
            frame.deltas.extend(delta);
            frame
        };
        let first = renderer
            .time_prepare(&frame_of(&scene, None))
            .expect("first frame");
        whole
            .time_prepare(&frame_of(&scene, None))
            .expect("first frame");
        let mut slot = crate::scalpel_session::ScalpelSession::default();
        slot.settings.depth = 1.0;
        let started = Instant::now();
        let press = DVec2::new(viewport.x * 0.4, viewport.y * 0.5);
        assert_eq!(slot.press(&scene, viewport, press), Ok(Some(0)));
        let press_ms = started.elapsed().as_secs_f64() * 1000.0;
        let mut whole_scene = scene.clone();
        let (mut step_ms, mut delta_ms, mut frame_ms, mut total_ms, mut bytes) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut copy_ms, mut whole_frame_ms, mut whole_total_ms, mut whole_bytes) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for k in 1..=40 {
            let px = DVec2::new(viewport.x * (0.4 + 0.005 * k as f64), viewport.y * 0.5);
            let started = Instant::now();
            let changed = slot.drag(&mut scene, viewport, px).expect("step");
            let step = started.elapsed().as_secs_f64() * 1000.0;
            let frame = renderer
                .time_prepare(&frame_of(&scene, slot.delta()))
                .expect("frame");
            let uploaded = renderer.last_frame_uploads().bytes as f64 / 1e6;
            // The delta's share of the step (built again: the same state gives the same delta).
            let open = slot.settings.open();
            let (Some(session), Some(stroke)) = (slot.session.as_mut(), slot.stroke.as_mut())
            else {
                panic!("no stroke");
            };
            let started = Instant::now();
            session.stroke_delta(&open, stroke);
            let delta = started.elapsed().as_secs_f64() * 1000.0;
            // The way before: the whole mesh into the scene, uploaded.
            let started = Instant::now();
            whole_scene.models[0]
                .replace_mesh_with_walls(session.display(&open), session.scalpel.wall_faces());
            let copy = started.elapsed().as_secs_f64() * 1000.0;
            let whole_frame = whole
                .time_prepare(&frame_of(&whole_scene, None))
                .expect("frame");
            if changed && k > 1 {
                step_ms.push(step);
                delta_ms.push(delta);
                frame_ms.push(frame);
                total_ms.push(step + frame);
                bytes.push(uploaded);
                copy_ms.push(copy);
                whole_frame_ms.push(whole_frame);
                whole_total_ms.push(step - delta + copy + whole_frame);
                whole_bytes.push(whole.last_frame_uploads().bytes as f64 / 1e6);
            }
        }
        let started = Instant::now();
        let released = slot.release(&mut scene);
        let release_ms = started.elapsed().as_secs_f64() * 1000.0;
        assert!(
            matches!(released, Released::Committed { .. }),
            "{released:?}"
        );
        let after_release = renderer
            .time_prepare(&frame_of(&scene, None))
            .expect("frame");
        let f = median_and_max;
        println!(
            "scalpel on {} triangles ({}): first frame {first:.1} ms, press {press_ms:.1} ms; \
             {} steps:\n  delta: step ms {} (of which the delta {}), frame ms {}, UI thread ms \
             {}, MB uploaded {}; release {release_ms:.1} ms + frame {after_release:.1} ms\n  \
             whole: copy ms {}, frame ms {}, UI thread ms {}, MB uploaded {}",
            sphere.triangle_count(),
            renderer.adapter_name(),
            step_ms.len(),
            f(&step_ms),
            f(&delta_ms),
            f(&frame_ms),
            f(&total_ms),
            f(&bytes),
            f(&copy_ms),
            f(&whole_frame_ms),
            f(&whole_total_ms),
            f(&whole_bytes),
        );
    }
}
