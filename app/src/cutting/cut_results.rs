//! What cuts produce: the parts of one cut, the parts Preview draws for a scene, how each cutter's
//! cut went, and the step of a sequence of cuts. Both the sequence and cache (`cut_scene.rs`)
//! and the single cut (`cut_parts.rs`) speak these types, so they live here and both import
//! them one way.

use csg::{Mesh, TargetIndex};
use glam::DVec3;

/// The three surfaces and the contour of one cut of a target by a closed cutter.
#[derive(Clone, Debug, Default)]
pub struct CutParts {
    /// The target outside the cutter, original orientation.
    pub kept: Mesh,
    /// The cutter surface inside the target, facing out of `kept`.
    pub walls: Mesh,
    /// The target inside the cutter.
    pub removed: Mesh,
    /// Where the target surface crosses the cutter surface, as polylines (closed loops repeat
    /// their first point at the end).
    pub contour: Vec<Vec<DVec3>>,
}

/// What a part of the preview is, which decides its colour and how it is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartKind {
    /// The target outside every cutter: the model's own colour, opacity and style.
    Kept,
    /// Cutter surface inside the target (normal cut): the wall colour, opaque.
    Wall,
    /// The removed piece with the Transparency view: model colour at the cutter's opacity.
    Removed,
    /// Removed surface inside a thin sub-cutter: model colour, opaque, two-sided.
    Ribbon,
    /// Walls of a solid slice: the wall colour, opaque.
    SliceWall,
}

/// One mesh of the preview.
#[derive(Clone, Debug)]
pub struct PreviewPart {
    /// Index of the model (in `Scene::models`) the part belongs to.
    pub model: usize,
    /// Index of the cutter (in `Scene::cutters`) that made it (`usize::MAX` for `Kept`, and for
    /// the `Wall` part that holds what is left of the model's scalpel incisions).
    pub cutter: usize,
    pub kind: PartKind,
    /// Opacity for `Removed` parts; 1 for the others.
    pub opacity: f32,
    pub mesh: Mesh,
}

/// Everything Preview mode draws for a scene.
#[derive(Clone, Debug, Default)]
pub struct PreviewGeometry {
    /// Per model (same length as `Scene::models`): true when the model is drawn by its parts
    /// instead of its own mesh.
    pub replaced: Vec<bool>,
    pub parts: Vec<PreviewPart>,
    /// Thick contour lines: (model index, polyline). Only for cutters with the normal-cut view.
    pub contours: Vec<(usize, Vec<DVec3>)>,
    /// Why a cutter could not cut (one line each, for the status line); such a cutter cuts
    /// nothing.
    pub notes: Vec<String>,
    /// Per cutter that ran (scene index order): whether its cut (and its ribbons and slices)
    /// was made by the exact boolean, and how long the boolean took.
    pub reports: Vec<(usize, CutReport)>,
}

/// How one cutter's cut went.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CutReport {
    /// The cut (and its ribbons and slices, if shown) was made; false: it was refused and the
    /// cutter cut nothing.
    pub exact: bool,
    /// Wall time of the cutter's boolean against the cached index, in milliseconds (0 for a cut
    /// taken from the cache).
    pub cut_ms: f64,
}

impl PreviewGeometry {
    /// Total triangles of all parts (for the status line).
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.mesh.triangle_count()).sum()
    }

    /// Without the removed-piece views (transparency, ribbons, slices): the kept parts and walls
    /// a normal cut shows.
    pub fn without_views(&self) -> PreviewGeometry {
        PreviewGeometry {
            replaced: self.replaced.clone(),
            parts: self
                .parts
                .iter()
                .filter(|p| matches!(p.kind, PartKind::Kept | PartKind::Wall))
                .cloned()
                .collect(),
            contours: self.contours.clone(),
            notes: self.notes.clone(),
            reports: self.reports.clone(),
        }
    }
}

/// Tag of a triangle of a cut model that belongs to the model's own surface; any other tag is the
/// scene index of the cutter whose wall the triangle is (see [`super::cut_scene::cut_in_turn`]).
pub const SURFACE: u32 = u32::MAX;

/// Tag of a triangle of a cut model that is a wall of a scalpel incision in the model's own mesh
/// (`crate::scene::wall_faces`): drawn as a wall, not cut surface; no cutter's contour runs along it.
pub const INCISION: u32 = u32::MAX - 1;

/// What one cutter of a sequence did (see [`super::cut_scene::cut_in_turn`]); borrowed by the step callback.
pub struct Step<'a> {
    /// Scene index of the cutter.
    pub cutter: usize,
    /// The surface this cutter cut, indexed: the model closed by the walls of the cutters before
    /// it.
    pub before: &'a TargetIndex,
    /// The mesh of `before`.
    pub before_mesh: &'a Mesh,
    /// Tag of every triangle of `before_mesh` ([`SURFACE`] or a cutter index).
    pub before_tags: &'a [u32],
    /// The model's surface inside this cutter that the cutters before had not removed (walls of
    /// earlier cutters left out), with the model's orientation. Empty for cutters the caller of
    /// [`super::cut_scene::cut_in_turn`] said it may skip.
    pub removed: &'a Mesh,
    /// The closed result after this cutter, T ∖ (K1 ∪ … ∪ Ki), welded: kept surface and walls.
    pub after: &'a Mesh,
    /// Tag of every triangle of `after`.
    pub after_tags: &'a [u32],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_kept_parts_and_walls_stay() {
        let part = |kind| PreviewPart {
            model: 0,
            cutter: 0,
            kind,
            opacity: 1.0,
            mesh: csg::Mesh::default(),
        };
        let full = PreviewGeometry {
            replaced: vec![true],
            parts: [
                PartKind::Kept,
                PartKind::Wall,
                PartKind::Removed,
                PartKind::Ribbon,
                PartKind::SliceWall,
            ]
            .into_iter()
            .map(part)
            .collect(),
            ..Default::default()
        };
        let cut = full.without_views();
        let kinds: Vec<PartKind> = cut.parts.iter().map(|p| p.kind).collect();
        assert_eq!(kinds, vec![PartKind::Kept, PartKind::Wall]);
        assert_eq!(cut.replaced, vec![true]);
    }
}
