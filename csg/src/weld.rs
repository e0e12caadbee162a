//! Welding of bit-identical positions (STL stores every triangle's corners separately).
//!
//! OWNER: core helper (foundation issue). Signatures are fixed; bodies to be written.

use glam::DVec3;

use crate::mesh::Mesh;

/// Merges vertices whose positions are exactly equal (`0.0` and `-0.0` are the same point), keeping
/// the first occurrence's index order. Never moves a vertex.
pub fn weld_exact(mesh: &Mesh) -> Mesh {
    let _ = mesh;
    unimplemented!("core helper")
}

/// Welds a triangle soup: `corners.len()` must be a multiple of 3, each triple one triangle.
pub fn weld_soup(corners: &[DVec3]) -> Mesh {
    let _ = corners;
    unimplemented!("core helper")
}
