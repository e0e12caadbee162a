//! Tapered groove ends: the groove's depth goes to zero over a short distance at each crack tip.
//!
//! A groove closes at a crack tip (the tip is its own bottom, see [`super::groove`]). Its floor
//! vertex nearest the tip used to sit at the full blade depth right under the path vertex next
//! to the tip, so the walls dropped from the surface to the full depth over one path segment:
//! a cliff of long thin triangles at each end, which showed as a torn end once the incision
//! opened. Here the floor vertex nearest each tip is moved so that the groove reaches its full
//! depth [`TAPER_DEPTHS`] blade depths from the tip, along the path:
//! - at the start, the first floor vertex slides along under the path while its run grows, up to
//!   that distance from the start, at the depth that distance gives (full depth once there);
//! - at the end (the temporary tip of every step and the end of the cut), the last floor vertex,
//!   when the tip is nearer than that distance to where it sits, is raised to the depth its
//!   distance from the tip gives (never above [`MIN_DEPTH`] of the blade depth, so its walls
//!   keep their shape).
//!
//! Only positions of floor vertices change (journaled like every edit, so an undone tip puts
//! them back): no triangle is added, so the groove's element budget is untouched, and the walls
//! are the same fans as before, now sloping into the groove from the tips.
//! Cost: a few path segments per step (the loops stop one taper length from the tip).

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

/// The point of `path` (vertex positions) `s` along it from its first vertex (its last vertex
/// when the path is shorter) and the index of the segment it is on.
fn along(mesh: &DynMesh, path: &[u32], s: f64) -> (DVec3, usize) {
    let mut left = s;
    for i in 0..path.len().saturating_sub(1) {
        let (a, b) = (mesh.pos(path[i]), mesh.pos(path[i + 1]));
        let l = a.distance(b);
        if l >= left && l > 0.0 {
            return (a.lerp(b, left / l), i);
        }
        left -= l;
    }
    let last = path.len().saturating_sub(1);
    (mesh.pos(path[last]), last)
}

/// Places the groove's first floor vertex (see the module doc) after path vertex `k`'s bottom
/// was made or reused. Nothing unless the groove starts at a crack tip and vertices `1..=k`
/// all use the first floor vertex.
pub(crate) fn shape_start(g: &Groove, mesh: &mut DynMesh, path: &[u32], k: usize) {
    let Some(&first) = g.bottom_vertices.first() else {
        return;
    };
    if k == 0
        || k >= path.len()
        || g.bottoms.first() != Some(&path[0])
        || g.bottoms
            .get(1..=k)
            .is_none_or(|b| b.iter().any(|&x| x != first))
    {
        return;
    }
    let reach = TAPER_DEPTHS * g.depth;
    // Length of the run under the first floor vertex, up to the taper's reach.
    let mut run = 0.0;
    for i in 0..k {
        run += mesh.pos(path[i]).distance(mesh.pos(path[i + 1]));
        if run >= reach {
            break;
        }
    }
    let station = run.min(reach);
    let (top, i) = along(mesh, &path[..=k], station);
    let n = normal_at(mesh, path[i.max(1).min(k)]);
    if n == DVec3::ZERO {
        return;
    }
    let depth = g.depth * (station / reach).clamp(MIN_DEPTH, 1.0);
    mesh.set_pos(first, top - n * depth);
}

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
    // Where the floor vertex sits along the path: the point of the path segments within reach
    // of the tip nearest above it (across the local normal).
    let pb = mesh.pos(b);
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
