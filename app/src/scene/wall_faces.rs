//! Which faces of a model's mesh are incision walls (the scalpel's groove and through-cut walls,
//! below the surface), so that every view draws them as the inside of the tissue: their own
//! colour and a hard edge at the lips (`crate::cutting::wall_split`).
//!
//! The marks belong to one mesh: a [`WallFaces`] remembers the mesh it was made for (a weak
//! pointer, compared by identity), and a model whose mesh is replaced without new marks simply
//! has none ([`WallFaces::for_mesh`] answers an empty list). So no code that swaps a model's mesh
//! can draw another mesh's faces as walls by forgetting to clear them.

use std::sync::{Arc, Weak};

use csg::Mesh;

/// The wall faces of one mesh, ascending and unique, every id a face of that mesh.
#[derive(Debug, Default)]
pub struct WallFaces {
    mesh: Weak<Mesh>,
    faces: Arc<[u32]>,
}

impl WallFaces {
    /// The marks of `mesh` (`faces` in any order; duplicates and ids past its faces dropped);
    /// `None` when no face is a wall.
    pub fn new(mesh: &Arc<Mesh>, mut faces: Vec<u32>) -> Option<Arc<WallFaces>> {
        let n = mesh.triangles.len();
        faces.retain(|&f| (f as usize) < n);
        faces.sort_unstable();
        faces.dedup();
        (!faces.is_empty()).then(|| {
            Arc::new(WallFaces {
                mesh: Arc::downgrade(mesh),
                faces: faces.into(),
            })
        })
    }

    /// The wall faces when these marks were made for `mesh` (the same allocation), else none.
    pub fn for_mesh<'a>(walls: &'a Option<Arc<WallFaces>>, mesh: &Arc<Mesh>) -> &'a [u32] {
        match walls {
            Some(w) if std::ptr::eq(w.mesh.as_ptr(), Arc::as_ptr(mesh)) => &w.faces,
            _ => &[],
        }
    }

    /// [`WallFaces::for_mesh`] as a shared list (the same allocation every call, so a renderer
    /// can tell the marks it uploaded by identity); `None` for no wall.
    pub fn shared_for_mesh(walls: &Option<Arc<WallFaces>>, mesh: &Arc<Mesh>) -> Option<Arc<[u32]>> {
        match walls {
            Some(w) if std::ptr::eq(w.mesh.as_ptr(), Arc::as_ptr(mesh)) => Some(w.faces.clone()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_are_sorted_bounded_and_only_for_their_mesh() {
        let mesh = Arc::new(csg::testkit::icosphere(1, 1.0));
        let n = mesh.triangles.len() as u32;
        let walls = WallFaces::new(&mesh, vec![7, 3, 7, n, 0]);
        assert_eq!(WallFaces::for_mesh(&walls, &mesh), &[0, 3, 7]);
        let same_shape = Arc::new((*mesh).clone());
        assert!(WallFaces::for_mesh(&walls, &same_shape).is_empty());
        assert!(WallFaces::new(&mesh, vec![n]).is_none());
        assert!(WallFaces::for_mesh(&None, &mesh).is_empty());
    }
}
