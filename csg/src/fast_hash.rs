//! Hash maps and sets for small integer keys: vertex, edge and face ids, grid cells.
//!
//! The boolean's intersection stage and the scalpel's live opening look such keys up several
//! times per element they visit. The standard library's default hasher (SipHash, keyed at
//! random against collision attacks) took a large share of that time; these keys are our own
//! ids, not untrusted input, so a multiply-rotate hash (FxHash's) is enough. A caller must not
//! let a map's iteration order decide a result (sort, or only look up); none does.

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// FxHash's multiply-rotate over 64-bit words (see the module doc).
#[derive(Default, Clone, Copy)]
pub struct FastHasher(u64);

impl Hasher for FastHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    #[inline]
    fn write_i64(&mut self, i: i64) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
}

/// A [`HashMap`] with [`FastHasher`].
pub type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// A [`HashSet`] with [`FastHasher`].
pub type FastSet<K> = HashSet<K, BuildHasherDefault<FastHasher>>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_and_ids_next_to_each_other_spread_over_the_table() {
        // Neighbouring cells and consecutive ids must not collide (a constant or identity-like
        // hash would put them in one bucket group and make every lookup a scan).
        let hash = |c: (i64, i64, i64)| {
            let mut h = FastHasher::default();
            std::hash::Hash::hash(&c, &mut h);
            h.finish()
        };
        let mut seen = HashSet::new();
        for x in -5..5 {
            for y in -5..5 {
                for z in -5..5 {
                    assert!(seen.insert(hash((x, y, z))), "({x}, {y}, {z}) collides");
                }
            }
        }
        let top: HashSet<u64> = (0u32..4096)
            .map(|v| {
                let mut h = FastHasher::default();
                h.write_u32(v);
                h.finish() >> 57
            })
            .collect();
        assert!(top.len() > 100, "consecutive ids share their top bits");
    }

    #[test]
    fn a_map_finds_what_it_holds() {
        let mut m: FastMap<u32, u32> = FastMap::default();
        for v in 0..10_000 {
            m.insert(v * 7, v);
        }
        assert!((0..10_000).all(|v| m.get(&(v * 7)) == Some(&v)));
        assert!(!m.contains_key(&1));
    }
}
