//! The indexed triangle mesh every part of Cutaway shares.
//!
//! Positions are `f64` so that `f32` file data enters exactly and every vertex the cut did not
//! create keeps its input coordinates bit for bit. Triangles are counter-clockwise seen from
//! outside (outward normals by the right-hand rule) for closed, oriented meshes.

use glam::DVec3;

use crate::aabb::Aabb;

/// Structural problems that make a mesh unusable (as opposed to topological facts such as "open",
/// which [`crate::MeshReport`] describes and which Cutaway accepts).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A triangle names a vertex that does not exist. Fix the file's face indices.
    #[error(
        "triangle {triangle} uses vertex {index}, but the mesh has only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        triangle: usize,
        index: u32,
        vertex_count: usize,
    },
    /// A coordinate is NaN or infinite. Fix the file's vertex data.
    #[error("vertex {vertex} has a non-finite coordinate {position:?}")]
    NonFinite { vertex: usize, position: [f64; 3] },
    /// More vertices than a `u32` index can name.
    #[error("{count} vertices is more than a u32 index can address")]
    TooManyVertices { count: usize },
}

/// An indexed triangle mesh in `f64`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, all finite. Must have at most `u32::MAX` entries.
    pub positions: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    /// Every index must be `< positions.len()`.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Builds a mesh after checking its structure ([`Mesh::sanity_check`]).
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Mesh, MeshError> {
        let mesh = Mesh {
            positions,
            triangles,
        };
        mesh.sanity_check()?;
        Ok(mesh)
    }

    /// Checks the structural invariants written on the fields: finite positions, indices in
    /// range, vertex count addressable by `u32`. Call it where data enters and after mutations in
    /// tests. Topology (closed, manifold, oriented) is reported by [`Mesh::report`] instead.
    pub fn sanity_check(&self) -> Result<(), MeshError> {
        let Mesh {
            positions,
            triangles,
        } = self;
        if positions.len() > u32::MAX as usize {
            return Err(MeshError::TooManyVertices {
                count: positions.len(),
            });
        }
        if let Some((vertex, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                position: p.to_array(),
            });
        }
        let n = positions.len();
        for (triangle, tri) in triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count: n,
                });
            }
        }
        Ok(())
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when the mesh has no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The three corner positions of triangle `t`.
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Unnormalized normal of triangle `t` (twice its area in length).
    pub fn face_normal_scaled(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.corners(t);
        (b - a).cross(c - a)
    }

    /// Bounding box of the vertices that triangles use (all vertices if there are no triangles).
    pub fn bbox(&self) -> Aabb {
        if self.triangles.is_empty() {
            return Aabb::from_points(&self.positions);
        }
        let mut b = Aabb::EMPTY;
        for tri in &self.triangles {
            for &i in tri {
                b.grow(self.positions[i as usize]);
            }
        }
        b
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| self.face_normal_scaled(t).length() * 0.5)
            .sum()
    }

    /// Signed enclosed volume (positive for a closed mesh with outward normals). Meaningful only
    /// for closed meshes. Computed relative to the bounding-box centre to limit cancellation.
    pub fn volume(&self) -> f64 {
        let origin = self.bbox().center();
        if !origin.is_finite() {
            return 0.0;
        }
        let mut sum = 0.0;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.corners(t);
            sum += (a - origin).dot((b - origin).cross(c - origin));
        }
        sum / 6.0
    }

    /// Appends `other`, offsetting its indices. Returns the index of its first triangle.
    pub fn append(&mut self, other: &Mesh) -> usize {
        let base = self.positions.len() as u32;
        let first = self.triangles.len();
        self.positions.extend_from_slice(&other.positions);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
        first
    }

    /// The same surface with every triangle's orientation reversed.
    pub fn reversed(&self) -> Mesh {
        Mesh {
            positions: self.positions.clone(),
            triangles: self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        }
    }

    /// Drops vertices no triangle uses, keeping the order of the rest.
    pub fn compacted(&self) -> Mesh {
        let mut remap = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let triangles = self
            .triangles
            .iter()
            .map(|tri| {
                tri.map(|i| {
                    let r = &mut remap[i as usize];
                    if *r == u32::MAX {
                        *r = positions.len() as u32;
                        positions.push(self.positions[i as usize]);
                    }
                    *r
                })
            })
            .collect();
        Mesh {
            positions,
            triangles,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube with outward-facing triangles.
    pub(crate) fn unit_cube() -> Mesh {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let positions = vec![
            p(0., 0., 0.),
            p(1., 0., 0.),
            p(1., 1., 0.),
            p(0., 1., 0.),
            p(0., 0., 1.),
            p(1., 0., 1.),
            p(1., 1., 1.),
            p(0., 1., 1.),
        ];
        let quads = [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 0, 4, 7],
        ];
        let mut triangles = Vec::new();
        for [a, b, c, d] in quads {
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn cube_measures() {
        let cube = unit_cube();
        assert_eq!(cube.volume(), 1.0);
        assert_eq!(cube.area(), 6.0);
        assert_eq!(cube.bbox().size(), DVec3::ONE);
        assert_eq!(cube.reversed().volume(), -1.0);
    }

    #[test]
    fn sanity_check_rejects_bad_index_and_nan() {
        let mut cube = unit_cube();
        cube.triangles[3][1] = 99;
        assert!(matches!(
            cube.sanity_check(),
            Err(MeshError::IndexOutOfRange { index: 99, .. })
        ));
        let mut cube = unit_cube();
        cube.positions[2].y = f64::NAN;
        assert!(matches!(
            cube.sanity_check(),
            Err(MeshError::NonFinite { vertex: 2, .. })
        ));
    }

    #[test]
    fn compacted_drops_unused_vertices() {
        let mut cube = unit_cube();
        cube.positions.push(DVec3::splat(5.0));
        let c = cube.compacted();
        assert_eq!(c.positions.len(), 8);
        assert_eq!(c.volume(), 1.0);
    }
}
