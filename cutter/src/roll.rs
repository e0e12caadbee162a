//! The paint roller's sizes and settings: what one extrusion move is told (δ, spacing, the
//! straight constraint) and the box sizes in multiples of δ (thesis 3.3.1). Shared by the
//! extrusion ([`crate::extrude`]) and the wedge sweep ([`crate::wedge`]), so neither imports the
//! other for them.

/// Initial strip width as a multiple of δ (thesis 3.3.1).
pub const INITIAL_WIDTH: f64 = 10.0;
/// Initial depth as a multiple of δ.
pub const INITIAL_DEPTH: f64 = 5.0;
/// Width of a freshly started leading box, as a multiple of δ ("very narrow").
pub const MIN_WIDTH: f64 = 0.25;
/// Displacement of one face-rotation step, as a multiple of δ.
pub const ROTATION_STEP: f64 = 2.0;

/// Largest number of boxes one mouse move may lock (a far jump of the mouse).
pub(crate) const MAX_BOXES_PER_MOVE: usize = 16;

/// Settings of one extrusion move.
#[derive(Clone, Copy, Debug)]
pub struct RollSettings {
    /// Scene increment δ.
    pub delta: f64,
    /// Segment spacing ω: a box is locked when it reaches ω·δ wide.
    pub spacing: f64,
    /// Straight-path constraint (Shift, or the Straight kind).
    pub straight: bool,
    /// A rolled plane keeps the back direction of the plane before it (the cutter goes along
    /// one direction, the view it was painted in) instead of the inward normal of its front face.
    pub keep_direction: bool,
    /// A rolled leading plane keeps its own depth (new planes take it) instead of the depth of
    /// the plane before it.
    pub keep_depth: bool,
}
