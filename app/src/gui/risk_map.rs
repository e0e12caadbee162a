//! The window's side of the risk map (the distances are [`crate::cutting::wall_risk`]'s): once
//! per frame, take a finished map and, when the cut on screen or the risk settings changed, map
//! the cut again on a worker, one job at a time, keeping the critical structures' indexes
//! between jobs. A map is drawn only on the cut it was computed for: while a new one is being
//! computed, or while the cutter is dragged in Edit mode (the live cut changes every frame), the
//! walls show their own colour rather than a map of another cut.

use std::sync::{Arc, Mutex, Weak};

use crate::cutting::cut_scene::PreviewGeometry;
use crate::cutting::wall_risk::{CriticalIndexes, RiskKey, WallRisk, wall_risk};
use crate::gui::action::Mode;
use crate::gui::jobs::Job;
use crate::gui::state::AppState;

/// A map and what it was computed for.
struct Computed {
    source: Weak<PreviewGeometry>,
    key: RiskKey,
    risk: Option<Arc<WallRisk>>,
}

/// The risk map's worker and its newest result.
#[derive(Default)]
pub struct RiskMap {
    shown: Option<Computed>,
    job: Option<(Weak<PreviewGeometry>, RiskKey, Job<Option<WallRisk>>)>,
    /// The critical structures' indexes, shared with the worker.
    indexes: Arc<Mutex<CriticalIndexes>>,
    /// Wall time of the newest map in milliseconds.
    pub last_ms: Option<f64>,
    /// Why the newest map failed (one line), if it did.
    pub failed: Option<String>,
}

impl RiskMap {
    /// True while a map is being computed.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }
}

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

fn same(source: &Weak<PreviewGeometry>, cut: &Arc<PreviewGeometry>) -> bool {
    source.upgrade().is_some_and(|s| Arc::ptr_eq(&s, cut))
}

/// Once per frame: takes a finished map and starts the next one when needed.
pub fn update(app: &mut AppState, ctx: &egui::Context) {
    let map = &mut app.viewport.risk;
    if let Some((source, key, job)) = &mut map.job
        && let Some(result) = job.poll()
    {
        match result {
            Ok(risk) => {
                map.last_ms = Some(job.started.elapsed().as_secs_f64() * 1000.0);
                map.failed = None;
                map.shown = Some(Computed {
                    source: source.clone(),
                    key: key.clone(),
                    risk: risk.map(Arc::new),
                });
            }
            Err(e) => map.failed = Some(crate::platform::errors::error_line(&e)),
        }
        map.job = None;
    }
    if !app.scene.risk.is_on() {
        app.viewport.risk.shown = None;
        return;
    }
    let Some(cut) = cut_on_screen(app) else {
        return;
    };
    if app.mode == Mode::Edit && app.viewport.editor_dragging() {
        return;
    }
    let key = RiskKey::of(&app.scene);
    let map = &mut app.viewport.risk;
    let current = map
        .shown
        .as_ref()
        .is_some_and(|c| same(&c.source, &cut) && c.key == key);
    if current || map.job.is_some() {
        return;
    }
    let scene = app.scene.clone();
    let indexes = map.indexes.clone();
    let worker_cut = cut.clone();
    let repaint = ctx.clone();
    let job = Job::spawn(
        "Mapping the walls' distances",
        move || repaint.request_repaint(),
        move |_| {
            let mut indexes = indexes
                .lock()
                .map_err(|_| anyhow::anyhow!("the risk map's indexes are unusable"))?;
            Ok(wall_risk(&scene, &worker_cut, &mut indexes))
        },
    );
    map.job = Some((Arc::downgrade(&cut), key, job));
}

/// The map of the cut on screen, when one was computed for it and the current settings.
pub fn current(app: &AppState) -> Option<Arc<WallRisk>> {
    if !app.scene.risk.is_on() || (app.mode == Mode::Edit && app.viewport.editor_dragging()) {
        return None;
    }
    let cut = cut_on_screen(app)?;
    let c = app.viewport.risk.shown.as_ref()?;
    if !same(&c.source, &cut) || c.key != RiskKey::of(&app.scene) {
        return None;
    }
    c.risk.clone()
}
