//! # Scalpel mode: progressive cutting of a triangle surface along a tool path
//!
//! The second way to cut (papers: Bruyns 2002, interactive cross cutting, progressive
//! re-meshing of thin membranes, Sela 2004 DFFD incision; goals in `notes/scalpel.md`).
//!
//! ## Model
//! A [`Scalpel`] owns a [`DynMesh`] (the `csg` mesh plus half-edge twins it patches locally) and
//! receives tool samples: [`Scalpel::begin_stroke`], [`Scalpel::step`] per sample,
//! [`Scalpel::end_stroke`]. Each step walks the surface from the last permanent cut vertex toward
//! the sample (a plane through the cut vertex, the sample and the local normal), splitting each
//! triangle it crosses so that the cut runs along mesh edges, then opens those edges (a slit with
//! two lips) or, with a depth on a closed surface, closes the slit with groove walls.
//!
//! - Cut points are vertices, points on edges or points inside faces ([`cut_point`]); an edge
//!   crossing closer than `snap_edge` (relative edge parameter) to a vertex goes through the
//!   vertex, an end point closer than `snap_end` to a vertex or edge lands on it, so no sliver is
//!   created and the mesh never has a T-junction. A vertex the walk goes through this way is first
//!   moved onto the cut where that keeps its triangles well shaped ([`relocate`]), so the cut
//!   keeps the drawn path's line instead of kinking toward the vertex.
//! - The end of the cut inside its last triangle (the tool tip) is *temporary*: it is undone at
//!   the next step and redone further on (Mor–Kanade), so sampling density and trembling do not
//!   leave permanent triangles.
//! - A stroke's first cut starts, and its cut ends when the stroke ends, at the drawn points:
//!   the tip vertex the walk snapped to a vertex or an edge near them is moved there where its
//!   triangles stay well shaped (`relocate::tip_onto`).
//! - Every step is a transaction over the mesh's journal: it commits a valid mesh or returns an
//!   error with the mesh exactly as before. Before committing, the triangles the step touched are
//!   validated locally (twins, orientation, fans, closedness for grooves; cost proportional to
//!   the step): a configuration the code does not handle costs one refused step, never a broken
//!   mesh. [`Scalpel::undo_stroke`] undoes a whole stroke.
//! - Crossing an existing slit ([`cross`]): at 15° or more between the cuts the new cut continues
//!   on the other lip; under 15° it merges into the existing cut (ends there).
//! - Crossing an existing groove (interactive cross cutting, Fig. 10): groove walls are marked
//!   by their floor vertices and the surface walk never enters them. A groove reaching another
//!   groove's lip opens into that trench (its walls end on the trench's floor vertex, between
//!   the two halves of the old wall); at 15° or more it goes on from the far lip, opening into
//!   the trench from that side too (an X: the crossing point gets 4 copies), under 15° it ends
//!   there (merge). The deeper cut determines the floor at the crossing: a shallower trench's
//!   floor vertex there is lowered to the new blade's depth. A groove whose first segment past
//!   a crossing reaches a trench lip again gets a middle vertex (a floor of its own between the
//!   two junctions); one that comes straight back into the trench it crossed, at the same floor
//!   vertex, ends on the lip in a crack tip instead of opening into it.
//! - A groove's walls are strips: every path vertex gets a floor vertex under it, along the
//!   surface normal averaged over a blade depth of path, so each segment's wall on each lip is a
//!   quad of two triangles and the floor a smooth polyline under the path (see [`groove`],
//!   "Wall shape"). Grooves snap to vertices like slits (`groove_snap_edge`, a quarter of an
//!   edge), so their lips keep within a quarter of an edge of the drawn path (notes Q2). The
//!   element budget is the notes' two (T1: at most 4 surface pieces in a crossed triangle, 3 edge
//!   to edge; T4: at most 4 wall triangles per segment), counted by [`budget::element_budget`].
//! - A cut that cannot leave its anchor toward a sample that is on the surface two triangles
//!   away (a trench's lip in the way where it cannot cross) ends there and starts again under
//!   the blade, instead of refusing every later step of the stroke. A groove starting on a
//!   trench's lip (or just past a trench it crossed) that would reach the same trench's lip at
//!   once ends there (merged).
//! - A through-cut's far side follows the far surface under each sample (a ray along the
//!   inward normal, searched near the far cut), so the slot follows a structure whose thickness
//!   changes. A slot reaching another cut or a boundary ends at its last tip and the stroke
//!   starts a new slot past it (its far side searched near where it starts again).
//! - [`Tool::Loop`] closes the stroke back to its start and reports the pieces it detached
//!   ([`loop_tool`]).
//! - [`dffd`] opens the incision by a displacement that is discontinuous across the cut, over a
//!   trailing time window; vertices outside its support are never written. The lips it shows
//!   follow the drawn path ([`drawn`]: each committed step records its tool sample), not the
//!   zigzag of mesh edges the cut runs along; [`lip_measure`] measures them against it.
//! - [`layers`] turns a stroke into strokes on every stacked surface the blade reaches;
//!   [`through`] cuts a slot through a structure thinner than the blade is deep.
//! - [`invariants`] validates the whole structure (used after every step in tests);
//!   [`survey`] counts refused steps on random strokes (tests, bench).
//!
//! ## Cost
//! `begin_stroke` scans the mesh once (nearest face, whether the surface is closed, the
//! through-cut ray). No step does (the searches inside a stroke examine at most
//! `RESTART_SEARCH` triangles): a cut restarting inside a stroke (after merging into another
//! cut) searches for its start outward from where it merged, over a bounded number of triangles,
//! and keeps the stroke's kind (groove, slit) and its surface's closedness.
//!
//! ## Robustness contract
//! Input: any [`csg::Mesh`] that passes `sanity_check`. Non-manifold edges and bow-tie vertices
//! are kept but never cut through (error, mesh unchanged). The only topological decision taken on
//! coordinates, the side of the walking plane a vertex is on, uses the exact
//! `csg::exact::orient3d_f64`;
//! snapping thresholds are relative to local edge lengths, never absolute.

pub mod blend;
pub mod budget;
pub mod cross;
pub mod cut_grid;
pub mod cut_point;
pub mod dffd;
pub mod drawn;
pub mod dyn_mesh;
pub mod feet;
mod field;
mod field_cache;
pub mod frames;
pub mod groove;
pub mod invariants;
pub mod kept_path;
pub mod layers;
pub mod lip_measure;
pub mod live_opening;
mod local_check;
pub mod locate;
pub mod loop_tool;
mod nearest_cut;
pub mod relocate;
pub mod sample;
mod side_walk;
mod sides;
pub mod step;
pub mod survey;
pub mod taper;
pub mod through;
pub mod unfold;
pub mod walls;

pub use cut_point::CutPoint;
pub use dffd::OpenOptions;
pub use dyn_mesh::DynMesh;
pub use invariants::{TopologyReport, ValidationError};
pub use step::{Scalpel, StepReport, StrokeReport};

/// What the blade does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tool {
    /// An open cut along the path.
    #[default]
    Scalpel,
    /// A closed path: the stroke is closed back to its start and cuts through, detaching the
    /// enclosed piece.
    Loop,
}

/// Settings of the blade.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalpelOptions {
    /// Blade depth below the surface (model units). `0` cuts a slit (thin membrane). Default `0`.
    pub depth: f64,
    /// Open or closed tool. Default [`Tool::Scalpel`].
    pub tool: Tool,
    /// Edge crossings at edge parameter below this (or above `1 - snap_edge`) go through the
    /// vertex instead. Default `0.25` (worst new angle ≈ 0.2 × parent's: notes §2).
    pub snap_edge: f64,
    /// `snap_edge` for grooves (depth > 0 on a closed surface). Default `0.25`, as for slits: a
    /// crossing snapped to a vertex is at most a quarter of the crossed edge off the drawn path
    /// (notes Q2) even where the vertex cannot be moved onto the cut ([`relocate`]). (It was
    /// coarser, `0.4`, to keep the floor's changes at mesh vertices within a combined element
    /// budget; the walls have their own budget now, see [`groove`], "Element budget".)
    pub groove_snap_edge: f64,
    /// End points within this fraction of the last segment from its ends snap to them; end
    /// points near an edge land on it. Default `0.25`.
    pub snap_end: f64,
    /// Cuts meeting an existing slit at less than this angle (degrees) merge into it instead of
    /// crossing. Default `15`.
    pub merge_angle_deg: f64,
    /// A sample farther than this from the surface is off the mesh. `None` (default) uses
    /// `depth + 5%` of the mesh's bounding-box diagonal.
    pub max_surface_distance: Option<f64>,
}

impl Default for ScalpelOptions {
    fn default() -> Self {
        ScalpelOptions {
            depth: 0.0,
            tool: Tool::Scalpel,
            snap_edge: 0.25,
            groove_snap_edge: 0.25,
            snap_end: 0.25,
            merge_angle_deg: 15.0,
            max_surface_distance: None,
        }
    }
}

impl ScalpelOptions {
    pub fn with_depth(mut self, depth: f64) -> Self {
        self.depth = depth;
        self
    }

    pub fn with_tool(mut self, tool: Tool) -> Self {
        self.tool = tool;
        self
    }
}

/// Why a scalpel step or stroke failed. The mesh is unchanged whenever one of these is returned.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ScalpelError {
    /// The sample is too far from the surface. Move the tool onto the mesh.
    #[error(
        "tool sample {point:?} is {distance} from the surface (more than {tolerance}): off the mesh"
    )]
    OffMesh {
        point: [f64; 3],
        distance: f64,
        tolerance: f64,
    },
    /// The mesh has no triangle to cut.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// The cut reached an edge with more than two faces or a bow-tie vertex.
    #[error(
        "non-manifold region at the cut near {point:?}: the scalpel cuts only manifold surfaces"
    )]
    NonManifold { point: [f64; 3] },
    /// A sample coordinate is NaN or infinite.
    #[error("tool sample {point:?} is not finite")]
    NonFinite { point: [f64; 3] },
    /// `step` or `end_stroke` without `begin_stroke`.
    #[error("no stroke in progress")]
    NoStroke,
    /// The surface walk did not reach the sample (degenerate geometry).
    #[error("the cut could not follow the surface toward {point:?}")]
    WalkFailed { point: [f64; 3] },
    /// A loop stroke did not come back to its start.
    #[error("the loop did not close: its end is {gap} from its start")]
    LoopNotClosed { gap: f64 },
    /// The options are invalid (negative depth, thresholds outside [0, 0.5)).
    #[error("invalid scalpel options: {0}")]
    BadOptions(String),
}
