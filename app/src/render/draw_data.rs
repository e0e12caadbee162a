//! Per-mesh and per-frame GPU data: CPU conversions (edges and polylines → line segments; f64
//! meshes → f32 vertices with smooth normals are `crate::cutting::vertices`) and the buffers that
//! hold them.
//!
//! Model meshes and preview parts are uploaded once and cached by the renderer; cutter overlays
//! are small and re-uploaded every frame.

use std::collections::HashSet;

use csg::Mesh;
use glam::DVec3;
use wgpu::util::DeviceExt as _;

use super::gpu_data::{RiskVertex, Segment};
use crate::cutting::vertices::mesh_vertices;
use crate::cutting::wall_risk::{RiskWall, WallRisk};

/// The vertices and triangles of a wall coloured by the risk map: one vertex per triangle
/// corner (a corner's distance belongs to its triangle, see [`crate::cutting::wall_risk`]) with
/// the corner's ramp position under the map's settings, and the normal of `source` (the wall it was
/// refined from) interpolated there, unnormalized, so the refined wall shades exactly as
/// `source` drawn as it is.
pub fn risk_vertices(
    wall: &RiskWall,
    risk: &WallRisk,
    source: &Mesh,
) -> (Vec<RiskVertex>, Vec<[u32; 3]>) {
    let smooth = mesh_vertices(source);
    let normal = |v: u32| DVec3::from(smooth[v as usize].normal_in_world.map(f64::from));
    let normals: Vec<[f32; 3]> = wall
        .origin
        .iter()
        .map(|o| o.interpolate(source, normal).as_vec3().to_array())
        .collect();
    let mut vertices = Vec::with_capacity(wall.mesh.triangles.len() * 3);
    for (t, corners) in wall.mesh.triangles.iter().zip(&wall.corner_mm) {
        for (&v, &mm) in t.iter().zip(corners) {
            vertices.push(RiskVertex {
                position_in_world: wall.mesh.positions[v as usize].as_vec3().to_array(),
                normal_in_world: normals[v as usize],
                ramp: risk.settings.ramp_position(f64::from(mm)),
            });
        }
    }
    let triangles = (0..wall.mesh.triangles.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    (vertices, triangles)
}

/// Every undirected edge of `mesh` once, as a segment (for wireframe drawing).
pub fn mesh_edges(mesh: &Mesh) -> Vec<Segment> {
    let mut seen = HashSet::with_capacity(mesh.triangles.len() * 3 / 2);
    let mut out = Vec::with_capacity(mesh.triangles.len() * 3 / 2);
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if seen.insert((a.min(b), a.max(b))) {
                out.push(segment(
                    mesh.positions[a as usize],
                    mesh.positions[b as usize],
                ));
            }
        }
    }
    out
}

/// Consecutive point pairs of every polyline, as segments.
pub fn polyline_segments<'a>(lines: impl IntoIterator<Item = &'a [DVec3]>) -> Vec<Segment> {
    let mut out = Vec::new();
    for line in lines {
        for w in line.windows(2) {
            out.push(segment(w[0], w[1]));
        }
    }
    out
}

/// The four outline edges of a bounded cutting plane, plus the edges joining consecutive planes
/// (front-top, back-top, back-bottom, front-bottom rails).
pub fn cutter_outline_segments(planes: &[[glam::DVec3; 4]]) -> Vec<Segment> {
    let mut out = Vec::new();
    for p in planes {
        for k in 0..4 {
            out.push(segment(p[k], p[(k + 1) % 4]));
        }
    }
    for w in planes.windows(2) {
        for k in 0..4 {
            out.push(segment(w[0][k], w[1][k]));
        }
    }
    out
}

fn segment(a: DVec3, b: DVec3) -> Segment {
    Segment {
        a_in_world: a.as_vec3().to_array(),
        b_in_world: b.as_vec3().to_array(),
    }
}

/// A triangle mesh on the GPU.
#[derive(Debug)]
pub struct GpuMesh {
    pub vertex_buffer: wgpu::Buffer,
    pub index_buffer: wgpu::Buffer,
    /// Three per triangle.
    pub index_count: u32,
    /// Wireframe edges, uploaded the first time the mesh is drawn as a wireframe.
    pub edges: Option<GpuSegments>,
}

impl GpuMesh {
    /// Uploads `mesh` (`None` when it has no triangle: wgpu buffers cannot be empty).
    pub fn upload(device: &wgpu::Device, label: &str, mesh: &Mesh) -> Option<GpuMesh> {
        if mesh.triangles.is_empty() {
            return None;
        }
        GpuMesh::upload_vertices(device, label, &mesh_vertices(mesh), &mesh.triangles)
    }

    /// Uploads prepared vertices and triangles (`None` when there is no triangle). The index
    /// buffer is also a storage buffer, so the renderer can hide faces in place (see
    /// `crate::cutting::delta`).
    pub fn upload_vertices<V: bytemuck::Pod>(
        device: &wgpu::Device,
        label: &str,
        vertices: &[V],
        triangles: &[[u32; 3]],
    ) -> Option<GpuMesh> {
        if triangles.is_empty() || vertices.is_empty() {
            return None;
        }
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{label} vertices")),
            contents: bytemuck::cast_slice(vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{label} indices")),
            contents: bytemuck::cast_slice(triangles),
            usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
        });
        Some(GpuMesh {
            vertex_buffer,
            index_buffer,
            index_count: (triangles.len() * 3) as u32,
            edges: None,
        })
    }

    /// Bytes this mesh's buffers hold (what its upload sent), edges left out.
    pub fn byte_size(&self) -> u64 {
        self.vertex_buffer.size() + self.index_buffer.size()
    }

    /// Uploads the wireframe edges of `mesh` (the mesh this was uploaded from) if not done yet.
    pub fn ensure_edges(&mut self, device: &wgpu::Device, label: &str, mesh: &Mesh) {
        if self.edges.is_none() {
            self.edges = GpuSegments::upload(device, &format!("{label} edges"), &mesh_edges(mesh));
        }
    }
}

/// Line segments on the GPU (one instance each).
#[derive(Debug)]
pub struct GpuSegments {
    pub buffer: wgpu::Buffer,
    pub count: u32,
}

impl GpuSegments {
    /// Bytes this upload sent.
    pub fn byte_size(&self) -> u64 {
        self.buffer.size()
    }

    /// `None` when there is no segment.
    pub fn upload(device: &wgpu::Device, label: &str, segments: &[Segment]) -> Option<GpuSegments> {
        if segments.is_empty() {
            return None;
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(segments),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Some(GpuSegments {
            buffer,
            count: segments.len() as u32,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_normals_of_a_tetrahedron_point_outward() {
        let mesh = Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        };
        let centre = DVec3::splat(0.25);
        for (v, p) in mesh_vertices(&mesh).iter().zip(&mesh.positions) {
            let n = DVec3::from(v.normal_in_world.map(f64::from));
            assert!((n.length() - 1.0).abs() < 1e-6);
            assert!(n.dot(*p - centre) > 0.0, "{n} at {p}");
        }
        assert_eq!(mesh_edges(&mesh).len(), 6);
    }

    #[test]
    fn polylines_become_consecutive_segments() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let segs = polyline_segments([&line[..]]);
        assert_eq!(segs.len(), 2);
        assert_eq!(segs[1].a_in_world, [1.0, 0.0, 0.0]);
    }
}
