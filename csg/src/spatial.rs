//! Spatial index over a mesh's triangles (wraps `obvhs`; its primitive remapping is hidden).
//!
//! `obvhs` builds a good binary BVH fast (PLOC), but it works in `f32` and renumbers its
//! primitives. This module keeps both facts inside:
//!
//! * **Conservative boxes.** Every triangle's `f64` box is rounded *outward* to `f32` before the
//!   build, so each node box contains its triangles exactly. Traversal happens here, in `f64`,
//!   over `obvhs`'s node array, with box tests widened by a few ulps, so no query can miss a
//!   triangle because of rounding. The triangle tests themselves run on the mesh's `f64` data.
//! * **Mesh face ids.** Every answer names a triangle by its index in the mesh.
//!
//! Queries take the same `&Mesh` the index was built from (its triangle count is checked in debug
//! builds); the index stores no copy of the geometry, only the tree.
//!
//! Ray casting uses the watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013) in
//! `f64`: a ray through a shared edge or vertex hits at least one of the triangles around it,
//! which parity counts and "pick the surface under the mouse" rely on. Closest-point queries are a
//! depth-first traversal that visits the nearer child first and prunes boxes farther than the best
//! point found, with the closest point on a triangle from Ericson (Real-Time Collision Detection,
//! 5.1.5), made safe for degenerate triangles.
//!
//! Coordinates beyond the `f32` range (about 3.4e38) are clamped there, and triangles out there may
//! be missed.

use std::fmt;
use std::time::Duration;

use glam::{DVec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;

use crate::aabb::Aabb;
use crate::mesh::Mesh;

/// A ray's first hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Triangle index in the mesh.
    pub face: u32,
    /// Ray parameter: the hit is `origin + t * direction`.
    pub t: f64,
    /// Barycentric weights of the triangle's corners 0, 1, 2 (sum 1).
    pub bary: DVec3,
    /// The hit point.
    pub point: DVec3,
}

/// The point of the surface closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    /// Triangle index in the mesh.
    pub face: u32,
    /// The closest point (on triangle `face`, up to rounding).
    pub point: DVec3,
    /// Barycentric weights of the triangle's corners 0, 1, 2 (each in `0..=1`, sum 1).
    pub bary: DVec3,
    /// Distance from the query point to `point`.
    pub distance: f64,
}

/// Build settings: `obvhs`'s fastest preset (PLOC with the minimum search distance, no
/// reinsertion, no leaf collapse), so every leaf holds exactly one face and its box is that face's
/// box. Measured on a 1M-triangle sphere (`benches/index.rs`): about half the build time of the
/// "very fast" preset (eight faces per leaf) at the same ray and closest-point query cost, for
/// about twice the node memory (48 bytes per node, `2n - 1` nodes).
const BUILD_PARAMS: BvhBuildParams = BvhBuildParams::fastest_build();

/// A BVH over the triangles of one mesh.
#[derive(Clone)]
pub struct SpatialIndex {
    /// The tree. Every leaf holds exactly one face: `bvh.primitive_indices[leaf.first_index]`, a
    /// mesh face id; every face is in exactly one leaf, and a leaf's box is its face's box. Empty
    /// (no node) for a mesh without triangles. Boxes contain the `f64` triangles exactly (rounded
    /// outward to `f32`).
    bvh: Bvh2,
    /// Number of triangles of the mesh the index was built from.
    triangle_count: usize,
    /// Absolute widening of node boxes during traversal, covering the rounding of `f64`
    /// arithmetic on coordinates of the mesh's magnitude (a few ulps of its largest coordinate).
    slack: f64,
}

impl fmt::Debug for SpatialIndex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SpatialIndex")
            .field("triangle_count", &self.triangle_count)
            .field("nodes", &self.bvh.nodes.len())
            .field("slack", &self.slack)
            .finish()
    }
}

/// Largest `f32` not above `x` (clamped to the finite `f32` range).
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    let f = if f as f64 > x { f.next_down() } else { f };
    f.max(-f32::MAX)
}

/// Smallest `f32` not below `x` (clamped to the finite `f32` range).
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    let f = if (f as f64) < x { f.next_up() } else { f };
    f.min(f32::MAX)
}

/// A node's box in `f64` (exact conversion), widened by `slack`.
#[inline(always)]
fn node_box(node: &Bvh2Node, slack: f64) -> (DVec3, DVec3) {
    let b = node.aabb();
    (
        b.min.as_dvec3() - DVec3::splat(slack),
        b.max.as_dvec3() + DVec3::splat(slack),
    )
}

/// Squared distance from `p` to the box `[min, max]` (0 inside).
#[inline(always)]
fn box_distance_squared(p: DVec3, (min, max): (DVec3, DVec3)) -> f64 {
    let d = (min - p).max(p - max).max(DVec3::ZERO);
    d.length_squared()
}

impl SpatialIndex {
    /// Builds the index for `mesh`.
    ///
    /// Requires a structurally valid mesh ([`Mesh::sanity_check`]).
    pub fn build(mesh: &Mesh) -> SpatialIndex {
        let mut max_abs = 0.0f64;
        let boxes: Vec<obvhs::aabb::Aabb> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                let (min, max) = (a.min(b).min(c), a.max(b).max(c));
                max_abs = max_abs
                    .max(min.abs().max_element())
                    .max(max.abs().max_element());
                obvhs::aabb::Aabb::new(
                    Vec3A::new(round_down(min.x), round_down(min.y), round_down(min.z)),
                    Vec3A::new(round_up(max.x), round_up(max.y), round_up(max.z)),
                )
            })
            .collect();
        let bvh = if boxes.is_empty() {
            Bvh2::default()
        } else {
            obvhs::bvh2::builder::build_bvh2(&boxes, BUILD_PARAMS, &mut Duration::default())
        };
        SpatialIndex {
            bvh,
            triangle_count: mesh.triangles.len(),
            slack: 16.0 * f64::EPSILON * max_abs,
        }
    }

    /// Number of triangles indexed.
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// The face of leaf `node` (each leaf holds exactly one).
    #[inline(always)]
    fn leaf_face(&self, node: &Bvh2Node) -> u32 {
        self.bvh.primitive_indices[node.first_index as usize]
    }

    /// First hit of the ray `origin + t * direction`, `0 <= t <= t_max` (both faces of a triangle hit).
    ///
    /// Watertight: a ray through a shared edge or vertex hits one of the triangles there. A ray
    /// lying in a triangle's plane does not hit it. Of several hits at the same `t`, the lowest
    /// face index wins. Returns `None` for a zero or non-finite direction.
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
        let ray = WatertightRay::new(origin, direction)?;
        if self.bvh.nodes.is_empty() || t_max.is_nan() || t_max < 0.0 {
            return None;
        }
        let inv = DVec3::ONE / direction;
        // Relative widening of slab parameters: two roundings each, compared across axes.
        let widen = 1.0 + 4.0 * f64::EPSILON;
        // Entry parameter of the ray into a box, None when it misses the box or the box lies
        // behind the origin.
        let enter_box = |(min, max): (DVec3, DVec3)| -> Option<f64> {
            let mut near = 0.0f64;
            let mut far = f64::INFINITY;
            for axis in 0..3 {
                if direction[axis] == 0.0 {
                    if origin[axis] < min[axis] || origin[axis] > max[axis] {
                        return None;
                    }
                    continue;
                }
                let t0 = (min[axis] - origin[axis]) * inv[axis];
                let t1 = (max[axis] - origin[axis]) * inv[axis];
                near = near.max(t0.min(t1));
                far = far.min(t0.max(t1));
            }
            (near <= far * widen).then_some(near)
        };
        let enter = |node: &Bvh2Node| enter_box(node_box(node, self.slack));

        let mut best: Option<RayHit> = None;
        let mut best_t = t_max;
        // (node, entry parameter); entries are re-checked when popped, as `best_t` shrinks.
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        if let Some(t) = enter(&self.bvh.nodes[0]) {
            stack.push((0, t));
        }
        while let Some((index, t_enter)) = stack.pop() {
            if t_enter > best_t * widen {
                continue;
            }
            let node = &self.bvh.nodes[index as usize];
            if node.is_leaf() {
                // Tested against `t_max`, not `best_t`, so that ties are decided by face index
                // on the computed `t` whatever order the tree visits them in.
                let face = self.leaf_face(node);
                if let Some(hit) = ray.intersect(mesh, face, t_max) {
                    let better = match best {
                        None => true,
                        Some(b) => hit.t < b.t || (hit.t == b.t && face < b.face),
                    };
                    if better {
                        best_t = hit.t;
                        best = Some(hit);
                    }
                }
                continue;
            }
            let limit = best_t * widen;
            let (l, r) = (node.first_index, node.first_index + 1);
            let hits = [l, r].map(|child| {
                enter(&self.bvh.nodes[child as usize])
                    .filter(|&t| t <= limit)
                    .map(|t| (child, t))
            });
            // Push the farther child first so the nearer one is visited first.
            match hits {
                [Some(a), Some(b)] => {
                    let (near, far) = if a.1 <= b.1 { (a, b) } else { (b, a) };
                    stack.push(far);
                    stack.push(near);
                }
                [Some(only), None] | [None, Some(only)] => stack.push(only),
                [None, None] => {}
            }
        }
        best
    }

    /// Appends to `out` every triangle whose bounding box overlaps `aabb` (inclusive; may include
    /// triangles whose box overlaps but the triangle itself does not).
    ///
    /// Conservative: every triangle whose exact `f64` box overlaps `aabb` is reported; a triangle
    /// whose box misses `aabb` by less than an `f32` ulp may be reported too. Order is the tree's.
    pub fn faces_in_box(&self, aabb: &Aabb, out: &mut Vec<u32>) {
        if aabb.is_empty() {
            return;
        }
        self.faces_where(
            |min, max| min.cmple(aabb.max).all() && aabb.min.cmple(max).all(),
            out,
        );
    }

    /// Appends to `out` the face of every leaf reached by descending only into nodes whose box
    /// (`min`, `max`: the node's `f32` box converted exactly to `f64`, not widened) passes
    /// `enter`. [`SpatialIndex::faces_in_box`] is this with a box-overlap test; the boolean
    /// also prunes by the cutter face's plane. Order is the tree's.
    pub fn faces_where(&self, mut enter: impl FnMut(DVec3, DVec3) -> bool, out: &mut Vec<u32>) {
        let mut test = |node: &Bvh2Node| {
            let b = node.aabb();
            enter(b.min.as_dvec3(), b.max.as_dvec3())
        };
        if self.bvh.nodes.is_empty() || !test(&self.bvh.nodes[0]) {
            return;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = &self.bvh.nodes[index as usize];
            if node.is_leaf() {
                out.push(self.leaf_face(node));
                continue;
            }
            for child in [node.first_index, node.first_index + 1] {
                if test(&self.bvh.nodes[child as usize]) {
                    stack.push(child);
                }
            }
        }
    }

    /// Closest surface point to `p` (None for an empty mesh).
    ///
    /// Of several faces at the same distance, the lowest face index wins.
    pub fn closest_point(&self, mesh: &Mesh, p: DVec3) -> Option<ClosestPoint> {
        self.closest_point_within(mesh, p, f64::INFINITY)
    }

    /// Closest surface point to `p` if it is at most `max_distance` away (None otherwise, or for
    /// an empty mesh, or a non-finite `p`). A small `max_distance` prunes most of the tree, so
    /// "is there surface near here" queries are cheaper than [`SpatialIndex::closest_point`].
    pub fn closest_point_within(
        &self,
        mesh: &Mesh,
        p: DVec3,
        max_distance: f64,
    ) -> Option<ClosestPoint> {
        debug_assert_eq!(
            mesh.triangles.len(),
            self.triangle_count,
            "index of another mesh"
        );
        if self.bvh.nodes.is_empty()
            || !p.is_finite()
            || max_distance.is_nan()
            || max_distance < 0.0
        {
            return None;
        }
        // Relative widening for pruning on squared distances.
        let widen = 1.0 + 8.0 * f64::EPSILON;
        let mut best: Option<(u32, DVec3, DVec3)> = None;
        let mut best_d2 = max_distance * max_distance;
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        let root_d2 = box_distance_squared(p, node_box(&self.bvh.nodes[0], self.slack));
        if root_d2 <= best_d2 * widen {
            stack.push((0, root_d2));
        }
        while let Some((index, d2)) = stack.pop() {
            if d2 > best_d2 * widen {
                continue;
            }
            let node = &self.bvh.nodes[index as usize];
            if node.is_leaf() {
                let face = self.leaf_face(node);
                let [a, b, c] = mesh.corners(face as usize);
                let (q, bary) = closest_on_triangle(p, a, b, c);
                let e2 = (p - q).length_squared();
                let better = match best {
                    None => e2 <= best_d2,
                    Some((f, _, _)) => e2 < best_d2 || (e2 == best_d2 && face < f),
                };
                if better {
                    best_d2 = e2;
                    best = Some((face, q, bary));
                }
                continue;
            }
            let (l, r) = (node.first_index, node.first_index + 1);
            let dl = box_distance_squared(p, node_box(&self.bvh.nodes[l as usize], self.slack));
            let dr = box_distance_squared(p, node_box(&self.bvh.nodes[r as usize], self.slack));
            let limit = best_d2 * widen;
            let (first, d_first, second, d_second) = if dl <= dr {
                (l, dl, r, dr)
            } else {
                (r, dr, l, dl)
            };
            if d_second <= limit {
                stack.push((second, d_second));
            }
            if d_first <= limit {
                stack.push((first, d_first));
            }
        }
        best.map(|(face, point, bary)| ClosestPoint {
            face,
            point,
            bary,
            distance: best_d2.sqrt(),
        })
    }

    /// Checks the index against `mesh`: built for its triangle count, every face in exactly one
    /// leaf and alone there, and every node box containing its children's boxes and its face's
    /// `f64` corners.
    pub fn sanity_check(&self, mesh: &Mesh) -> Result<(), String> {
        let SpatialIndex {
            bvh,
            triangle_count,
            slack,
        } = self;
        if *triangle_count != mesh.triangles.len() {
            return Err(format!(
                "index built for {triangle_count} triangles, mesh has {}",
                mesh.triangles.len()
            ));
        }
        if !(slack.is_finite() && *slack >= 0.0) {
            return Err(format!("slack {slack} is not a finite non-negative number"));
        }
        if bvh.nodes.is_empty() {
            return if *triangle_count == 0 {
                Ok(())
            } else {
                Err("no tree for a non-empty mesh".into())
            };
        }
        let mut seen = vec![false; *triangle_count];
        let mut stack = vec![0u32];
        let contains = |outer: &Bvh2Node, p: DVec3| {
            let b = outer.aabb();
            b.min.as_dvec3().cmple(p).all() && p.cmple(b.max.as_dvec3()).all()
        };
        while let Some(index) = stack.pop() {
            let node = bvh
                .nodes
                .get(index as usize)
                .ok_or_else(|| format!("node {index} out of range"))?;
            if node.is_leaf() {
                if node.prim_count != 1 {
                    return Err(format!("leaf {index} holds {} faces", node.prim_count));
                }
                let face = *bvh
                    .primitive_indices
                    .get(node.first_index as usize)
                    .ok_or_else(|| format!("leaf {index} primitive out of range"))?;
                let slot = seen
                    .get_mut(face as usize)
                    .ok_or_else(|| format!("leaf {index} names face {face}"))?;
                if std::mem::replace(slot, true) {
                    return Err(format!("face {face} is in two leaves"));
                }
                if !mesh
                    .corners(face as usize)
                    .iter()
                    .all(|&c| contains(node, c))
                {
                    return Err(format!("leaf {index} box does not contain face {face}"));
                }
                continue;
            }
            for child in [node.first_index, node.first_index + 1] {
                let c = bvh
                    .nodes
                    .get(child as usize)
                    .ok_or_else(|| format!("child {child} of node {index} out of range"))?;
                let b = c.aabb();
                if !contains(node, b.min.as_dvec3()) || !contains(node, b.max.as_dvec3()) {
                    return Err(format!("node {index} does not contain child {child}"));
                }
                stack.push(child);
            }
        }
        match seen.iter().position(|s| !s) {
            Some(face) => Err(format!("face {face} is in no leaf")),
            None => Ok(()),
        }
    }
}

/// A ray prepared for the watertight test: the axis of largest direction becomes "z" and the
/// ray is sheared to run along it, so each triangle edge is tested by a 2D edge function that is
/// computed identically (up to sign) for both triangles sharing it.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    origin: DVec3,
    direction: DVec3,
    /// Permuted axes: `kz` is the dominant direction axis; `kx`, `ky` keep the winding.
    kx: usize,
    ky: usize,
    kz: usize,
    /// Shear constants.
    shear: DVec3,
}

impl WatertightRay {
    /// Prepares the ray; None for a zero or non-finite direction or a non-finite origin.
    pub fn new(origin: DVec3, direction: DVec3) -> Option<WatertightRay> {
        if !origin.is_finite() || !direction.is_finite() || direction == DVec3::ZERO {
            return None;
        }
        let abs = direction.abs();
        let kz = if abs.x >= abs.y && abs.x >= abs.z {
            0
        } else if abs.y >= abs.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if direction[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let shear = DVec3::new(
            direction[kx] / direction[kz],
            direction[ky] / direction[kz],
            1.0 / direction[kz],
        );
        Some(WatertightRay {
            origin,
            direction,
            kx,
            ky,
            kz,
            shear,
        })
    }

    /// Hit of triangle `face` of `mesh` with `0 <= t <= t_max`, either side.
    pub fn intersect(&self, mesh: &Mesh, face: u32, t_max: f64) -> Option<RayHit> {
        let corners = mesh.corners(face as usize);
        let [a, b, c] = corners.map(|v| v - self.origin);
        let (kx, ky, kz, s) = (self.kx, self.ky, self.kz, self.shear);
        let ax = a[kx] - s.x * a[kz];
        let ay = a[ky] - s.y * a[kz];
        let bx = b[kx] - s.x * b[kz];
        let by = b[ky] - s.y * b[kz];
        let cx = c[kx] - s.x * c[kz];
        let cy = c[ky] - s.y * c[kz];
        // Edge functions; u belongs to corner 0 (edge b-c), v to corner 1, w to corner 2.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let (az, bz, cz) = (s.z * a[kz], s.z * b[kz], s.z * c[kz]);
        let t_scaled = u * az + v * bz + w * cz;
        // t = t_scaled / det must lie in [0, t_max]; compare without dividing.
        let (t_scaled, det_abs) = if det < 0.0 {
            (-t_scaled, -det)
        } else {
            (t_scaled, det)
        };
        if t_scaled < 0.0 || t_scaled > t_max * det_abs {
            return None;
        }
        let inv = 1.0 / det;
        let bary = DVec3::new(u * inv, v * inv, w * inv);
        let t = (t_scaled / det_abs).min(t_max);
        Some(RayHit {
            face,
            t,
            bary,
            point: self.origin + self.direction * t,
        })
    }
}

/// Closest point to `p` on triangle `abc` and its barycentric weights. Safe for degenerate
/// triangles (collinear or coincident corners): they fall back to the nearest of their sides.
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, DVec3::X);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, DVec3::Y);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = ratio(d1, d1 - d3);
        return (a + ab * v, DVec3::new(1.0 - v, v, 0.0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, DVec3::Z);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = ratio(d2, d2 - d6);
        return (a + ac * w, DVec3::new(1.0 - w, 0.0, w));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, DVec3::new(0.0, 1.0 - w, w));
    }
    let denom = va + vb + vc;
    if denom > 0.0 {
        let v = vb / denom;
        let w = vc / denom;
        let q = a + ab * v + ac * w;
        if q.is_finite() && v >= 0.0 && w >= 0.0 && v + w <= 1.0 {
            return (q, DVec3::new(1.0 - v - w, v, w));
        }
    }
    // Degenerate (or rounding put us nowhere): the nearest point on the three sides.
    let sides = [
        closest_on_segment(p, a, b),
        closest_on_segment(p, b, c),
        closest_on_segment(p, c, a),
    ];
    let mut best = 0;
    for k in 1..3 {
        if (p - sides[k].0).length_squared() < (p - sides[best].0).length_squared() {
            best = k;
        }
    }
    let (q, s) = sides[best];
    let mut bary = DVec3::ZERO;
    bary[best] = 1.0 - s;
    bary[(best + 1) % 3] += s;
    (q, bary)
}

/// `n / d` clamped to `0..=1`, 0 when `d` is not positive.
fn ratio(n: f64, d: f64) -> f64 {
    if d > 0.0 {
        (n / d).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point on segment `ab` to `p` and its parameter in `0..=1`.
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (DVec3, f64) {
    let ab = b - a;
    let s = ratio((p - a).dot(ab), ab.length_squared());
    (a + ab * s, s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    #[test]
    fn empty_and_single() {
        let empty = Mesh::default();
        let index = SpatialIndex::build(&empty);
        index.sanity_check(&empty).unwrap();
        assert_eq!(index.closest_point(&empty, DVec3::ZERO), None);
        assert_eq!(index.ray_cast(&empty, DVec3::ZERO, DVec3::X, 1.0), None);
        let mut out = vec![];
        index.faces_in_box(
            &Aabb {
                min: DVec3::splat(-1.0),
                max: DVec3::ONE,
            },
            &mut out,
        );
        assert!(out.is_empty());

        let tri = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let index = SpatialIndex::build(&tri);
        index.sanity_check(&tri).unwrap();
        let hit = index
            .ray_cast(&tri, DVec3::new(0.25, 0.25, 1.0), DVec3::NEG_Z, 10.0)
            .unwrap();
        assert_eq!((hit.face, hit.t), (0, 1.0));
        assert_eq!(hit.bary, DVec3::new(0.5, 0.25, 0.25));
        assert_eq!(hit.point, DVec3::new(0.25, 0.25, 0.0));
        // From below too (both sides), and not beyond t_max.
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 10.0)
                .is_some()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 0.5)
                .is_none()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::NEG_Z, 10.0)
                .is_none()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::ZERO, DVec3::ZERO, 10.0)
                .is_none()
        );
        let cp = index
            .closest_point(&tri, DVec3::new(2.0, 2.0, 3.0))
            .unwrap();
        assert_eq!(cp.point, DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(cp.bary, DVec3::new(0.0, 0.5, 0.5));
        assert!(
            index
                .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.6)
                .is_none()
        );
        assert!(
            index
                .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.7)
                .is_some()
        );
    }

    #[test]
    fn rays_through_shared_edges_and_vertices_hit() {
        // Axis rays through every vertex and edge midpoint of an axis-aligned cube must hit.
        let m = testkit::cube(DVec3::splat(-1.0), DVec3::ONE);
        let index = SpatialIndex::build(&m);
        index.sanity_check(&m).unwrap();
        for x in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            for y in [-1.0, -0.5, 0.0, 0.5, 1.0] {
                let hit = index.ray_cast(&m, DVec3::new(x, y, 5.0), DVec3::NEG_Z, 100.0);
                let hit = hit.unwrap_or_else(|| panic!("ray at ({x}, {y}) missed"));
                assert_eq!(hit.t, 4.0);
            }
        }
    }

    #[test]
    fn degenerate_triangles_closest_point() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
        let (q, bary) = closest_on_triangle(DVec3::new(1.5, 1.0, 0.0), a, b, c);
        assert_eq!(q, DVec3::new(1.5, 0.0, 0.0));
        assert!((bary.x + bary.y + bary.z - 1.0).abs() < 1e-15);
        assert_eq!(a * bary.x + b * bary.y + c * bary.z, q);
        let (q, _) = closest_on_triangle(DVec3::ONE, a, a, a);
        assert_eq!(q, a);
    }

    #[test]
    fn icosphere_queries() {
        let m = testkit::icosphere(3, 2.0);
        let index = SpatialIndex::build(&m);
        index.sanity_check(&m).unwrap();
        let hit = index
            .ray_cast(&m, DVec3::new(0.0, 0.0, -10.0), DVec3::Z, f64::INFINITY)
            .unwrap();
        assert!((hit.t - 8.0).abs() < 0.05 && hit.point.z < 0.0);
        let cp = index.closest_point(&m, DVec3::new(0.0, 0.0, 0.1)).unwrap();
        assert!((cp.distance - 1.9).abs() < 0.05);
        let mut out = vec![];
        index.faces_in_box(&m.bbox(), &mut out);
        out.sort_unstable();
        assert_eq!(out, (0..m.triangle_count() as u32).collect::<Vec<_>>());
    }
}
