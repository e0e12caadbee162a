//! Spatial index over a mesh's triangles (wraps `obvhs`; its primitive remapping is hidden).
//!
//! OWNER: core helper (foundation issue). Signatures are fixed; bodies to be written.
//! Queries take the same `&Mesh` the index was built from (checked in debug builds).

use glam::DVec3;

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
    pub face: u32,
    pub point: DVec3,
    pub bary: DVec3,
    pub distance: f64,
}

/// A BVH over the triangles of one mesh.
#[derive(Clone, Debug)]
pub struct SpatialIndex {
    _private: (),
}

impl SpatialIndex {
    /// Builds the index for `mesh`.
    pub fn build(mesh: &Mesh) -> SpatialIndex {
        let _ = mesh;
        unimplemented!("core helper")
    }

    /// First hit of the ray `origin + t * direction`, `0 <= t <= t_max` (both faces of a triangle hit).
    pub fn ray_cast(&self, mesh: &Mesh, origin: DVec3, direction: DVec3, t_max: f64) -> Option<RayHit> {
        let _ = (mesh, origin, direction, t_max);
        unimplemented!("core helper")
    }

    /// Appends to `out` every triangle whose bounding box overlaps `aabb` (inclusive; may include
    /// triangles whose box overlaps but the triangle itself does not).
    pub fn faces_in_box(&self, aabb: &Aabb, out: &mut Vec<u32>) {
        let _ = (aabb, out);
        unimplemented!("core helper")
    }

    /// Closest surface point to `p` (None for an empty mesh).
    pub fn closest_point(&self, mesh: &Mesh, p: DVec3) -> Option<ClosestPoint> {
        let _ = (mesh, p);
        unimplemented!("core helper")
    }
}
