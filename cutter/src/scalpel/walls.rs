//! Which triangles of a scalpel-cut mesh are walls (groove or through-cut walls, below the
//! surface), as a list a viewer or a file can carry.
//!
//! A viewer draws the walls as the inside of the tissue (their own colour, a hard edge at the
//! lips) and a saved mesh keeps the marking, so these are read from [`DynMesh::is_wall`] in one
//! pass. A mesh read back from such a file gets its walls marked again with
//! [`Scalpel::mark_walls`], so later strokes treat them as walls (the surface walk never crosses
//! them) and the viewer keeps drawing them.

use super::{DynMesh, Scalpel};

impl DynMesh {
    /// The wall triangles, ascending (ids of [`DynMesh::to_mesh`]'s triangles).
    pub fn wall_faces(&self) -> Vec<u32> {
        (0..self.triangle_count() as u32)
            .filter(|&t| self.is_wall(t))
            .collect()
    }
}

impl Scalpel {
    /// The wall triangles of the scalpel's mesh, ascending (see [`DynMesh::wall_faces`]).
    pub fn wall_faces(&self) -> Vec<u32> {
        self.mesh.wall_faces()
    }

    /// Marks triangles of the mesh the scalpel was made from as walls (ids of that mesh's
    /// triangles; others ignored), as a mesh saved with its walls comes back. Call it before the
    /// first stroke: it is not part of any stroke's undo.
    pub fn mark_walls(&mut self, faces: &[u32]) {
        for &t in faces {
            if let Some(w) = self.mesh.wall_tri.get_mut(t as usize) {
                *w = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ScalpelOptions;
    use super::*;
    use glam::DVec3;

    /// A groove's walls are exactly the triangles with a floor vertex, and marking them on a
    /// fresh scalpel of the cut mesh gives the same list.
    #[test]
    fn groove_walls_are_the_triangles_with_a_floor_vertex_and_survive_a_new_scalpel() {
        let mesh = csg::testkit::icosphere(4, 10.0);
        let mut scalpel = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(1.0)).unwrap();
        let samples: Vec<DVec3> = (0..=12)
            .map(|i| {
                let a = -0.5 + i as f64 / 12.0;
                DVec3::new(10.0 * a.sin(), -10.0 * a.cos() * 0.3, 10.0 * 0.95).normalize() * 10.0
            })
            .collect();
        scalpel.cut_stroke(&samples).unwrap();
        let walls = scalpel.wall_faces();
        assert!(walls.len() >= 8, "{} walls", walls.len());
        let m = scalpel.dyn_mesh();
        for t in 0..m.triangle_count() as u32 {
            let floor = m.triangles()[t as usize].iter().any(|&v| m.is_floor(v));
            assert_eq!(floor, walls.binary_search(&t).is_ok(), "triangle {t}");
        }
        let mut again = Scalpel::new(&scalpel.mesh(), ScalpelOptions::default()).unwrap();
        assert!(again.wall_faces().is_empty());
        again.mark_walls(&walls);
        again.mark_walls(&[u32::MAX]);
        assert_eq!(again.wall_faces(), walls);
    }
}
