//! Regions: connected components of a mesh (faces joined through shared edges).
//!
//! OWNER: core helper (foundation issue). Signatures are fixed; bodies to be written.

use crate::adjacency::EdgeAdjacency;
use crate::mesh::Mesh;

/// The region of every triangle.
#[derive(Clone, Debug, Default)]
pub struct Regions {
    /// Region id of each triangle, in `0..count`. Regions are numbered in order of their first
    /// triangle. Same length as `mesh.triangles`.
    pub region_of_triangle: Vec<u32>,
    /// Number of regions.
    pub count: usize,
}

impl Regions {
    /// Labels edge-connected components of `mesh` (non-manifold edges connect all their faces).
    pub fn build(mesh: &Mesh, adjacency: &EdgeAdjacency) -> Regions {
        let _ = (mesh, adjacency);
        unimplemented!("core helper")
    }
}

/// Splits `mesh` into one compacted mesh per region, in region order. Vertex coordinates are kept bit-exact.
pub fn split_regions(mesh: &Mesh) -> Vec<Mesh> {
    let _ = mesh;
    unimplemented!("core helper")
}
