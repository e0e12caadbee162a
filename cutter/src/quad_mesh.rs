//! The cutter's polygon mesh: closed, outward quads (and the wedge's triangles) before the boolean
//! sees triangles. Its own file because both the boxes ([`crate::cutter`]) and the subdivided
//! surface ([`crate::subdivision`]) are made of it, and neither should depend on the other for it.

use glam::DVec3;

use crate::geom;

/// A closed polygon mesh (quads, and triangles in a wedge), outward oriented.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct QuadMesh {
    pub positions: Vec<DVec3>,
    /// Faces as vertex indices, counter-clockwise seen from outside. 3 or 4 indices each, every
    /// index `< positions.len()`.
    pub faces: Vec<Vec<u32>>,
}

impl QuadMesh {
    /// Fan-triangulates every face into a [`csg::Mesh`].
    pub fn triangulate(&self) -> csg::Mesh {
        let mut triangles = Vec::with_capacity(self.faces.len() * 2);
        for f in &self.faces {
            for k in 1..f.len().saturating_sub(1) {
                triangles.push([f[0], f[k], f[k + 1]]);
            }
        }
        csg::Mesh {
            positions: self.positions.clone(),
            triangles,
        }
    }

    /// Signed enclosed volume (positive when outward oriented).
    pub fn volume(&self) -> f64 {
        geom::signed_volume(&self.positions, &self.faces)
    }

    /// Checks that every edge is used exactly once in each direction (closed and consistently
    /// oriented). Returns the first bad edge.
    pub fn check_closed(&self) -> Result<(), (u32, u32)> {
        let mut edges = std::collections::HashMap::<(u32, u32), i32>::new();
        for f in &self.faces {
            for k in 0..f.len() {
                let a = f[k];
                let b = f[(k + 1) % f.len()];
                if a == b {
                    return Err((a, b));
                }
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            if n != 1 || edges.get(&(b, a)) != Some(&1) {
                return Err((a, b));
            }
        }
        Ok(())
    }
}
