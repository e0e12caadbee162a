//! Live re-cut while painting (the thesis's future work: the cut follows the brush): in Edit mode the view
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
//!
//! ## Drawn from the cut's delta
//! The boolean returns the kept part as a delta against the cached target (faces removed, kept
//! pieces of split faces added). A model cut by one cutter is shown from that delta
//! ([`crate::cutting::delta`]): the model's mesh stays in its GPU buffers as it was uploaded, the
//! renderer hides the removed faces (and the ring of faces whose vertex normals the cut changed)
//! in place and draws a small patch. So per re-cut the UI thread uploads the patch, the walls
//! and the contour, never the model; the O(N) work that remains (the per-model vertex-to-face
//! table, built once per mesh) runs here on the worker. A model with several cutters (each cuts
//! the closed result of the ones before) or whose cut the exact boolean refuses goes through
//! [`preview_geometry_with`] as before and is drawn by whole parts.

use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use csg::Mesh;

use super::cut_scene::{
    CutCache, PartKind, PreviewGeometry, PreviewPart, cutter_mesh, preview_geometry_with,
};
use crate::cutting::delta::{self, MeshDelta, VertexFaces};
use crate::scene::{CutterViews, Scene, SceneCutter};

use super::scene_cuts::PreviewKey;

/// Wakes whoever shows the result (the window asks for a repaint) once a cut is ready.
pub type Repaint = Arc<dyn Fn() + Send + Sync>;

/// A finished live cut.
#[derive(Clone)]
pub struct LiveResult {
    /// Walls and contours of every cut model; the kept parts of models cut by several cutters
    /// (the others' kept parts are in `deltas`).
    pub geometry: Arc<PreviewGeometry>,
    /// The kept part of each model cut by one cutter, as a delta against the model's mesh.
    pub deltas: Vec<Arc<MeshDelta>>,
    /// The scene state it was computed for.
    pub key: LiveKey,
    /// Wall time of the cut in milliseconds (index builds included when they happened).
    pub ms: f64,
}

struct Request {
    scene: Scene,
    key: LiveKey,
    /// Called when the result is ready (None in tests).
    repaint: Option<Repaint>,
}

#[derive(Default)]
struct Slot {
    /// The newest request the worker has not taken yet.
    request: Option<Request>,
    /// Set when the owner is dropped: the worker exits at its next wait.
    shutdown: bool,
    /// Requests replaced in the slot before the worker took them (latest wins).
    dropped: u64,
    /// Set by [`LiveCut::clear`]: the worker drops its caches before its next request.
    forget: bool,
    /// What the worker's caches held after its last request (or after forgetting them).
    census: LiveCensus,
}

/// What the live-cut worker keeps between cuts (see [`LiveCut::census`]).
pub use crate::platform::memory_census::LiveCensus;

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
    requested: Option<LiveKey>,
    /// The newest finished cut, shown in Edit mode.
    shown: Option<LiveResult>,
    /// Cuts finished so far.
    pub finished: u64,
    /// A request was made since the worker last dropped its caches.
    worker_caches: bool,
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
            worker_caches: false,
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

/// What a live cut depends on: the cutters and their target meshes (as Preview's), and whether
/// each cutter's target is drawn solid. A solid model's kept part is drawn as a delta against its
/// mesh, a wireframe's from whole cut parts (its edges come from the mesh the delta would leave
/// uncut), so turning a cut model to wireframe or back is a new state to cut.
#[derive(Clone, Debug, PartialEq)]
pub struct LiveKey {
    cut: PreviewKey,
    solid_targets: Vec<bool>,
}

impl LiveKey {
    pub fn of(scene: &Scene) -> LiveKey {
        LiveKey {
            cut: PreviewKey::of(scene),
            solid_targets: scene
                .cutters
                .iter()
                .map(|c| {
                    scene
                        .models
                        .get(c.target)
                        .is_some_and(|m| m.style == crate::scene::ModelStyle::Solid)
                })
                .collect(),
        }
    }
}

impl LiveCut {
    /// Asks for the live cut of `scene` (its cutters as Normal Cuts). Does nothing when that
    /// state was already requested; replaces a request the worker has not started (latest wins).
    /// Returns true when a request was made. Never blocks on a cut.
    pub fn request(&mut self, scene: &Scene, repaint: Option<Repaint>) -> bool {
        let scene = live_scene(scene);
        let key = LiveKey::of(&scene);
        if self.requested.as_ref() == Some(&key) {
            return false;
        }
        if self.results.is_none() && !self.start_worker() {
            return false;
        }
        self.requested = Some(key.clone());
        self.worker_caches = true;
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

    /// The kept parts drawn as deltas in Edit mode (with [`LiveCut::geometry`]).
    pub fn deltas(&self) -> Vec<Arc<MeshDelta>> {
        self.shown
            .as_ref()
            .map(|r| r.deltas.clone())
            .unwrap_or_default()
    }

    /// True while the newest request has no result yet.
    pub fn pending(&self) -> bool {
        self.requested.is_some() && self.requested.as_ref() != self.shown.as_ref().map(|r| &r.key)
    }

    /// Requests replaced before the worker took them (latest wins).
    pub fn dropped(&self) -> u64 {
        self.shared.slot.lock().map(|s| s.dropped).unwrap_or(0)
    }

    /// True when a cut is shown or requested (what [`LiveCut::clear`] would forget).
    pub fn holds_a_cut(&self) -> bool {
        self.shown.is_some() || self.requested.is_some()
    }

    /// Forgets what was shown (Edit mode was left, the scene was replaced, or has no cutters
    /// left), and has the worker drop its caches: outside Edit mode nothing asks for a live cut,
    /// so the indexes, face tables and cuts of every cut model would otherwise stay in memory
    /// through Preview and Camera. Coming back to Edit mode cuts the models again in the
    /// background (each index is built again; the view shows the cut when it is ready).
    pub fn clear(&mut self) {
        self.shown = None;
        self.requested = None;
        if !std::mem::take(&mut self.worker_caches) {
            return;
        }
        if let Ok(mut slot) = self.shared.slot.lock() {
            slot.request = None;
            slot.forget = true;
        }
        self.shared.wake.notify_all();
    }

    /// What the worker's caches held after its last request (the memory test prints it).
    pub fn census(&self) -> LiveCensus {
        self.shared
            .slot
            .lock()
            .map(|s| s.census)
            .unwrap_or_default()
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
    let mut cache = LiveCache::default();
    loop {
        let request = {
            let Ok(mut slot) = shared.slot.lock() else {
                return;
            };
            loop {
                if slot.shutdown {
                    return;
                }
                if slot.forget {
                    slot.forget = false;
                    cache = LiveCache::default();
                    slot.census = cache.census();
                    // The caches were model-sized and freed on this thread: hand the pages back.
                    crate::platform::free_pages::trim_now();
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
            let drawn = live_geometry(&request.scene, &mut cache);
            cache.forget_unused();
            drawn
        }));
        let (geometry, deltas) = match computed {
            Ok(g) => g,
            Err(_) => {
                // A bug in a cut must not take the window down: show the scene uncut, note why.
                cache = LiveCache::default();
                let geometry = PreviewGeometry {
                    replaced: vec![false; request.scene.models.len()],
                    notes: vec!["the live cut failed (internal error); see Preview".into()],
                    ..PreviewGeometry::default()
                };
                (geometry, Vec::new())
            }
        };
        if let Ok(mut slot) = shared.slot.lock() {
            slot.census = cache.census();
        }
        let result = LiveResult {
            geometry: Arc::new(geometry),
            deltas,
            key: request.key,
            ms: started.elapsed().as_secs_f64() * 1000.0,
        };
        if results.send(result).is_err() {
            return;
        }
        if let Some(repaint) = request.repaint {
            repaint();
        }
    }
}

/// What the worker keeps between cuts: the exact indexes and cut prefixes ([`CutCache`]), the
/// vertex-to-face table of each model mesh (for the deltas' normals), and the last live cut of
/// each model (so a model whose cutter did not change is not cut again and keeps its delta, which
/// the renderer then does not touch).
///
/// Each entry is kept while the newest request uses it and dropped after the first request that
/// does not ([`LiveCache::forget_unused`]): the cache holds what the current live view is made
/// of, whatever the number of cutters or the history of the session, never a copy per past state.
#[derive(Default)]
struct LiveCache {
    cuts: CutCache,
    /// Per mesh: its vertex-to-face table, and whether this request used it.
    faces: Vec<(std::sync::Weak<Mesh>, Arc<VertexFaces>, bool)>,
    /// Per mesh: the cutter of its last live cut, the cut, and whether this request used it.
    models: Vec<(std::sync::Weak<Mesh>, SceneCutter, ModelLive, bool)>,
}

/// The live cut of one model by one cutter.
#[derive(Clone)]
struct ModelLive {
    walls: Arc<Mesh>,
    contours: Arc<Vec<Vec<glam::DVec3>>>,
    kept: Arc<MeshDelta>,
}

impl LiveCache {
    fn faces(&mut self, mesh: &Arc<Mesh>) -> Arc<VertexFaces> {
        if let Some((_, f, used)) = self
            .faces
            .iter_mut()
            .find(|(w, _, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
        {
            *used = true;
            return f.clone();
        }
        let faces = Arc::new(VertexFaces::build(mesh));
        self.faces.push((Arc::downgrade(mesh), faces.clone(), true));
        faces
    }

    fn census(&self) -> LiveCensus {
        LiveCensus {
            cuts: self.cuts.census(),
            face_tables: self.faces.len(),
            model_cuts: self.models.len(),
        }
    }

    /// Drops what the request just answered did not use (see [`LiveCache`]).
    fn forget_unused(&mut self) {
        self.cuts.forget_unused();
        self.faces
            .retain(|(w, _, used)| *used && w.strong_count() > 0);
        self.models
            .retain(|(w, _, _, used)| *used && w.strong_count() > 0);
        for (_, _, used) in &mut self.faces {
            *used = false;
        }
        for (_, _, _, used) in &mut self.models {
            *used = false;
        }
    }

    /// The live cut of `mesh` (incision walls `walls`, which belong to it) by `cutter` (None:
    /// the exact boolean refused it).
    fn model(
        &mut self,
        mesh: &Arc<Mesh>,
        walls: &[u32],
        cutter: &SceneCutter,
    ) -> Option<ModelLive> {
        if let Some((_, _, live, used)) = self
            .models
            .iter_mut()
            .find(|(w, c, _, _)| c == cutter && w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
        {
            *used = true;
            return Some(live.clone());
        }
        let index = self.cuts.index(mesh).ok()?;
        let surface = cutter_mesh(cutter);
        let live = if surface.is_empty() {
            ModelLive {
                walls: Arc::default(),
                contours: Arc::default(),
                kept: Arc::new(MeshDelta {
                    base: mesh.clone(),
                    ..MeshDelta::default()
                }),
            }
        } else {
            let result = csg::subtract(&index, &surface).ok()?;
            let faces = self.faces(mesh);
            let kept = Arc::new(delta::of_cut(mesh, &faces, &result, walls));
            let contours = crate::cutting::cut_scene::contour_polylines(result.contours);
            ModelLive {
                walls: Arc::new(result.walls.mesh),
                contours: Arc::new(contours),
                kept,
            }
        };
        // One entry per mesh: older states of an edited cutter are never asked for again.
        self.models
            .retain(|(w, _, _, _)| !w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)));
        self.models
            .push((Arc::downgrade(mesh), cutter.clone(), live.clone(), true));
        Some(live)
    }
}

/// The live cut of `scene` (its cutters as Normal Cuts): models cut by one cutter as deltas
/// (walls and contour in the geometry), the others by [`preview_geometry_with`].
fn live_geometry(scene: &Scene, cache: &mut LiveCache) -> (PreviewGeometry, Vec<Arc<MeshDelta>>) {
    let mut geometry = PreviewGeometry {
        replaced: vec![false; scene.models.len()],
        ..PreviewGeometry::default()
    };
    let mut deltas = Vec::new();
    let mut rest = scene.clone();
    for (m, model) in scene.models.iter().enumerate() {
        let cutters: Vec<usize> = (0..scene.cutters.len())
            .filter(|&c| scene.cutters[c].target == m && scene.cutters[c].views.any())
            .collect();
        // A wireframe is drawn from the mesh's edges, which a delta does not patch.
        let [c] = cutters[..] else { continue };
        if model.style != crate::scene::ModelStyle::Solid {
            continue;
        }
        let Some(live) = cache.model(&model.model.mesh, model.wall_faces(), &scene.cutters[c])
        else {
            continue;
        };
        // Drawn here: the remaining scene leaves this cutter out.
        rest.cutters[c].views = CutterViews {
            cut: false,
            transparency: None,
            ribbons: None,
            slices: None,
        };
        geometry.replaced[m] = true;
        if !live.walls.is_empty() {
            geometry.parts.push(PreviewPart {
                model: m,
                cutter: c,
                kind: PartKind::Wall,
                opacity: 1.0,
                mesh: Mesh::clone(&live.walls),
            });
        }
        geometry
            .contours
            .extend(live.contours.iter().map(|line| (m, line.clone())));
        deltas.push(live.kept);
    }
    if rest.cutters.iter().any(|c| c.views.any()) {
        let others = preview_geometry_with(&rest, &mut cache.cuts);
        for (r, o) in geometry.replaced.iter_mut().zip(&others.replaced) {
            *r |= *o;
        }
        geometry.parts.extend(others.parts);
        geometry.contours.extend(others.contours);
        geometry.notes.extend(others.notes);
    }
    (geometry, deltas)
}

#[cfg(test)]
mod tests;

/// The live cut driven by the editor on the embedded knee, as the window does it: the editor
/// makes a cutter on the skin and extrudes it move by move; after every move the live cut of the
/// new cutter is requested and awaited. Prints the re-cut time per move (the status line's "last
/// cut"); for release figures run
/// `cargo test --release -p cutaway --lib live_cut_follows_the_editor_on_the_knee -- --nocapture`.
#[cfg(test)]
mod knee_tests;

/// The live cut drawn from its delta looks exactly as the whole kept part did, and a re-cut
/// uploads only what changed.
#[cfg(test)]
mod view_tests;

/// The UI thread's cost of a live re-cut on a 2M-triangle model: what a frame does when a new
/// live cut arrives (take it, hand it to the renderer, which uploads what changed). Prints
/// figures; no timing assertion, so it is ignored in `cargo test`; run it with
/// `WGPU_BACKEND=vulkan cargo test -p cutaway --lib ui_thread_cost -- --ignored --nocapture`.
#[cfg(test)]
mod timings_tests;
