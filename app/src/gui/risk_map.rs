//! The window's side of the risk map (the worker is [`crate::cutting::risk_worker`]): which cut is
//! on screen, and when a map is drawn. A map is drawn only on the cut it was computed for: while
//! a new one is being computed, or while the cutter is dragged in Edit mode (the live cut changes
//! every frame), the walls show their own colour rather than a map of another cut.

use std::sync::Arc;

use crate::cutting::cut_scene::PreviewGeometry;
use crate::cutting::wall_risk::WallRisk;
use crate::gui::action::Mode;
use crate::gui::state::AppState;

/// The cut whose walls the view shows now: the live cut in Edit mode, the computed cut in the
/// modes that show it.
fn cut_on_screen(app: &AppState) -> Option<Arc<PreviewGeometry>> {
    if app.scene.cutters.is_empty() {
        return None;
    }
    match app.mode {
        Mode::Edit if app.viewport.live.enabled => app.viewport.live.geometry(),
        Mode::Edit => None,
        Mode::Camera | Mode::Preview | Mode::Scalpel => app.viewport.preview.clone(),
    }
}

/// Once per frame: takes a finished map and starts the next one when needed.
pub fn update(app: &mut AppState, ctx: &egui::Context) {
    app.viewport.risk.poll();
    if !app.scene.risk.is_on() {
        app.viewport.risk.clear();
        return;
    }
    let Some(cut) = cut_on_screen(app) else {
        return;
    };
    if app.mode == Mode::Edit && app.viewport.editor_dragging() {
        return;
    }
    let repaint = ctx.clone();
    app.viewport
        .risk
        .request(&app.scene, &cut, move || repaint.request_repaint());
}

/// The map of the cut on screen, when one was computed for it and the current settings.
pub fn current(app: &AppState) -> Option<Arc<WallRisk>> {
    if !app.scene.risk.is_on() || (app.mode == Mode::Edit && app.viewport.editor_dragging()) {
        return None;
    }
    let cut = cut_on_screen(app)?;
    app.viewport.risk.of(&app.scene, &cut)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gui::app::StartOptions;
    use crate::scene::risk::RiskSettings;
    use crate::scene::{ModelUnit, Scene, SceneCutter, SceneModel};
    use glam::DVec3;

    /// A session of an 80 mm block cut in front of y = 0 and a vessel 1 mm behind that wall,
    /// with the vessel critical; returns its path.
    fn session(dir: &std::path::Path) -> std::path::PathBuf {
        let mut scene = Scene::default();
        for (name, mesh) in [
            (
                "tissue",
                csg::testkit::cube(DVec3::splat(-40.0), DVec3::splat(40.0)),
            ),
            ("vessel", {
                let mut m = csg::testkit::icosphere(3, 5.0);
                for p in &mut m.positions {
                    p.y += 6.0;
                }
                m
            }),
        ] {
            let path = dir.join(format!("{name}.ply"));
            crate::io::write_mesh(&path, &mesh).unwrap();
            let mut model = SceneModel::new(name, path, Arc::new(mesh), [0.8, 0.6, 0.5]);
            model.unit = ModelUnit::Structure;
            scene.models.push(model);
        }
        let plane = |x: f64| {
            cutter::BoundedPlane::from_corners([
                DVec3::new(x, -60.0, 20.0),
                DVec3::new(x, 0.0, 20.0),
                DVec3::new(x, 0.0, -20.0),
                DVec3::new(x, -60.0, -20.0),
            ])
        };
        scene.cutters.push(SceneCutter::new(
            0,
            cutter::Cutter {
                kind: cutter::CutKind::Straight,
                smooth: false,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                planes: vec![plane(-20.0), plane(20.0)],
                direction: cutter::CutDirection::Normal,
            },
        ));
        scene.camera = scene.framing_camera();
        scene.risk = RiskSettings {
            critical: vec!["vessel".into()],
            ..RiskSettings::default()
        };
        let path = dir.join("risk.json");
        crate::session::save(&path, &scene).unwrap();
        path
    }

    /// The window maps the cut on a worker, draws the map only on the cut it was computed for,
    /// and draws none once the map is switched off.
    #[test]
    fn the_window_draws_the_map_of_the_cut_on_screen_only() {
        let dir = std::env::temp_dir().join(format!("cutaway-risk-map-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let start = StartOptions {
            paths: vec![session(&dir)],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = crate::gui::test_window::open(start, 1280.0, 800.0);
        let ctx = h.ctx.clone();
        h.state_mut()
            .apply(&ctx, crate::gui::action::Action::SetMode(Mode::Preview));
        crate::gui::test_window::settle(&mut h);
        let map = current(h.state()).expect("a map of the cut on screen");
        let nearest = map.nearest.clone().expect("a nearest wall");
        assert_eq!(nearest.structure, "vessel");
        assert!(
            (0.9..1.1).contains(&nearest.distance_mm),
            "{}",
            nearest.distance_mm
        );
        let inputs = crate::gui::bridge::frame_inputs(h.state(), [640, 400]);
        assert!(inputs.risk.is_some_and(|r| Arc::ptr_eq(&r, &map)));

        // The cutter moves: the old map stays on the old cut while that is on screen, and is
        // not drawn on the new cut once it is.
        let old_cut = h
            .state()
            .viewport
            .preview
            .clone()
            .expect("the cut on screen");
        {
            let app = h.state_mut();
            let planes = &mut app.scene.cutters[0].cutter.planes;
            for plane in planes.iter_mut() {
                *plane = cutter::BoundedPlane::from_corners(
                    plane.corners().map(|p| p - DVec3::new(0.0, 2.0, 0.0)),
                );
            }
        }
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        loop {
            h.step();
            let shown = h.state().viewport.preview.clone();
            if shown.is_some_and(|p| !Arc::ptr_eq(&p, &old_cut)) {
                break;
            }
            if let Some(m) = current(h.state()) {
                assert!(Arc::ptr_eq(&m, &map), "a map of another cut");
            }
            assert!(
                std::time::Instant::now() < deadline,
                "the cut was not redone"
            );
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        let drawn = crate::gui::bridge::frame_inputs(h.state(), [640, 400]).risk;
        assert!(
            drawn.is_none_or(|m| !Arc::ptr_eq(&m, &map)),
            "the old map is drawn on the new cut"
        );
        crate::gui::test_window::settle(&mut h);
        let moved = current(h.state()).expect("the moved cut is mapped");
        let d = moved.nearest.as_ref().unwrap().distance_mm;
        assert!((2.9..3.1).contains(&d), "{d}");

        h.state_mut().scene.risk.shown = false;
        h.step();
        assert!(current(h.state()).is_none());
        assert!(
            crate::gui::bridge::frame_inputs(h.state(), [640, 400])
                .risk
                .is_none()
        );
    }
}
