//! Where a stroke starts, without a pass over the mesh.
//!
//! The first step of a stroke has three questions that the surface walk cannot answer locally,
//! because it does not yet know where it is: which triangle lies under the sample, whether the
//! surface there is closed (a groove must keep it closed), and where the blade's ray leaves the
//! structure (a through-cut). Answered by scanning every triangle they cost 50–170 ms per
//! stroke on a 2-million-triangle mesh, far beyond a frame. A [`Locator`] answers them from
//! structures built once when the scalpel is made ([`super::Scalpel::new`], which the window runs
//! off its UI thread when a model is selected):
//!
//! - a BVH ([`csg::SpatialIndex`]) over the mesh as it was given. Cutting never moves the rest
//!   pose of the surface and keeps every input vertex, so the input triangle nearest a sample
//!   names a vertex next to the current triangles under it; a search bounded by
//!   [`super::cut_point::RESTART_SEARCH`] triangles outward from that vertex
//!   ([`super::cut_point::closest_face_near`]) finds them. The same holds for the blade's ray;
//! - the connected component of each input triangle and whether it was closed. A stroke that
//!   leaves a boundary edge on a component marks it open ([`super::Scalpel::end_stroke`]; undone
//!   with the stroke).
//!
//! Where the bounded search finds nothing (a sample over a region cut into many small pieces),
//! the old linear scan answers, so the result never depends on the shortcut being possible.

use std::fmt;
use std::sync::Arc;

use glam::DVec3;

use super::dyn_mesh::{DynMesh, is_real};

/// Structures for starting a stroke in time independent of the mesh size (module docs).
#[derive(Clone)]
pub struct Locator {
    /// The mesh as the scalpel was given it.
    input: Arc<csg::Mesh>,
    index: Arc<csg::SpatialIndex>,
    /// Connected component (over manifold edges) of each input triangle.
    component: Arc<Vec<u32>>,
    /// Whether each component was closed (no boundary edge) in the input.
    closed_input: Arc<Vec<bool>>,
    /// How far inside the surface the blade's ray starts (relative to the mesh's size).
    ray_start: f64,
}

impl fmt::Debug for Locator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Locator")
            .field("triangles", &self.input.triangles.len())
            .field("components", &self.closed_input.len())
            .finish()
    }
}

impl Locator {
    /// Builds the index and the components of `mesh`, whose half-edge form is `dyn_mesh` (made
    /// from it, not cut yet). Cost O(N log N), once per scalpel.
    pub fn build(mesh: &csg::Mesh, dyn_mesh: &DynMesh) -> Locator {
        let nt = dyn_mesh.triangle_count();
        let mut component = vec![u32::MAX; nt];
        let mut closed = Vec::new();
        let mut stack = Vec::new();
        for seed in 0..nt {
            if component[seed] != u32::MAX {
                continue;
            }
            let id = closed.len() as u32;
            let mut is_closed = true;
            component[seed] = id;
            stack.push(seed as u32);
            while let Some(t) = stack.pop() {
                for k in 0..3 {
                    let g = dyn_mesh.twin(3 * t + k);
                    if !is_real(g) {
                        is_closed = false;
                        continue;
                    }
                    let u = (g / 3) as usize;
                    if component[u] == u32::MAX {
                        component[u] = id;
                        stack.push(u as u32);
                    }
                }
            }
            closed.push(is_closed);
        }
        Locator {
            ray_start: 1e-7 * mesh.bbox().diagonal().max(f64::MIN_POSITIVE),
            input: Arc::new(mesh.clone()),
            index: Arc::new(csg::SpatialIndex::build(mesh)),
            component: Arc::new(component),
            closed_input: Arc::new(closed),
        }
    }

    /// Whether each component was closed in the input (the scalpel keeps its own copy that
    /// strokes update).
    pub fn closed_input(&self) -> Vec<bool> {
        self.closed_input.to_vec()
    }

    /// The current surface triangle nearest `q`: `(triangle, barycentric weights, distance)`,
    /// with the component it lies in. `None` for an empty mesh.
    pub fn closest_face(&self, mesh: &DynMesh, q: DVec3) -> Option<(u32, DVec3, f64, u32)> {
        let cp = self.index.closest_point(&self.input, q)?;
        let component = self.component[cp.face as usize];
        let on = cp.point.distance(q) + 1e-9 * (1.0 + q.length());
        let mut best: Option<(u32, DVec3, f64)> = None;
        for v in self.corners_by_weight(cp.face, cp.bary) {
            if let Some(found) =
                super::cut_point::closest_face_near(mesh, v, q, super::cut_point::RESTART_SEARCH)
                && best.is_none_or(|b| found.2 < b.2)
            {
                best = Some(found);
            }
            if best.is_some_and(|b| b.2 <= on) {
                break;
            }
        }
        let (t, w, d) = match best {
            Some(b) if b.2 <= on => b,
            _ => super::cut_point::closest_face(mesh, q)?,
        };
        Some((t, w, d, component))
    }

    /// The first surface the ray from vertex `v` (at `origin`) along `dir` meets within
    /// `max_distance`, if it faces away from the ray (a far side): `(triangle, barycentric
    /// weights, distance)` on the current mesh. `None` when the ray meets nothing, or first a
    /// surface facing it (another structure inside).
    pub fn far_side(
        &self,
        mesh: &DynMesh,
        v: u32,
        origin: DVec3,
        dir: DVec3,
        max_distance: f64,
    ) -> Option<(u32, DVec3, f64)> {
        // Start just inside the surface so the triangles around `v` are not hit at distance 0.
        let eps = self.ray_start;
        let hit = self
            .index
            .ray_cast(&self.input, origin + dir * eps, dir, max_distance)?;
        if self.input.face_normal_scaled(hit.face as usize).dot(dir) <= 0.0 {
            return None;
        }
        let s = hit.t + eps;
        for w in self.corners_by_weight(hit.face, hit.bary) {
            if let Some(found) = super::through::ray_hit_near(
                mesh,
                w,
                origin,
                dir,
                s,
                super::cut_point::RESTART_SEARCH,
            ) && !mesh.triangles()[found.0 as usize]
                .iter()
                .any(|&x| mesh.same_point(x, v))
            {
                return Some(found);
            }
        }
        super::through::ray_first_hit(mesh, origin, dir, v)
    }

    /// The corners of input triangle `face`, heaviest barycentric weight first.
    fn corners_by_weight(&self, face: u32, bary: DVec3) -> [u32; 3] {
        let tri = self.input.triangles[face as usize];
        let w = bary.to_array();
        let mut order = [0usize, 1, 2];
        order.sort_by(|&a, &b| w[b].total_cmp(&w[a]));
        order.map(|k| tri[k])
    }
}
