//! [`PickIndex`]: first hits of rays (pointer picks, the scalpel's surface rays) through an
//! `obvhs` BVH, with csg's watertight `f64` triangle test on its candidates.
//!
//! Why two trees: `csg`'s own Morton BVH ([`crate::SpatialIndex`]) builds faster and answers box
//! queries (the boolean's broad phase) faster, but `obvhs`'s PLOC tree is the better tree for
//! rays: `cargo bench -p csg --bench bvh` prints both side by side on the 2M-triangle sphere. So
//! the boolean keeps csg's tree and rays go through this one.
//!
//! Exactness: `obvhs` traverses in `f32`. The tree's boxes are the faces' `f64` boxes rounded
//! outward to `f32` and padded by a bound on the `f32` ray's error, so every face the `f64` ray
//! can hit is a candidate; each candidate is tested with [`WatertightRay`] on the `f64` mesh and
//! the nearest hit wins, ties to the lowest face index. The answer is therefore the same as
//! [`crate::SpatialIndex::ray_cast`]'s: a ray through a shared edge or vertex hits one of the faces
//! there.
//!
//! Size: the window keeps a tree per model for as long as the model lives, so the tree is built
//! with leaves of up to [`LEAF_FACES`] faces and keeps only what a traversal reads (the nodes and
//! the leaves' face order). One face per leaf made two 48-byte nodes per face, four times the
//! mesh's own `f64` data (the window's largest holding after loading); a ray now tests a few more
//! faces in each leaf it reaches.

use std::time::Duration;

use glam::Vec3A;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::ray::{Ray, RayHit as ObvhsHit};

use crate::spatial::{RayHit, WatertightRay};
use crate::{Aabb, DVec3, Mesh};

/// Direction components smaller than this (relative to the unit direction) are treated as zero
/// by the `f32` traversal; the padding covers the drift this allows inside the mesh's box.
const TINY_DIRECTION: f64 = 1.0 / (1u64 << 20) as f64;

/// The most faces a leaf of the tree holds (see the module documentation).
pub const LEAF_FACES: u32 = 4;

/// An `obvhs` BVH over a mesh's faces, for ray picks. Build it once per mesh (it does not follow
/// edits) and pass the same mesh to [`PickIndex::ray_cast`].
pub struct PickIndex {
    bvh: Bvh2,
    /// The mesh's box, padded like the face boxes.
    bounds: Aabb,
    /// Added on every side of every face box: bounds the `f32` ray's drift inside `bounds`.
    pad: f64,
    triangle_count: usize,
}

impl std::fmt::Debug for PickIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PickIndex")
            .field("triangles", &self.triangle_count)
            .field("nodes", &self.bvh.nodes.len())
            .finish()
    }
}

/// Largest `f32` not above `x`.
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// Smallest `f32` not below `x`.
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

impl PickIndex {
    /// Builds the tree over `mesh`'s faces (parallel PLOC, one face per leaf).
    pub fn build(mesh: &Mesh) -> PickIndex {
        let bbox = mesh.bbox();
        let (pad, bounds) = if bbox.is_empty() {
            (0.0, bbox)
        } else {
            // f32 rounding of the clipped origin (|x| <= the largest coordinate + a diagonal),
            // of the direction, and the drift of zeroed tiny components over one diagonal; all
            // far below 2^-18 of that scale.
            let scale = bbox.min.abs().max(bbox.max.abs()).max_element() + bbox.diagonal();
            let pad = scale / f64::from(1u32 << 18);
            let p = DVec3::splat(pad);
            (
                pad,
                Aabb {
                    min: bbox.min - p,
                    max: bbox.max + p,
                },
            )
        };
        let boxes: Vec<obvhs::aabb::Aabb> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                let (min, max) = (a.min(b).min(c) - pad, a.max(b).max(c) + pad);
                obvhs::aabb::Aabb::new(
                    Vec3A::new(round_down(min.x), round_down(min.y), round_down(min.z)),
                    Vec3A::new(round_up(max.x), round_up(max.y), round_up(max.z)),
                )
            })
            .collect();
        let params = BvhBuildParams {
            max_prims_per_leaf: LEAF_FACES,
            // Every subtree of up to LEAF_FACES faces becomes one leaf (a node costing as much
            // as LEAF_FACES face tests makes every such collapse pay): a node costs 48 bytes for
            // as long as the model lives, an extra face test a few nanoseconds per pick.
            collapse_traversal_cost: LEAF_FACES as f32,
            ..BvhBuildParams::fastest_build()
        };
        let mut bvh = obvhs::bvh2::builder::build_bvh2(&boxes, params, &mut Duration::default());
        drop(boxes);
        // A traversal reads the nodes and the leaves' face order only; the builder's maps back
        // (face to node, node to parent) and spare capacity would live as long as the tree.
        bvh.parents = Vec::new();
        bvh.primitives_to_nodes = Vec::new();
        bvh.primitive_indices_freelist = Vec::new();
        bvh.nodes.shrink_to_fit();
        bvh.primitive_indices.shrink_to_fit();
        PickIndex {
            bvh,
            bounds,
            pad,
            triangle_count: mesh.triangles.len(),
        }
    }

    /// Number of triangles indexed.
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// Bytes the tree holds on the heap (its nodes and the leaves' face order).
    pub fn heap_bytes(&self) -> usize {
        self.bvh.nodes.capacity() * size_of::<obvhs::bvh2::node::Bvh2Node>()
            + self.bvh.primitive_indices.capacity() * size_of::<u32>()
    }

    /// First hit of the ray `origin + t * direction`, `0 <= t <= t_max` (both faces of a
    /// triangle hit): the same answer as [`crate::SpatialIndex::ray_cast`] (watertight, ties to
    /// the lowest face index). `None` for a zero or non-finite direction.
    pub fn ray_cast(
        &self,
        mesh: &Mesh,
        origin: DVec3,
        direction: DVec3,
        t_max: f64,
    ) -> Option<RayHit> {
        debug_assert_eq!(
            mesh.triangles.len(),
            self.triangle_count,
            "index of another mesh"
        );
        let exact = WatertightRay::new(origin, direction)?;
        if self.bvh.nodes.is_empty() || t_max.is_nan() || t_max < 0.0 {
            return None;
        }
        // Clip to the padded mesh box in f64, so the f32 origin is near the mesh (its rounding
        // is then covered by the padding), and traverse with a unit direction.
        let (enter, leave) = clip(&self.bounds, origin, direction)?;
        if enter > t_max {
            return None;
        }
        let length = direction.length();
        let unit = direction / length;
        let unit = DVec3::select(
            unit.abs().cmplt(DVec3::splat(TINY_DIRECTION)),
            DVec3::ZERO,
            unit,
        );
        let start = origin + direction * enter;
        // The f32 traversal's parameter s is a distance from `start`: t = enter + s / length.
        let to_s = |t: f64| ((t - enter) * length + 2.0 * self.pad) as f32;
        let ray = Ray::new(
            start.as_vec3a(),
            unit.as_vec3a(),
            0.0,
            to_s(t_max.min(leave)).next_up(),
        );
        let mut best: Option<RayHit> = None;
        let mut stack = Vec::with_capacity(64);
        let mut hit = ObvhsHit::none();
        self.bvh
            .ray_traverse_dynamic(&mut stack, ray, &mut hit, |node, ray, _| {
                for i in node.first_index..node.first_index + node.prim_count {
                    let face = self.bvh.primitive_indices[i as usize];
                    let Some(h) = exact.intersect(mesh, face, t_max) else {
                        continue;
                    };
                    let better = match best {
                        None => true,
                        Some(b) => h.t < b.t || (h.t == b.t && face < b.face),
                    };
                    if better {
                        best = Some(h);
                        // Boxes entered beyond the hit (plus the padding) cannot hold a
                        // nearer or tied face.
                        ray.tmax = ray.tmax.min(to_s(h.t).next_up());
                    }
                }
                true
            });
        best
    }
}

/// Parameters where `origin + t * direction` enters and leaves `b` (enter clamped to 0); None
/// when it misses or `b` lies behind the origin.
fn clip(b: &Aabb, origin: DVec3, direction: DVec3) -> Option<(f64, f64)> {
    let mut near = 0.0f64;
    let mut far = f64::INFINITY;
    for axis in 0..3 {
        let (o, d) = (origin[axis], direction[axis]);
        if d == 0.0 {
            if o < b.min[axis] || o > b.max[axis] {
                return None;
            }
            continue;
        }
        let t0 = (b.min[axis] - o) / d;
        let t1 = (b.max[axis] - o) / d;
        near = near.max(t0.min(t1));
        far = far.min(t0.max(t1));
    }
    (near <= far).then_some((near, far))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SpatialIndex;
    use crate::testkit;

    /// Both trees give the same face and `t` for `rays`; returns how many hit.
    fn same_picks(mesh: &Mesh, rays: &[(DVec3, DVec3, f64)]) -> usize {
        let ours = PickIndex::build(mesh);
        let theirs = SpatialIndex::build(mesh);
        let mut hits = 0;
        for &(o, d, t_max) in rays {
            let a = ours.ray_cast(mesh, o, d, t_max).map(|h| (h.face, h.t));
            let b = theirs.ray_cast(mesh, o, d, t_max).map(|h| (h.face, h.t));
            assert_eq!(a, b, "ray {o} + t {d}, t <= {t_max}");
            hits += usize::from(a.is_some());
        }
        hits
    }

    #[test]
    fn random_rays_pick_what_the_spatial_index_picks() {
        let mesh = testkit::icosphere(4, 1.0);
        let mut rng = testkit::SplitMix(7);
        let mut rays = Vec::new();
        for _ in 0..2000 {
            // From outside and from inside, aimed near the sphere, some with a short reach.
            let o = rng.in_cube(1.0) * 3.0;
            let d = rng.in_cube(1.0) * 0.2 - o * rng.next_f64();
            let t_max = if rng.next_f64() < 0.2 {
                rng.next_f64()
            } else {
                f64::INFINITY
            };
            rays.push((o, d, t_max));
        }
        let hits = same_picks(&mesh, &rays);
        assert!(hits > 500 && hits < 2000, "{hits} of 2000 rays hit");
    }

    #[test]
    fn rays_through_vertices_and_edges_and_along_axes_hit_one_face_there() {
        let mesh = testkit::icosphere(3, 1.0);
        let mut rays = Vec::new();
        for t in (0..mesh.triangles.len()).step_by(7) {
            let [a, b, c] = mesh.corners(t);
            for target in [a, (a + b) * 0.5, (a + b + c) / 3.0] {
                // From far away (the f32 origin would be far from the mesh without clipping).
                let o = target * 1e4 + DVec3::new(0.0, 0.0, 1e-3);
                rays.push((o, target - o, f64::INFINITY));
            }
        }
        // Axis-parallel rays, and rays with a tiny component along an axis.
        for k in 0..50 {
            let y = -0.9 + 0.036 * k as f64;
            rays.push((DVec3::new(-5.0, y, 0.1), DVec3::X, f64::INFINITY));
            rays.push((
                DVec3::new(-5.0, y, 0.1),
                DVec3::new(1.0, 1e-12, -1e-9),
                f64::INFINITY,
            ));
        }
        let hits = same_picks(&mesh, &rays);
        assert!(hits >= rays.len() - 10, "{hits} of {} rays hit", rays.len());
    }

    #[test]
    fn far_meshes_and_empty_meshes() {
        // A mesh far from the origin: f32 keeps ~7 digits, the padding scales with it.
        let mut mesh = testkit::icosphere(3, 1.0);
        for p in &mut mesh.positions {
            *p += DVec3::new(1e5, -2e5, 3e4);
        }
        let centre = DVec3::new(1e5, -2e5, 3e4);
        let mut rng = testkit::SplitMix(11);
        let rays: Vec<_> = (0..500)
            .map(|_| {
                let o = centre + rng.in_cube(1.0) * 4.0;
                (o, centre + rng.in_cube(1.0) * 0.5 - o, f64::INFINITY)
            })
            .collect();
        assert!(same_picks(&mesh, &rays) > 400);
        let empty = Mesh::default();
        let index = PickIndex::build(&empty);
        assert!(index.ray_cast(&empty, DVec3::ZERO, DVec3::X, 1.0).is_none());
        assert!(
            PickIndex::build(&mesh)
                .ray_cast(&mesh, centre, DVec3::ZERO, 1.0)
                .is_none()
        );
    }
}
