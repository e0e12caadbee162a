//! Topological validation report of a mesh: closed, manifold, oriented, degenerate faces.
//!
//! OWNER: core helper (foundation issue). Signatures are fixed; bodies to be written.

use crate::mesh::Mesh;

/// Topological facts about a mesh. Cutaway accepts open and non-manifold meshes; this report says
/// what the mesh is so that callers can decide (and `cutaway info` can print it).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshReport {
    pub vertices: usize,
    pub triangles: usize,
    pub edges: usize,
    /// Edges used by exactly one face.
    pub boundary_edges: usize,
    /// Edges used by three or more faces.
    pub nonmanifold_edges: usize,
    /// Manifold edges whose two faces traverse it in the same direction (inconsistent orientation).
    pub misoriented_edges: usize,
    /// Triangles with a repeated vertex index or collinear corners (exact test).
    pub degenerate_triangles: usize,
    /// Vertices whose faces form more than one fan (non-manifold vertices).
    pub nonmanifold_vertices: usize,
    /// Connected components (see [`crate::regions`]).
    pub regions: usize,
    /// Every edge is used by exactly two faces.
    pub closed: bool,
    /// No non-manifold edge or vertex and consistently oriented.
    pub manifold: bool,
}

impl Mesh {
    /// Computes the topological report.
    pub fn report(&self) -> MeshReport {
        unimplemented!("core helper")
    }
}
