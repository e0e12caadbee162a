//! A mesh's vertices as they are drawn: `f32` positions with area-weighted smooth normals and
//! the incision-wall flag, in the layout the renderer's vertex buffers take. The live cut's and
//! the scalpel's deltas ([`super::delta`]) and the wall split ([`super::wall_split`]) build
//! them here, off the UI thread, so the renderer only uploads.

use bytemuck::{Pod, Zeroable};
use csg::Mesh;
use glam::DVec3;

/// One mesh vertex. Keep in sync with `VertexIn` in `mesh.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Vertex {
    pub position_in_world: [f32; 3],
    /// Area-weighted vertex normal, unit length (zero for isolated vertices).
    pub normal_in_world: [f32; 3],
    /// 1 for a corner of an incision wall (drawn in the draw's wall colour), 0 elsewhere
    /// ([`super::wall_split`]).
    pub wall: f32,
}

/// Vertices of `mesh` with area-weighted smooth normals (each face adds its unnormalized normal,
/// which is twice its area long, to its three corners).
pub fn mesh_vertices(mesh: &Mesh) -> Vec<Vertex> {
    let mut normals = vec![DVec3::ZERO; mesh.positions.len()];
    for t in 0..mesh.triangles.len() {
        let n = mesh.face_normal_scaled(t);
        for &i in &mesh.triangles[t] {
            normals[i as usize] += n;
        }
    }
    vertices_with_normals(&mesh.positions, &normals)
}

/// GPU vertices from positions and summed (unnormalized) normals; a zero sum gives a zero normal.
pub fn vertices_with_normals(positions: &[DVec3], normal_sums: &[DVec3]) -> Vec<Vertex> {
    positions
        .iter()
        .zip(normal_sums)
        .map(|(&p, &n)| super::wall_split::vertex(p, n, false))
        .collect()
}
