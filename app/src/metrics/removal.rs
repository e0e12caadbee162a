//! What the cuts take away from each structure: removed volume, removed surface area, wall
//! area, and each cutter's depth.
//!
//! The cutters of a model cut it in turn exactly as Preview does ([`cut_in_turn`]), so the numbers
//! describe the picture the user sees. For every step, with `before` the closed surface the
//! cutter cut (the model closed by the walls of the cutters before it) and `after` the closed
//! result:
//! - removed volume = vol(before) − vol(after). By the boolean's measure identity this equals
//!   vol(removed + reversed walls) of the step (checked by `csg::cutcheck` to 1e-9); both are
//!   signed volumes about the same origin (the model's box centre, which keeps the terms small),
//!   so only the rounding of the new vertices enters. It is reported only for closed models (an
//!   open surface encloses no volume);
//! - removed area = area of the model's own surface in `before` − in `after` (walls of earlier
//!   cutters that a later one removes are not the model's surface and are not counted);
//! - wall area = area of the walls the cutter leaves in the final result (a later cutter may take
//!   some of them away);
//! - depth = how far the cut reaches below the surface along the cutter's depth direction (the
//!   mean of its planes' front → back directions): from the shallowest point of the model
//!   surface it removed to the deepest point of its removed piece or walls. Exact for straight
//!   cutters (one direction); for a curved cutter it is measured along the mean direction.
//!
//! Cuts must be exact: when the boolean refuses a cutter the measurement fails instead of
//! measuring the approximate stand-in.

use std::sync::Arc;

use csg::Mesh;
use glam::DVec3;

use crate::cutting::cut_scene::{CutCache, SURFACE, cut_in_turn};
use crate::scene::{Scene, SceneCutter};

/// The measures of one cutter.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CutterMeasures {
    /// Scene index of the cutter (0-based).
    pub index: usize,
    /// Name of the structure it cuts.
    pub target: String,
    /// mm³; `None` when the structure is not closed.
    pub removed_volume: Option<f64>,
    /// mm².
    pub removed_area: f64,
    /// mm².
    pub wall_area: f64,
    /// mm.
    pub depth: f64,
}

/// The cut of one model by all of its cutters.
#[derive(Clone, Debug)]
pub struct ModelCut {
    /// Index in `Scene::models`.
    pub model: usize,
    /// T ∖ (K1 ∪ … ∪ Kn), welded: the kept surface closed by the walls.
    pub closed: Arc<Mesh>,
    /// Per triangle of `closed`: [`SURFACE`] or the scene index of the cutter whose wall it is.
    pub tags: Arc<Vec<u32>>,
    /// Whether the model's own mesh is closed (its volumes mean something).
    pub model_closed: bool,
    pub cutters: Vec<CutterMeasures>,
}

impl ModelCut {
    /// All walls left by the cuts (every triangle not of the model's own surface).
    pub fn walls(&self) -> Mesh {
        crate::cutting::cut_scene::select(&self.closed, |t| self.tags[t] != SURFACE)
    }
}

/// Cuts every model that has cutters showing anything (as Preview does) and measures each step.
/// Fails, naming the cutter, when a cut could not be made exactly.
pub fn cut_models(scene: &Scene) -> anyhow::Result<Vec<ModelCut>> {
    let mut cache = CutCache::default();
    let mut out = Vec::new();
    for (m, model) in scene.models.iter().enumerate() {
        let cutters: Vec<(usize, &SceneCutter)> = scene
            .cutters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.target == m && c.views.any())
            .collect();
        if cutters.is_empty() {
            continue;
        }
        let model_closed = model.model.mesh.report().closed;
        let origin = model.model.mesh.bbox().center();
        let mut measures = Vec::new();
        let sequence = cut_in_turn(
            &mut cache,
            &model.model.mesh,
            &cutters,
            |_| false,
            |step| {
                let walls = (0..step.after.triangle_count())
                    .filter(|&t| step.after_tags[t] == step.cutter as u32)
                    .flat_map(|t| step.after.corners(t));
                let depth = cut_depth(&scene.cutters[step.cutter], step.removed, walls);
                let volume =
                    volume_about(step.before_mesh, origin) - volume_about(step.after, origin);
                let removed_area = surface_area(step.before_mesh, step.before_tags)
                    - surface_area(step.after, step.after_tags);
                measures.push(CutterMeasures {
                    index: step.cutter,
                    target: model.model.name.clone(),
                    removed_volume: model_closed.then_some(volume),
                    removed_area,
                    wall_area: 0.0,
                    depth,
                });
            },
        );
        if let Some(note) = sequence.notes.first() {
            anyhow::bail!("{}: {note}; metrics need exact cuts", model.model.name);
        }
        for measure in &mut measures {
            let tag = measure.index as u32;
            measure.wall_area = (0..sequence.closed.triangle_count())
                .filter(|&t| sequence.tags[t] == tag)
                .map(|t| sequence.closed.face_normal_scaled(t).length() * 0.5)
                .sum();
        }
        out.push(ModelCut {
            model: m,
            closed: sequence.closed,
            tags: sequence.tags,
            model_closed,
            cutters: measures,
        });
    }
    Ok(out)
}

/// The extent along `cutter`'s mean depth direction from the shallowest point of `removed` (the
/// model surface it took) to the deepest point of `removed` and `walls` (0 when it took none).
fn cut_depth(cutter: &SceneCutter, removed: &Mesh, walls: impl Iterator<Item = DVec3>) -> f64 {
    let direction = cutter
        .cutter
        .planes
        .iter()
        .map(|p| (p.back_top - p.front_top) + (p.back_bottom - p.front_bottom))
        .sum::<DVec3>()
        .try_normalize();
    let Some(direction) = direction else {
        return 0.0;
    };
    let used = removed
        .triangles
        .iter()
        .flatten()
        .map(|&v| removed.positions[v as usize]);
    let shallowest = used
        .clone()
        .map(|p| p.dot(direction))
        .fold(f64::INFINITY, f64::min);
    if !shallowest.is_finite() {
        return 0.0;
    }
    let deepest = used
        .chain(walls)
        .map(|p| p.dot(direction))
        .fold(f64::NEG_INFINITY, f64::max);
    deepest - shallowest
}

/// Signed volume enclosed by `mesh`, as the sum of the tetrahedra from `origin` to its triangles.
fn volume_about(mesh: &Mesh, origin: DVec3) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize] - origin);
            a.dot(b.cross(c))
        })
        .sum::<f64>()
        / 6.0
}

/// Area of the triangles of `mesh` tagged [`SURFACE`].
fn surface_area(mesh: &Mesh, tags: &[u32]) -> f64 {
    (0..mesh.triangle_count())
        .filter(|&t| tags[t] == SURFACE)
        .map(|t| mesh.face_normal_scaled(t).length() * 0.5)
        .sum()
}
