//! Welding of bit-identical positions (STL stores every triangle's corners separately).
//!
//! Only exactly equal coordinates are merged: Cutaway never moves a vertex, so welding with a
//! tolerance (which would change geometry and can fold thin structures together) is out. `0.0`
//! and `-0.0` compare equal and are merged; the first occurrence's bits are kept.
//!
//! Welding is a hash lookup per corner keyed on the coordinates' bit patterns (a multiply–xor
//! mix), in a compact open-addressing table of packed `u64` slots. A small direct-mapped cache of
//! recently seen positions sits in front of it: in a soup most corners repeat a vertex of a nearby
//! triangle, and the cache answers those without touching the big table. A 1M-triangle soup (3M
//! corners) welds in well under 0.3 s (see `benches/index.rs`).
//!
//! Welding never drops a triangle: two distinct vertices at one position become one index, so a
//! triangle that had them both becomes a repeated-index (degenerate) triangle that
//! [`crate::MeshReport`] counts.

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
#[derive(Clone, Copy)]
struct PositionKey {
    bits: [u64; 3],
    hash: u64,
}

impl PositionKey {
    /// The coordinates' bits with `-0.0` turned into `0.0`.
    fn bits(p: DVec3) -> [u64; 3] {
        // `x + 0.0` maps -0.0 to +0.0 and leaves every other value's bits alone.
        [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
    }

    fn new(p: DVec3) -> PositionKey {
        let bits = PositionKey::bits(p);
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

/// Slots of [`Welder::recent`]; a power of two. 4096 slots (32 KiB) stay in L1/L2 and catch
/// almost every repeat in a soup (measured: 2.38M of the 2.51M repeats in a 1M-triangle sphere
/// soup), where a vertex comes back within a few hundred triangles.
const RECENT_SLOTS: usize = 4096;

/// Assigns indices to distinct positions in order of first occurrence.
///
/// The table is open addressing with linear probing over packed `u64` slots (`tag << 32 |
/// index + 1`, 0 = empty), at most half full: a new position usually costs one cache miss, where a
/// general-purpose map with 40-byte entries costs two or three on a million-vertex table.
struct Welder {
    /// Distinct positions, first occurrence's bits. At most `u32::MAX - 1` of them.
    positions: Vec<DVec3>,
    /// Hash table: slot `k` is 0 (empty) or `(hash >> 32) << 32 | (index + 1)` for the position
    /// `positions[index]` whose probe sequence starts at `hash & (slots.len() - 1)`. Length is a
    /// power of two, more than twice `positions.len()`.
    slots: Vec<u64>,
    /// Direct-mapped cache in front of `slots`: entry `hash % RECENT_SLOTS` holds the index of the
    /// last position seen there, or `u32::MAX`. A hit is confirmed by comparing bits, so the cache
    /// never changes an answer; it only skips the big table's cache misses.
    recent: Vec<u32>,
}

impl Welder {
    /// A welder expecting about `n` distinct positions (it grows past that).
    fn with_capacity(n: usize) -> Welder {
        Welder {
            positions: Vec::with_capacity(n),
            slots: vec![0; (2 * n + 2).next_power_of_two().max(16)],
            recent: vec![u32::MAX; RECENT_SLOTS],
        }
    }

    fn index_of(&mut self, p: DVec3) -> u32 {
        let key = PositionKey::new(p);
        let cache_slot = key.hash as usize & (RECENT_SLOTS - 1);
        let cached = self.recent[cache_slot];
        if let Some(&q) = self.positions.get(cached as usize)
            && PositionKey::bits(q) == key.bits
        {
            return cached;
        }
        let tag = key.hash >> 32;
        let mask = self.slots.len() - 1;
        let mut k = key.hash as usize & mask;
        let index = loop {
            let slot = self.slots[k];
            if slot == 0 {
                let index = self.positions.len() as u32;
                self.slots[k] = (tag << 32) | u64::from(index + 1);
                self.positions.push(p);
                if 2 * self.positions.len() >= self.slots.len() {
                    self.grow();
                }
                break index;
            }
            if slot >> 32 == tag {
                let index = (slot as u32) - 1;
                if PositionKey::bits(self.positions[index as usize]) == key.bits {
                    break index;
                }
            }
            k = (k + 1) & mask;
        };
        self.recent[cache_slot] = index;
        index
    }

    /// Doubles the table and reinserts every position.
    fn grow(&mut self) {
        let mut slots = vec![0u64; 2 * self.slots.len()];
        let mask = slots.len() - 1;
        for (index, &p) in self.positions.iter().enumerate() {
            let hash = PositionKey::new(p).hash;
            let mut k = hash as usize & mask;
            while slots[k] != 0 {
                k = (k + 1) & mask;
            }
            slots[k] = ((hash >> 32) << 32) | (index as u64 + 1);
        }
        self.slots = slots;
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
