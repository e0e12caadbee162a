//! Moving a mesh vertex onto the cut instead of bending the cut to the vertex.
//!
//! Where the cut crosses an edge close to one of its ends, splitting the edge there would leave
//! a sliver, so the cut goes through that end vertex instead (snapping, notes §2, Q1). Snapping
//! alone bends the cut toward the vertex: the lips kink up to the snap radius (a quarter of an
//! edge for slits, up to half for grooves) off the drawn path, which shows as a ragged incision
//! once it opens. Nienhuys and van der Stappen (and SOFA's `SnapAlongPath`) move the vertex onto
//! the cut instead: the cut keeps its line and the mesh keeps its triangle count.
//!
//! [`onto_cut`] moves the vertex to the crossing point on the edge being crossed (so it stays on
//! the surface: the point lies on an edge of the input), only when that is safe:
//! - the vertex is an ordinary surface vertex: no copies (not on a cut), not a groove floor, not
//!   a bow-tie, its fan closed (not on a boundary, a slit or a crack tip) and free of walls;
//! - no triangle of its fan turns over or loses more than half of its smallest angle
//!   ([`KEEP_ANGLE`]): the quality bound of the notes (Q1: a move of at most the snap radius
//!   keeps the 1-ring above the bound snapping itself gives).
//!
//! Otherwise the cut snaps as before. The tips of a stroke are treated alike ([`tip_onto`]): its
//! start vertex and, when the stroke ends, its end vertex move from the vertex or edge they
//! snapped to onto the drawn start and end, on the same shape condition. The move is journaled like every other edit, so a refused
//! step or an undone tip puts the vertex back bit for bit.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, prev};

/// A move may lower the smallest angle of a triangle of the vertex's fan to this fraction of
/// what it was, no lower.
pub const KEEP_ANGLE: f64 = 0.5;

/// A moved triangle's normal must stay within this angle (degrees) of its old one (no fold).
const MAX_TURN_DEG: f64 = 30.0;

/// Moves vertex `b` to `y` (a point on an edge of `b`'s fan, where the cut crosses it) when that
/// keeps every triangle around `b` well shaped (see the module doc). Returns whether it moved.
pub(crate) fn onto_cut(mesh: &mut DynMesh, b: u32, y: DVec3, fan: &mut Vec<u32>) -> bool {
    if !y.is_finite()
        || mesh.singular[b as usize]
        || mesh.is_floor(b)
        || !mesh.copies(b).is_empty()
        || !mesh.fan_into(b, fan)
    {
        return false;
    }
    let pb = mesh.pos(b);
    if pb == y {
        return true;
    }
    if fan.iter().any(|&h| mesh.is_wall(h / 3)) || !keeps_shape(mesh, b, y, fan) {
        return false;
    }
    mesh.set_pos(b, y);
    true
}

/// Moves crack tip `x` (the end of a finished cut: no copies, not a floor vertex) to `y`, the
/// drawn end of the cut on the surface, when that keeps every triangle around it well shaped
/// (the same test as [`onto_cut`], walls included: a groove's tip is its own bottom, its walls
/// move with it). The cut snaps its end to a vertex or an edge near the drawn end so as to make
/// no sliver; moving the tip there afterwards ends the lips where the user drew. Returns
/// whether it moved.
pub(crate) fn tip_onto(mesh: &mut DynMesh, x: u32, y: DVec3, fan: &mut Vec<u32>) -> bool {
    if !y.is_finite() || mesh.singular[x as usize] || mesh.is_floor(x) || !mesh.copies(x).is_empty()
    {
        return false;
    }
    mesh.fan_into(x, fan);
    if fan.is_empty() || !keeps_shape(mesh, x, y, fan) {
        return false;
    }
    mesh.set_pos(x, y);
    true
}

/// Whether moving `b` to `y` keeps each triangle of `fan` (`b`'s outgoing half-edges) from
/// turning over (its normal turns less than [`MAX_TURN_DEG`]) and above [`KEEP_ANGLE`] of its
/// smallest angle.
fn keeps_shape(mesh: &DynMesh, b: u32, y: DVec3, fan: &[u32]) -> bool {
    let pb = mesh.pos(b);
    let cos_turn = MAX_TURN_DEG.to_radians().cos();
    for &h in fan {
        let (c, d) = (mesh.pos(mesh.dest(h)), mesh.pos(mesh.origin(prev(h))));
        let before = (c - pb).cross(d - pb);
        let after = (c - y).cross(d - y);
        let l = before.length() * after.length();
        if !(l > 0.0 && before.dot(after) >= cos_turn * l) {
            return false;
        }
        if min_angle(y, c, d) < KEEP_ANGLE * min_angle(pb, c, d) {
            return false;
        }
    }
    true
}

/// Smallest angle (radians) of triangle `a b c` (0 when degenerate).
pub fn min_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let angle = |p: DVec3, q: DVec3, r: DVec3| {
        let (u, v) = (q - p, r - p);
        let l = u.length() * v.length();
        if l == 0.0 {
            0.0
        } else {
            (u.dot(v) / l).clamp(-1.0, 1.0).acos()
        }
    };
    angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
}
