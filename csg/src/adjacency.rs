//! Edge → faces adjacency that tolerates boundary and non-manifold edges.
//!
//! OWNER: core helper (foundation issue). Signatures are fixed; bodies to be written.

use crate::mesh::Mesh;

/// Undirected edges of a mesh and the faces around each, in CSR form.
#[derive(Clone, Debug, Default)]
pub struct EdgeAdjacency {
    /// Undirected edges as `[lo, hi]` vertex indices with `lo < hi`, sorted, without duplicates.
    pub edges: Vec<[u32; 2]>,
    /// CSR offsets: the faces of edge `e` are `edge_faces[edge_face_offsets[e]..edge_face_offsets[e + 1]]`.
    /// Length is `edges.len() + 1`.
    pub edge_face_offsets: Vec<u32>,
    /// Face indices, grouped per edge (see `edge_face_offsets`), ascending within a group.
    pub edge_faces: Vec<u32>,
    /// For each triangle, its three edge ids: entry `k` is the edge from corner `k` to corner `(k + 1) % 3`.
    /// Same length as `mesh.triangles`.
    pub triangle_edges: Vec<[u32; 3]>,
}

impl EdgeAdjacency {
    /// Builds the adjacency of `mesh` (degenerate triangles with repeated indices included as they are).
    pub fn build(mesh: &Mesh) -> EdgeAdjacency {
        let _ = mesh;
        unimplemented!("core helper")
    }

    /// Faces using edge `e`.
    pub fn faces_of_edge(&self, e: u32) -> &[u32] {
        let e = e as usize;
        &self.edge_faces[self.edge_face_offsets[e] as usize..self.edge_face_offsets[e + 1] as usize]
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }
}
