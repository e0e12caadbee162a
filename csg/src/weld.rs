//! Welding of bit-identical positions (STL stores every triangle's corners separately).
//!
//! Only exactly equal coordinates are merged: Cutaway never moves a vertex, so welding with a
//! tolerance (which would change geometry and can fold thin structures together) is out. `0.0`
//! and `-0.0` compare equal and are merged; the first occurrence's bits are kept.
//!
//! Welding is a hash lookup per corner keyed on the coordinates' bit patterns; the hash is a
//! multiply–xor mix computed once per key, fed to the standard table through a pass-through
//! hasher (SipHash would triple the cost on 3M corners).
//!
//! Welding never drops a triangle: two distinct vertices at one position become one index, so a
//! triangle that had them both becomes a repeated-index (degenerate) triangle that
//! [`crate::MeshReport`] counts.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

use glam::DVec3;

use crate::mesh::Mesh;

/// Merges vertices whose positions are exactly equal (`0.0` and `-0.0` are the same point), keeping
/// the first occurrence's index order. Never moves a vertex.
///
/// Vertices no triangle uses are kept (merged like the others); see [`Mesh::compacted`] to drop them.
pub fn weld_exact(mesh: &Mesh) -> Mesh {
    let mut welder = Welder::with_capacity(mesh.positions.len());
    let remap: Vec<u32> = mesh.positions.iter().map(|&p| welder.index_of(p)).collect();
    let triangles = mesh
        .triangles
        .iter()
        .map(|tri| tri.map(|i| remap[i as usize]))
        .collect();
    Mesh {
        positions: welder.positions,
        triangles,
    }
}

/// Welds a triangle soup: `corners.len()` must be a multiple of 3, each triple one triangle.
///
/// Vertices are numbered in order of first occurrence. Trailing corners that do not make a whole
/// triangle are ignored (loaders report such a truncated file before they get here).
pub fn weld_soup(corners: &[DVec3]) -> Mesh {
    // A closed soup has about one distinct position per six corners.
    let mut welder = Welder::with_capacity(corners.len() / 5);
    let triangles = corners
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]].map(|p| welder.index_of(p)))
        .collect();
    Mesh {
        positions: welder.positions,
        triangles,
    }
}

/// The bit patterns of a position with `-0.0` turned into `0.0`, and a mixed hash of them.
#[derive(Clone, Copy, PartialEq, Eq)]
struct PositionKey {
    bits: [u64; 3],
    hash: u64,
}

impl PositionKey {
    fn new(p: DVec3) -> PositionKey {
        // `x + 0.0` maps -0.0 to +0.0 and leaves every other value's bits alone.
        let bits = [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
        let mut h = bits[0].wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h = (h ^ bits[1]).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
        h = (h ^ bits[2]).wrapping_mul(0x1656_67B1_9E37_79F9);
        // Final avalanche (murmur3 fmix64): the table uses both high and low bits.
        h ^= h >> 33;
        h = h.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
        h ^= h >> 33;
        PositionKey { bits, hash: h }
    }
}

impl Hash for PositionKey {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.hash);
    }
}

/// Passes the precomputed [`PositionKey::hash`] through unchanged.
#[derive(Default)]
struct PassThroughHasher(u64);

impl Hasher for PassThroughHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        // Not used by `PositionKey`; fold bytes in anyway so the hasher stays correct.
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = v;
    }
}

/// Assigns indices to distinct positions in order of first occurrence.
struct Welder {
    /// Distinct positions, first occurrence's bits.
    positions: Vec<DVec3>,
    /// Position key → index into `positions`.
    index: HashMap<PositionKey, u32, BuildHasherDefault<PassThroughHasher>>,
}

impl Welder {
    fn with_capacity(n: usize) -> Welder {
        Welder {
            positions: Vec::with_capacity(n),
            index: HashMap::with_capacity_and_hasher(n, Default::default()),
        }
    }

    fn index_of(&mut self, p: DVec3) -> u32 {
        let next = self.positions.len() as u32;
        let i = *self.index.entry(PositionKey::new(p)).or_insert(next);
        if i == next {
            self.positions.push(p);
        }
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    #[test]
    fn soup_of_icosphere_welds_back_to_it() {
        let m = testkit::icosphere(3, 1.0);
        let welded = weld_soup(&testkit::to_soup(&m));
        welded.sanity_check().unwrap();
        assert_eq!(welded.vertex_count(), m.vertex_count());
        assert_eq!(welded.triangle_count(), m.triangle_count());
        // Same triangles up to a vertex renumbering.
        for (a, b) in m.triangles.iter().zip(&welded.triangles) {
            assert_eq!(
                a.map(|i| m.positions[i as usize]),
                b.map(|i| welded.positions[i as usize])
            );
        }
        // Welded soup corners are numbered in first-occurrence order.
        let mut seen = 0;
        for &i in welded.triangles.iter().flatten() {
            assert!(i <= seen);
            if i == seen {
                seen += 1;
            }
        }
    }

    #[test]
    fn signed_zero_merges_and_nothing_moves() {
        let a = DVec3::new(0.0, 1.0, -0.0);
        let b = DVec3::new(-0.0, 1.0, 0.0);
        let c = DVec3::new(1.0, 0.0, 0.0);
        let near = DVec3::new(1.0 + f64::EPSILON, 0.0, 0.0);
        let m = weld_soup(&[a, c, near, b, near, c]);
        m.sanity_check().unwrap();
        assert_eq!(m.positions.len(), 3);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 1]]);
        // The first occurrence's bits are kept: the -0.0 in z stays.
        assert_eq!(m.positions[0].z.to_bits(), (-0.0f64).to_bits());
        assert_eq!(m.positions[2], near);
    }

    #[test]
    fn weld_exact_keeps_first_occurrence_order_and_degenerates() {
        let p = |x: f64| DVec3::new(x, 0.0, 0.0);
        let m = Mesh::new(
            vec![p(3.0), p(1.0), p(3.0), p(2.0)],
            vec![[0, 1, 2], [2, 3, 1]],
        )
        .unwrap();
        let w = weld_exact(&m);
        w.sanity_check().unwrap();
        assert_eq!(w.positions, vec![p(3.0), p(1.0), p(2.0)]);
        assert_eq!(w.triangles, vec![[0, 1, 0], [0, 2, 1]]);
        assert_eq!(weld_soup(&[p(1.0), p(2.0)]), Mesh::default());
    }
}
