//! Tapered groove ends: the groove's depth goes to zero over a short distance at each crack tip.
//!
//! A groove closes at a crack tip (the tip is its own bottom, see [`super::groove`]). A floor
//! vertex at the full blade depth under a path vertex right next to a tip makes the walls drop
//! from the surface to the full depth over one path segment: a cliff of long thin triangles,
//! which showed as a torn end once the incision opened. So the depth tapers over
//! [`TAPER_DEPTHS`](super::groove::TAPER_DEPTHS) blade depths at both ends (a slope of about 27°), never below
//! [`MIN_DEPTH`](super::groove::MIN_DEPTH) of the blade depth (so the walls keep their shape):
//! - **Start** ([`Groove::start_depth`]): a floor vertex made within the taper length of the groove's
//!   start (a crack tip, not a trench it opens into) is made shallower, straight below the path
//!   vertex it belongs to. Only its depth changes, never where it sits along the path: a later
//!   cut crossing the groove near its start finds the floor vertex under the lip vertex it
//!   belongs to (moving it along the path broke such cross cuts).
//! - **End** ([`shape_end`]): at the end of a cut (the temporary tip of every step and the end
//!   of the stroke), each floor vertex of the groove's own that sits nearer than the taper
//!   length to the tip along the path is raised to the depth its distance from the tip gives.
//!
//! Only positions of floor vertices change (journaled like every edit, so an undone tip puts
//! them back): no triangle is added, so the groove's element budget is untouched.
//! Cost: constant at the start; a few path segments per step at the end (the loop stops one
//! taper length from the tip).

use glam::DVec3;

use super::dyn_mesh::DynMesh;
use super::groove::Groove;
/// The taper's shape constants live with the groove that builds floors at those depths.
pub use super::groove::{MIN_DEPTH, TAPER_DEPTHS};

/// A floor vertex lies under a stretch of path when it is at most this many blade depths
/// across from it (see [`shape_end`]).
const UNDER: f64 = 0.25;

/// Raises the groove's floor vertices near the tip at path index `last` (see the module doc).
/// `path` includes the tip. Walks back from the tip over the path within a taper length (plus
/// a blade depth: a floor vertex sits at most that far across from its path vertex) and stops
/// at the first floor vertex that is not one of this groove's own (a trench it opened into, or
/// its start's crack tip).
pub(crate) fn shape_end(g: &Groove, mesh: &mut DynMesh, path: &[u32], last: usize) {
    if last == 0 || last >= path.len() || g.bottoms.get(last) != Some(&path[last]) {
        return;
    }
    let reach = TAPER_DEPTHS * g.depth;
    // One normal for finding where floor vertices sit along the path near the tip (the surface
    // turns little over a taper length): a normal per path vertex cost more than the step.
    let n_tip = normal_at(mesh, path[last]);
    let mut seen = None;
    let mut arc = 0.0;
    let mut i = last;
    while i > 0 && arc < reach + g.depth {
        let Some(&b) = g.bottoms.get(i - 1) else {
            return;
        };
        arc += mesh.pos(path[i]).distance(mesh.pos(path[i - 1]));
        i -= 1;
        if seen == Some(b) {
            continue;
        }
        seen = Some(b);
        // Floor vertices within reach were made last (they are at least a blade depth apart).
        let own = g
            .bottom_vertices
            .iter()
            .rev()
            .take(OWN_LOOKBACK)
            .any(|&x| x == b);
        if b == path[i] || !own {
            return;
        }
        raise(g, mesh, path, last, b, n_tip);
    }
}

/// How many of a groove's newest floor vertices [`shape_end`] looks among for the one under a
/// path vertex near the tip.
const OWN_LOOKBACK: usize = 8;

/// Raises floor vertex `b` toward the tip at path index `last`, when the tip is nearer than the
/// taper length to where `b` sits along the path (found across `n_tip`, the normal at the tip).
fn raise(g: &Groove, mesh: &mut DynMesh, path: &[u32], last: usize, b: u32, n_tip: DVec3) {
    let reach = TAPER_DEPTHS * g.depth;
    let pb = mesh.pos(b);
    // The floor vertex is at most a blade depth below a path point: farther than that plus the
    // reach from the tip, it sits more than the reach along the path from it (the usual case,
    // checked in constant time).
    if pb.distance(mesh.pos(path[last])) > reach + g.depth {
        return;
    }
    // Where the floor vertex sits along the path: the point of the path segments within reach
    // of the tip nearest above it (across the local normal).
    let mut arc = 0.0;
    let mut best: Option<(f64, f64, DVec3, u32)> = None;
    let mut i = last;
    while i > 0 && arc < reach {
        let (c, a) = (mesh.pos(path[i]), mesh.pos(path[i - 1]));
        let ca = a - c;
        let l = ca.length();
        let u = if l > 0.0 {
            ((pb - c).dot(ca) / (l * l)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let foot = c + ca * u;
        let near = if u < 0.5 { path[i] } else { path[i - 1] };
        let x = pb - foot;
        let off = (x - n_tip * x.dot(n_tip)).length();
        if best.is_none_or(|(o, ..)| off < o) {
            best = Some((off, arc + u * l, foot, near));
        }
        arc += l;
        i -= 1;
    }
    // Floor vertices are made under path vertices: one farther across than this from the
    // path within reach lies under the path beyond it.
    let Some((off, from_tip, top, near)) = best else {
        return;
    };
    if from_tip >= reach || off > UNDER * g.depth {
        return;
    }
    let n = normal_at(mesh, near);
    if n == DVec3::ZERO {
        return;
    }
    let depth_now = (top - pb).dot(n);
    let depth = g.depth * (from_tip / reach).clamp(MIN_DEPTH, 1.0);
    if depth < depth_now {
        mesh.set_pos(b, top - n * depth);
    }
}

/// Unit surface normal at path vertex `v`: over all its copies (a lip copy's own surface fan is
/// one side of the cut, whose normal leans to that side). Zero when degenerate.
fn normal_at(mesh: &DynMesh, v: u32) -> DVec3 {
    let mut scratch = Vec::new();
    let mut n = mesh.surface_normal(v, &mut scratch);
    for c in mesh.copies(v) {
        n += mesh.surface_normal(c, &mut scratch);
    }
    n.normalize_or_zero()
}
