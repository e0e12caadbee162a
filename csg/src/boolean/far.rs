//! Cutters that reach beyond the target's lattice.
//!
//! A target's lattice is chosen when its index is built, before any cutter exists: the target
//! spans a quarter of the lattice's range, so a cutter may reach four to eight half-sizes of the
//! target from its centre (see [`crate::lattice`]). That is room for every cutter drawn on a
//! target seen whole, but not for one painted across a small target seen from far away (a
//! kidney in a whole body, a stroke that deliberately runs past a small structure): its planes
//! reach many target sizes out, although only the part near the target cuts anything.
//!
//! Such a cut runs on a second index of the same mesh whose lattice spans the target and the
//! cutter together. Exactness is unchanged: every decision is still an exact predicate on
//! lattice points within the same bit budget ([`crate::lattice::LATTICE_BITS`]); only the lattice
//! step grows with the box, to at most [`MAX_REACH`] times the step of the target's own lattice
//! (for a 10 mm structure with a cutter reaching a metre, still tens of nanometres). The second
//! index shares the target's mesh, so its result names the same faces and vertices as a cut on
//! the cached index would. Building it costs one pass over the target, which is small in the
//! case this exists for; a cutter farther than [`MAX_REACH`] target sizes is refused.

use crate::aabb::Aabb;
use crate::mesh::Mesh;
use crate::target::TargetIndex;

/// How many target sizes (the longest side of its box) the target and a cutter may span
/// together before the cut is refused: the lattice step is then at most about `MAX_REACH` times
/// the target's own step, 2⁻¹⁷ of the target's size.
pub const MAX_REACH: f64 = 1024.0;

/// An index of `target`'s mesh whose lattice also spans every vertex of `cutters`, when they are
/// finite and span together with the target at most [`MAX_REACH`] target sizes; `None`
/// otherwise (the caller keeps its out-of-range error).
pub(crate) fn index_with_room(target: &TargetIndex, cutters: &[&Mesh]) -> Option<TargetIndex> {
    let own = Aabb::from_points(&target.mesh.positions);
    if own.is_empty() {
        return None;
    }
    let mut room = own;
    for cutter in cutters {
        for &p in &cutter.positions {
            if !p.is_finite() {
                return None;
            }
            room.grow(p);
        }
    }
    let size = own.size().max_element();
    let reach = room.size().max_element();
    if reach.is_nan() || reach > MAX_REACH * size {
        return None;
    }
    TargetIndex::build_with_room(target.mesh.clone(), &room).ok()
}
