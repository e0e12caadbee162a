//! What every stage after the exact intersection reads: the target, the prepared cutter and
//! the intersections found between them.

use crate::intersect::{Intersections, PointKey, PreparedCutter};
use crate::solids::solid_of_face;
use crate::target::TargetIndex;

/// Below this many touched faces (or contour segments), the stages that could run in parallel
/// run on the calling thread: a rayon hand-off costs more than splitting a few faces.
pub(crate) const PARALLEL_MIN: usize = 64;

/// The inputs of stages 3–6 of one cut.
pub(crate) struct CutInputs<'a> {
    pub target: &'a TargetIndex,
    pub cutter: &'a PreparedCutter,
    pub isect: &'a Intersections,
}

impl CutInputs<'_> {
    /// The target face an intersection point lies on.
    pub fn face_of_point(&self, p: u32) -> u32 {
        match self.isect.keys[p as usize] {
            PointKey::Ef { face, .. } => face,
            PointKey::Fe { face, .. } => face,
        }
    }

    /// The region solid whose surface an intersection point lies on.
    pub fn solid_of_point(&self, p: u32) -> u32 {
        solid_of_face(self.target, self.face_of_point(p))
    }
}
