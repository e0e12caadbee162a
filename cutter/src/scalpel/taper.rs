//! Tapered groove ends: the groove's depth goes to zero over a short distance at each crack tip.
//!
//! A groove closes at a crack tip (the tip is its own bottom, see [`super::groove`]). Its last
//! floor vertex could sit at the full blade depth under a path vertex right next to the tip, so
//! the walls dropped from the surface to the full depth over one path segment: a cliff of long
//! thin triangles at the end, which showed as a torn end once the incision opened. Here, at
//! the end of a cut (the temporary tip of every step and the end of the stroke), the last floor
//! vertex, when the tip is nearer than [`TAPER_DEPTHS`] blade depths to where it sits along the
//! path, is raised to the depth its distance from the tip gives (never above [`MIN_DEPTH`] of
//! the blade depth, so its walls keep their shape): the walls slope from the tip into the
//! groove. (The start of a groove is not tapered: its first floor vertex stays at full depth
//! under the second path vertex. Moving it along the path put it away from where a later cut
//! crossing the groove near its start looks for it.)
//!
//! Only positions of floor vertices change (journaled like every edit, so an undone tip puts
//! them back): no triangle is added, so the groove's element budget is untouched.
//! Cost: a few path segments per step (the loop stops one taper length from the tip).

use glam::DVec3;

use super::dyn_mesh::DynMesh;
use super::groove::Groove;

/// The groove reaches its full depth this many blade depths from a crack tip (a slope of about
/// 27°).
pub const TAPER_DEPTHS: f64 = 2.0;

/// A floor vertex near a tip keeps at least this fraction of the blade depth.
pub const MIN_DEPTH: f64 = 0.2;

/// A floor vertex lies under a stretch of path when it is at most this many blade depths
/// across from it (see [`shape_end`]).
const UNDER: f64 = 0.25;

/// Raises the groove's last floor vertex toward the tip at path index `last` (see the module
/// doc). `path` includes the tip. Nothing when the floor vertex before the tip is not one of
/// this groove's own (a trench it opened into) or sits a taper length or more from the tip.
pub(crate) fn shape_end(g: &Groove, mesh: &mut DynMesh, path: &[u32], last: usize) {
    if last == 0 || last >= path.len() || g.bottoms.get(last) != Some(&path[last]) {
        return;
    }
    let Some(&b) = g.bottoms.get(last - 1) else {
        return;
    };
    if g.bottom_vertices.last() != Some(&b) || b == path[last - 1] {
        return;
    }
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
        let n = normal_at(mesh, near);
        let x = pb - foot;
        let off = (x - n * x.dot(n)).length();
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
