//! Strokes of surface points replayed through a [`ScalpelSession`], as the window would cut
//! them: `cutaway scalpel`, and the tests that compare it with the window.
//!
//! Each stroke is pressed on the model whose surface is nearest its first point (the window
//! presses on the model under the pointer), started there, stepped to each following point
//! and released, which commits it, cuts the layers below and detaches a loop's pieces as in
//! the window. The scene's meshes afterwards are what the window shows after the same strokes.

use std::sync::{Arc, Weak};
use std::time::Instant;

use glam::{DVec2, DVec3};

use csg::{Mesh, SpatialIndex};

use super::{Released, ScalpelSession};
use crate::scene::Scene;

/// What a replay did.
#[derive(Clone, Debug, Default)]
pub struct Replay {
    /// Microseconds per point: the press and first step for a stroke's first point, one step for
    /// each other point (the release is not a step).
    pub step_us: Vec<f64>,
    pub triangles_cut: usize,
    pub triangles_created: usize,
}

/// Why a replay stopped: the stroke and point (0-based) the scalpel refused, and why. The
/// scene keeps the strokes before it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("stroke {stroke} point {point}: {message}")]
pub struct ReplayError {
    pub stroke: usize,
    pub point: usize,
    pub message: String,
}

/// Replays `strokes` on `scene` through `session` (see the module doc). Every refusal is an
/// error: a step, a stroke that cannot end, a layer below that cannot be cut.
pub fn replay(
    session: &mut ScalpelSession,
    scene: &mut Scene,
    strokes: &[Vec<DVec3>],
) -> Result<Replay, ReplayError> {
    let mut out = Replay::default();
    let mut indexes: Vec<(Weak<Mesh>, Arc<SpatialIndex>)> = Vec::new();
    for (s, stroke) in strokes.iter().enumerate() {
        let fail = |point: usize, message: String| ReplayError {
            stroke: s,
            point,
            message,
        };
        let Some(&first) = stroke.first() else {
            continue;
        };
        let model = nearest_model(scene, first, &mut indexes)
            .ok_or_else(|| fail(0, "the scene has no surface to cut".to_string()))?;
        // The scalpel is made before the press (the window makes it when the model is selected),
        // so the first step's time is the cut's own.
        session.ready(scene, model).map_err(|e| fail(0, e))?;
        let start = Instant::now();
        let begun = session
            .press_at(scene, model, first, DVec2::ZERO)
            .and_then(|_| session.begin());
        out.step_us.push(start.elapsed().as_secs_f64() * 1e6);
        begun.map_err(|e| fail(0, e))?;
        for (k, &q) in stroke.iter().enumerate().skip(1) {
            let start = Instant::now();
            let r = session.step_to(scene, q);
            out.step_us.push(start.elapsed().as_secs_f64() * 1e6);
            r.map_err(|e| fail(k, e))?;
        }
        match session.release(scene) {
            Released::Nothing => {}
            Released::Failed(e) => return Err(fail(stroke.len() - 1, e)),
            Released::Committed { refused, .. } if !refused.is_empty() => {
                return Err(fail(stroke.len() - 1, refused.join("; ")));
            }
            Released::Committed { .. } => {}
        }
        if let Some(r) = &session.last_stroke {
            out.triangles_cut += r.triangles_cut;
            out.triangles_created += r.triangles_created;
        }
    }
    Ok(out)
}

/// The visible model whose surface is nearest `p` (indexes cached by mesh in `indexes`).
fn nearest_model(
    scene: &Scene,
    p: DVec3,
    indexes: &mut Vec<(Weak<Mesh>, Arc<SpatialIndex>)>,
) -> Option<usize> {
    indexes.retain(|(w, _)| w.strong_count() > 0);
    let mut best: Option<(usize, f64)> = None;
    for (i, m) in scene.models.iter().enumerate() {
        if !m.visible || m.model.mesh.triangles.is_empty() {
            continue;
        }
        let index = match indexes
            .iter()
            .find(|(w, _)| w.upgrade().is_some_and(|x| Arc::ptr_eq(&x, &m.model.mesh)))
        {
            Some((_, index)) => index.clone(),
            None => {
                let index = Arc::new(SpatialIndex::build(&m.model.mesh));
                indexes.push((Arc::downgrade(&m.model.mesh), index.clone()));
                index
            }
        };
        if let Some(cp) = index.closest_point(&m.model.mesh, p) {
            let d = cp.point.distance(p);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
    }
    best.map(|(i, _)| i)
}
