//! The layers below a stroke in the window's scene, and the pieces a loop detaches.
//!
//! Each structure is a model of its own, so the surfaces under the touched one (muscle under
//! skin) are the other visible models. When a groove stroke commits, the blade below each of
//! its samples is cast against them as they were before the stroke, and every model it meets
//! within the depth is cut with strokes of its own, with the depth left there: the one strategy
//! of `cutter::scalpel::layers`, which `cutaway scalpel` uses through this same code. They go
//! into the scene with the top cut, so the stroke stays one undo step for all of them. A model
//! whose strokes the scalpel refuses keeps its mesh (the same `Arc`) and is reported.

use std::collections::HashSet;
use std::sync::Arc;

use glam::DVec3;

use csg::{Mesh, SpatialIndex};
use cutter::scalpel::StrokeReport;
use cutter::scalpel::layers::{LayerStroke, Surface, cut_layer_walls, reach, strokes_below};

use super::ScalpelSettings;
use crate::scene::Scene;

/// What [`cut_layers`] did.
#[derive(Debug, Default)]
pub(crate) struct LayersOutcome {
    /// Models cut, with what their strokes did (summed).
    pub(crate) cut: Vec<(usize, StrokeReport)>,
    /// Models the scalpel refused to cut, with why (each left exactly as it was).
    pub(crate) refused: Vec<(usize, String)>,
}

/// Cuts the layers below a committed stroke on `model` into the scene (see the module doc):
/// each model met gets its own scalpel strokes with the depth left there, opened like the top
/// cut, and becomes edited. `top_mesh` and `top_index` are the touched model's surface before
/// the stroke; `samples` the stroke's samples (`None` off the surface). `index_of` gives a model
/// mesh's spatial index; it is asked only for visible models whose bounds the blade reaches.
pub(crate) fn cut_layers(
    scene: &mut Scene,
    model: usize,
    top_mesh: &Mesh,
    top_index: &SpatialIndex,
    samples: &[Option<DVec3>],
    settings: &ScalpelSettings,
    index_of: &mut dyn FnMut(&Arc<Mesh>) -> Arc<SpatialIndex>,
) -> LayersOutcome {
    let depth = settings.depth.max(0.0);
    let Some(reach) = reach(samples, depth) else {
        return LayersOutcome::default();
    };
    let others: Vec<(usize, Arc<Mesh>, Arc<SpatialIndex>)> = scene
        .models
        .iter()
        .enumerate()
        .filter(|(i, m)| {
            *i != model
                && m.visible
                && m.opacity > 0.0
                && !m.model.mesh.triangles.is_empty()
                && m.model.mesh.bbox().overlaps(&reach)
        })
        .map(|(i, m)| (i, m.model.mesh.clone(), index_of(&m.model.mesh)))
        .collect();
    let surfaces: Vec<Surface> = others
        .iter()
        .map(|(i, mesh, index)| Surface {
            id: *i as u32,
            mesh,
            index,
        })
        .collect();
    let strokes = strokes_below(top_mesh, top_index, samples, depth, &surfaces);
    let mut outcome = LayersOutcome::default();
    let open = settings.open();
    for (target, mesh, _) in &others {
        let mine: Vec<&LayerStroke> = strokes
            .iter()
            .filter(|r| r.region as usize == *target)
            .collect();
        if mine.is_empty() {
            continue;
        }
        let walls = scene.models[*target].wall_faces();
        match cut_layer_walls(mesh, walls, &mine, settings.options(), &open) {
            Ok(Some((cut, walls, report))) => {
                if let Some(m) = scene.models.get_mut(*target) {
                    m.replace_mesh_with_walls(Arc::new(cut), walls);
                    outcome.cut.push((*target, report));
                }
            }
            Ok(None) => {}
            Err(e) => outcome.refused.push((*target, e.to_string())),
        }
    }
    outcome
}

/// `mesh` without the triangles of `pieces` (matched by their corner coordinates, bit for bit:
/// the pieces were copied out of this mesh), compacted; and which of the kept triangles are
/// walls, given the walls `walls` (ascending) of `mesh` (the triangles keep their order).
pub(crate) fn without_pieces_walls(
    mesh: &Mesh,
    pieces: &[Mesh],
    walls: &[u32],
) -> (Mesh, Vec<u32>) {
    type Key = [[u64; 3]; 3];
    let key = |corners: [DVec3; 3]| -> Key {
        corners.map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
    };
    let mut remove: HashSet<Key> = HashSet::new();
    for piece in pieces {
        for t in 0..piece.triangle_count() {
            remove.insert(key(piece.corners(t)));
        }
    }
    let kept: Vec<usize> = (0..mesh.triangle_count())
        .filter(|&t| !remove.contains(&key(mesh.corners(t))))
        .collect();
    let kept_walls = kept
        .iter()
        .enumerate()
        .filter(|&(_, &t)| walls.binary_search(&(t as u32)).is_ok())
        .map(|(k, _)| k as u32)
        .collect();
    let rest = Mesh {
        positions: mesh.positions.clone(),
        triangles: kept.iter().map(|&t| mesh.triangles[t]).collect(),
    };
    // Compacting renumbers vertices only: the triangles keep their order.
    (rest.compacted(), kept_walls)
}

/// A lighter shade of the model's colour for a piece cut out of it.
pub(crate) fn piece_colour(c: [f32; 3]) -> [f32; 3] {
    c.map(|x| (x * 0.6 + 0.4).min(1.0))
}
