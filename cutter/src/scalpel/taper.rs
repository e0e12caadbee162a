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

use super::dyn_mesh::DynMesh;
use super::groove::Groove;
/// The taper's shape constants live with the groove that builds floors at those depths.
pub use super::groove::{MIN_DEPTH, TAPER_DEPTHS};

/// Raises the groove's floor vertices near the tip at path index `last` (see the module doc).
/// `path` includes the tip. Walks back from the tip over the path within a taper length and
/// stops at the first floor vertex that is not one of this groove's own (a trench it opened
/// into, or its start's crack tip). Each path vertex has its own floor vertex (see
/// [`super::groove`], "Wall shape"), which moves up along the line joining the two, so the
/// floor keeps its averaged direction.
pub(crate) fn shape_end(g: &Groove, mesh: &mut DynMesh, path: &[u32], last: usize) {
    if last == 0 || last >= path.len() || g.bottoms.get(last) != Some(&path[last]) {
        return;
    }
    let reach = TAPER_DEPTHS * g.depth;
    let mut arc = 0.0;
    let mut i = last;
    while i > 0 {
        arc += mesh.pos(path[i]).distance(mesh.pos(path[i - 1]));
        i -= 1;
        if arc >= reach {
            return;
        }
        let Some(&b) = g.bottoms.get(i) else {
            return;
        };
        // The floor vertex of path vertex `i` was made after those of the path vertices
        // before it: among the newest `last - i` of the groove's own (plus one, where a middle
        // vertex was inserted next to a junction; see `Scalpel::join_trench`).
        let own = g
            .bottom_vertices
            .iter()
            .rev()
            .take(last - i + 1)
            .any(|&x| x == b);
        if b == path[i] || !own {
            return;
        }
        let (top, pb) = (mesh.pos(path[i]), mesh.pos(b));
        let depth_now = top.distance(pb);
        let depth = g.depth * (arc / reach).clamp(MIN_DEPTH, 1.0);
        if depth < depth_now && depth_now > 0.0 {
            mesh.set_pos(b, top + (pb - top) * (depth / depth_now));
        }
    }
}
