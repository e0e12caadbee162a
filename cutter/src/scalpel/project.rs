//! Tool samples onto the surface.
//!
//! A path file's samples, and the window's samples where the pointer leaves the model (a miss is
//! put on the view plane through the last hit), lie near the surface rather than on it. The walk
//! aims at a sample through a plane containing the local normal, so a sample a little off the
//! surface still gives the right direction, but not the right *distance*: one an edge length
//! outside a convex surface is farther from the anchor's fan than the cut can reach there, and
//! the cut counted as stuck, ended and started again under the blade, so a path drawn a
//! millimetre off the skin cut a row of separate short grooves instead of one. Each sample is
//! therefore moved to the nearest point of the surface around the cut before the walk (the path
//! file format promises exactly that: samples are "projected onto it").
//!
//! The search is local (best-first outward from the anchor over at most [`PROJECT_SEARCH`]
//! triangles, stopping once no unvisited triangle's box can be nearer than the best point), so
//! a step's cost does not depend on the mesh size; groove walls are passed through but never
//! projected onto (a sample over an open trench lands on a lip's surface, not inside it).

use glam::DVec3;

use super::cut_point::{closest_on_triangle, visit_near};
use super::dyn_mesh::DynMesh;

/// Most triangles examined to project one sample.
pub const PROJECT_SEARCH: usize = 512;

/// The point of the surface nearest `q` among the triangles reached from vertex `near` (and its
/// copies), or `None` when the search met no surface triangle.
pub fn onto_surface(mesh: &DynMesh, near: u32, q: DVec3) -> Option<DVec3> {
    let mut best: Option<(DVec3, f64)> = None;
    visit_near(mesh, near, q, PROJECT_SEARCH, |t, box_distance| {
        if best.is_some_and(|(_, d)| box_distance >= d) {
            return false;
        }
        if !mesh.is_wall(t) {
            let [a, b, c] = mesh.triangles[t as usize].map(|x| mesh.pos(x));
            let w = closest_on_triangle(q, a, b, c);
            let p = a * w.x + b * w.y + c * w.z;
            let d = p.distance(q);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((p, d));
            }
        }
        true
    });
    best.map(|(p, _)| p)
}
