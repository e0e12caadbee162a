//! The risk map of the cut on screen, computed on a worker (the distances are
//! [`crate::cutting::wall_risk`]'s): when the cut or the risk settings changed, the cut is mapped
//! again, one job at a time, keeping the critical structures' indexes between jobs. A map is
//! given only for the cut and the settings it was computed for, so a view never draws a map of
//! another cut. egui-free: the window says which cut is on screen and how to wake it.

use std::sync::{Arc, Mutex, Weak};

use crate::cutting::cut_scene::PreviewGeometry;
use crate::cutting::wall_risk::{CriticalIndexes, RiskKey, WallRisk, wall_risk};
use crate::platform::jobs::Job;
use crate::scene::Scene;

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

fn same(source: &Weak<PreviewGeometry>, cut: &Arc<PreviewGeometry>) -> bool {
    source.upgrade().is_some_and(|s| Arc::ptr_eq(&s, cut))
}

impl RiskMap {
    /// True while a map is being computed.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    /// Takes a finished map, if the worker has one.
    pub fn poll(&mut self) {
        if let Some((source, key, job)) = &mut self.job
            && let Some(result) = job.poll()
        {
            match result {
                Ok(risk) => {
                    self.last_ms = Some(job.started.elapsed().as_secs_f64() * 1000.0);
                    self.failed = None;
                    self.shown = Some(Computed {
                        source: source.clone(),
                        key: key.clone(),
                        risk: risk.map(Arc::new),
                    });
                }
                Err(e) => self.failed = Some(crate::platform::errors::error_line(&e)),
            }
            self.job = None;
        }
    }

    /// Forgets the map shown (the map is switched off).
    pub fn clear(&mut self) {
        self.shown = None;
    }

    /// Starts mapping `cut` with `scene`'s risk settings, unless its map is there or a job runs;
    /// the worker calls `wake` when it is done.
    pub fn request(
        &mut self,
        scene: &Scene,
        cut: &Arc<PreviewGeometry>,
        wake: impl Fn() + Send + 'static,
    ) {
        let key = RiskKey::of(scene);
        let current = self
            .shown
            .as_ref()
            .is_some_and(|c| same(&c.source, cut) && c.key == key);
        if current || self.job.is_some() {
            return;
        }
        let scene = scene.clone();
        let indexes = self.indexes.clone();
        let worker_cut = cut.clone();
        let job = Job::spawn("Mapping the walls' distances", wake, move |_| {
            let mut indexes = indexes
                .lock()
                .map_err(|_| anyhow::anyhow!("the risk map's indexes are unusable"))?;
            Ok(wall_risk(&scene, &worker_cut, &mut indexes))
        });
        self.job = Some((Arc::downgrade(cut), key, job));
    }

    /// The map of `cut`, when one was computed for it and `scene`'s current risk settings.
    pub fn of(&self, scene: &Scene, cut: &Arc<PreviewGeometry>) -> Option<Arc<WallRisk>> {
        let c = self.shown.as_ref()?;
        if !same(&c.source, cut) || c.key != RiskKey::of(scene) {
            return None;
        }
        c.risk.clone()
    }
}
