//! Live re-cut while painting (issue 4 "Speed", the thesis's future work): in Edit mode the view
//! shows the cut result (kept part, walls, contour) under the translucent cutter, re-cut after
//! every change of the cutters.
//!
//! The cut never runs on the UI thread. One long-lived worker owns a [`CutCache`] (the exact
//! index of every target mesh, built once, and the closed results of earlier cutters of a model),
//! so a re-cut costs one boolean against a cached index. Requests go through a one-element slot:
//! a new request replaces one the worker has not taken yet (latest wins), so while the user
//! drags faster than the cut runs, intermediate states are skipped instead of queued, and the
//! view shows the newest finished cut until the next one is ready. A frame never waits for a cut.
//!
//! The live view is the Normal Cut of every cutter whatever its Visualization settings
//! (transparency, ribbons and slices are Preview's): that is what painting needs, and the cheapest
//! view to recompute.

use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use crate::cutaway_geometry::{CutCache, PreviewGeometry, preview_geometry_with};
use crate::scene::{CutterViews, Scene};

use super::bridge::PreviewKey;

/// A finished live cut.
#[derive(Clone)]
pub struct LiveResult {
    pub geometry: Arc<PreviewGeometry>,
    /// The cutters and target meshes it was computed for.
    pub key: PreviewKey,
    /// Wall time of the cut in milliseconds (index builds included when they happened).
    pub ms: f64,
}

struct Request {
    scene: Scene,
    key: PreviewKey,
    /// Woken when the result is ready (None in tests).
    repaint: Option<egui::Context>,
}

#[derive(Default)]
struct Slot {
    /// The newest request the worker has not taken yet.
    request: Option<Request>,
    /// Set when the owner is dropped: the worker exits at its next wait.
    shutdown: bool,
    /// Requests replaced in the slot before the worker took them (latest wins).
    dropped: u64,
}

struct Shared {
    slot: Mutex<Slot>,
    wake: Condvar,
}

/// The live-cut worker and what it last produced.
pub struct LiveCut {
    /// The "Live cut" toggle of the cutter panel (on by default).
    pub enabled: bool,
    shared: Arc<Shared>,
    results: Option<Receiver<LiveResult>>,
    /// Key of the newest request (one scene state is cut once).
    requested: Option<PreviewKey>,
    /// The newest finished cut, shown in Edit mode.
    shown: Option<LiveResult>,
    /// Cuts finished so far.
    pub finished: u64,
}

impl Default for LiveCut {
    fn default() -> Self {
        LiveCut {
            enabled: true,
            shared: Arc::new(Shared {
                slot: Mutex::new(Slot::default()),
                wake: Condvar::new(),
            }),
            results: None,
            requested: None,
            shown: None,
            finished: 0,
        }
    }
}

impl Drop for LiveCut {
    fn drop(&mut self) {
        // The worker may be inside a cut: never join it from the UI thread; it exits when it next
        // looks at the slot (its result has nowhere to go by then).
        if let Ok(mut slot) = self.shared.slot.lock() {
            slot.shutdown = true;
            slot.request = None;
        }
        self.shared.wake.notify_all();
    }
}

/// `scene` as the live cut shows it: every cutter with the Normal Cut view only.
pub fn live_scene(scene: &Scene) -> Scene {
    let mut live = scene.clone();
    for c in &mut live.cutters {
        c.views = CutterViews {
            cut: true,
            transparency: None,
            ribbons: None,
            slices: None,
        };
    }
    live
}

impl LiveCut {
    /// Asks for the live cut of `scene` (its cutters as Normal Cuts). Does nothing when that
    /// state was already requested; replaces a request the worker has not started (latest wins).
    /// Returns true when a request was made. Never blocks on a cut.
    pub fn request(&mut self, scene: &Scene, repaint: Option<egui::Context>) -> bool {
        let scene = live_scene(scene);
        let key = PreviewKey::of(&scene);
        if self.requested.as_ref() == Some(&key) {
            return false;
        }
        if self.results.is_none() && !self.start_worker() {
            return false;
        }
        self.requested = Some(key.clone());
        if let Ok(mut slot) = self.shared.slot.lock() {
            if slot.request.is_some() {
                slot.dropped += 1;
            }
            slot.request = Some(Request {
                scene,
                key,
                repaint,
            });
        }
        self.shared.wake.notify_all();
        true
    }

    fn start_worker(&mut self) -> bool {
        let (tx, rx) = channel();
        let shared = self.shared.clone();
        let spawned = std::thread::Builder::new()
            .name("cutaway live cut".into())
            .spawn(move || worker(&shared, &tx));
        match spawned {
            Ok(_) => {
                self.results = Some(rx);
                true
            }
            Err(_) => false,
        }
    }

    /// Takes finished cuts (the newest wins); true when the shown cut changed.
    pub fn poll(&mut self) -> bool {
        let Some(rx) = &self.results else {
            return false;
        };
        let mut changed = false;
        loop {
            match rx.try_recv() {
                Ok(result) => {
                    self.finished += 1;
                    self.shown = Some(result);
                    changed = true;
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    // The worker is gone (it panicked outside a cut): start afresh next request.
                    self.results = None;
                    self.requested = None;
                    break;
                }
            }
        }
        changed
    }

    /// The newest finished cut.
    pub fn shown(&self) -> Option<&LiveResult> {
        self.shown.as_ref()
    }

    /// The geometry to draw in Edit mode.
    pub fn geometry(&self) -> Option<Arc<PreviewGeometry>> {
        self.shown.as_ref().map(|r| r.geometry.clone())
    }

    /// True while the newest request has no result yet.
    pub fn pending(&self) -> bool {
        self.requested.is_some() && self.requested.as_ref() != self.shown.as_ref().map(|r| &r.key)
    }

    /// Requests replaced before the worker took them (latest wins).
    pub fn dropped(&self) -> u64 {
        self.shared.slot.lock().map(|s| s.dropped).unwrap_or(0)
    }

    /// Forgets what was shown (the scene was replaced, or has no cutters left).
    pub fn clear(&mut self) {
        self.shown = None;
        self.requested = None;
        if let Ok(mut slot) = self.shared.slot.lock() {
            slot.request = None;
        }
    }

    /// Waits until the newest request's result arrived (tests only; the UI polls).
    pub fn wait(&mut self, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        loop {
            self.poll();
            if !self.pending() {
                return self.shown.is_some();
            }
            if Instant::now() > deadline {
                return false;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// The worker: waits for a request, cuts, sends the result, repeats until shut down.
fn worker(shared: &Shared, results: &Sender<LiveResult>) {
    let mut cache = CutCache::default();
    loop {
        let request = {
            let Ok(mut slot) = shared.slot.lock() else {
                return;
            };
            loop {
                if slot.shutdown {
                    return;
                }
                if let Some(r) = slot.request.take() {
                    break r;
                }
                slot = match shared.wake.wait(slot) {
                    Ok(s) => s,
                    Err(_) => return,
                };
            }
        };
        let started = Instant::now();
        let computed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            preview_geometry_with(&request.scene, &mut cache)
        }));
        let geometry = match computed {
            Ok(g) => g,
            Err(_) => {
                // A bug in a cut must not take the window down: show the scene uncut, note why.
                cache = CutCache::default();
                PreviewGeometry {
                    replaced: vec![false; request.scene.models.len()],
                    notes: vec!["the live cut failed (internal error); see Preview".into()],
                    ..PreviewGeometry::default()
                }
            }
        };
        let result = LiveResult {
            geometry: Arc::new(geometry),
            key: request.key,
            ms: started.elapsed().as_secs_f64() * 1000.0,
        };
        if results.send(result).is_err() {
            return;
        }
        if let Some(ctx) = request.repaint {
            ctx.request_repaint();
        }
    }
}

/// Once per frame: takes a finished live cut (its time goes to the status line) and, in Edit
/// mode with "Live cut" on, asks for the cut of the current cutters.
pub fn update_live(app: &mut super::CutawayApp, ctx: &egui::Context) {
    let live = &mut app.viewport.live;
    if live.poll()
        && let Some(r) = live.shown()
    {
        app.status.last_cut_ms = Some(r.ms);
    }
    if app.mode != super::Mode::Edit || !live.enabled {
        // Outside Edit mode the models may change under it (Remove All Cut Geometry, loads):
        // start afresh when Edit mode comes back.
        if live.shown.is_some() || live.requested.is_some() {
            live.clear();
        }
        return;
    }
    if app.scene.cutters.is_empty() {
        live.clear();
        return;
    }
    live.request(&app.scene, Some(ctx.clone()));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutaway_geometry::PartKind;
    use crate::cutaway_geometry::tests::scene_with_cube_cut;
    use csg::Mesh;

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
        let mut closed = Mesh::default();
        for p in &g.parts {
            closed.append(&p.mesh);
        }
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
            scene.cutters[0].planes =
                crate::cutaway_geometry::tests::box_cutter(x, 3.0, -1.0, 1.0, 1.0, 3.0);
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
        let g = live.geometry().unwrap();
        let mut closed = Mesh::default();
        for p in &g.parts {
            closed.append(&p.mesh);
        }
        let expected = 8.0 - (2.0 - last_x);
        assert!(
            (closed.volume() - expected).abs() < 1e-9,
            "{} vs {expected}",
            closed.volume()
        );
    }
}

/// The live cut driven by the editor on the embedded knee, as the window does it: the editor
/// makes a cutter on the skin and extrudes it move by move; after every move the live cut of the
/// new cutter is requested and awaited. Prints the re-cut time per move (the status line's "last
/// cut"); for release figures run
/// `cargo test --release -p cutaway --lib live_cut_follows_the_editor_on_the_knee -- --nocapture`.
#[cfg(test)]
mod knee {
    use super::*;
    use crate::cutaway_geometry::PartKind;
    use crate::gui::app::CutterInit;
    use crate::gui::bridge::EditorSlot;
    use cutter::EditorEvent;
    use glam::DVec2;

    #[test]
    fn live_cut_follows_the_editor_on_the_knee() {
        let knee = crate::assets::scene("knee").expect("embedded knee");
        let mut scene = Scene::default();
        for model in crate::assets::load_scene(knee).expect("load the knee") {
            let color = crate::assets::default_color(&model.name);
            scene.models.push(crate::scene::SceneModel::new(
                model.name,
                model.source,
                Arc::new(model.mesh),
                color,
            ));
        }
        scene.camera = scene.framing_camera();
        let viewport = DVec2::new(1280.0, 800.0);
        let press = viewport * 0.5 + DVec2::new(-60.0, 0.0);
        let ray = scene.camera.ray_through_pixel(viewport, press);
        let (target, _) = crate::gui::viewport::pick(&scene, &ray).expect("the knee is in view");
        let mut slot = EditorSlot::default();
        assert!(slot.ensure(&scene, target, viewport, &CutterInit::default()));
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
        let lead = *scene.cutters[0].planes.last().unwrap();
        let handle = scene
            .camera
            .project(viewport, (lead[0] + lead[3]) * 0.5)
            .expect("handle in view");
        slot.handle(&mut scene, viewport, EditorEvent::press(handle.x, handle.y));
        let planes_before = scene.cutters[0].planes.clone();
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
            scene.cutters[0].planes, planes_before,
            "the drag did not extrude"
        );
        assert!(!times.is_empty());
        let mut sorted = times.clone();
        sorted.sort_by(f64::total_cmp);
        println!(
            "live re-cut of {} ({} triangles): first cut (index build included) {first:.1} ms; \
             {} re-cuts while painting: median {:.1} ms, max {:.1} ms",
            scene.models[target].name,
            scene.models[target].mesh.triangle_count(),
            times.len(),
            sorted[sorted.len() / 2],
            sorted[sorted.len() - 1],
        );
    }
}
