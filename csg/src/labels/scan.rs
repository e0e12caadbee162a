//! One pass over a label grid: each label's voxel count and bounding box.
//!
//! The box lets each label be extracted from its own small region instead of the whole grid.
//! Values below 65536 (every `u8`/`u16` grid and most `u32` ones) are tallied in a dense table;
//! larger `u32` values in a map. Slabs of z run in parallel and are merged.

use std::collections::HashMap;

use rayon::prelude::*;

use super::{LabelGrid, LabelValue};

/// Voxel count and inclusive voxel bounding box of one label value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LabelStats {
    pub value: u32,
    /// Number of voxels holding `value` (at least 1).
    pub voxels: u64,
    /// Smallest voxel index holding `value`, per axis.
    pub min: [usize; 3],
    /// Largest voxel index holding `value`, per axis (`>= min`).
    pub max: [usize; 3],
}

impl LabelStats {
    fn first(value: u32, at: [usize; 3], voxels: u64) -> LabelStats {
        LabelStats {
            value,
            voxels,
            min: at,
            max: at,
        }
    }

    fn merge(&mut self, o: &LabelStats) {
        self.voxels += o.voxels;
        for a in 0..3 {
            self.min[a] = self.min[a].min(o.min[a]);
            self.max[a] = self.max[a].max(o.max[a]);
        }
    }

    /// Voxels in the bounding box.
    pub fn box_voxels(&self) -> u64 {
        (0..3)
            .map(|a| (self.max[a] - self.min[a] + 1) as u64)
            .product()
    }
}

/// Below this a value is tallied in the dense table.
const DENSE: usize = 1 << 16;

/// Per-value tallies of one slab: values below [`DENSE`] find their entry through a table of
/// indices (4 bytes per value, so each slab's table is small to create and merge), larger ones
/// through a map.
struct Tally {
    index: Vec<u32>,
    stats: Vec<LabelStats>,
    sparse: HashMap<u32, LabelStats>,
}

/// No entry for this value yet.
const ABSENT: u32 = u32::MAX;

impl Tally {
    fn new() -> Tally {
        Tally {
            index: vec![ABSENT; DENSE],
            stats: Vec::new(),
            sparse: HashMap::new(),
        }
    }

    fn add(&mut self, s: LabelStats) {
        if (s.value as usize) < DENSE {
            let slot = &mut self.index[s.value as usize];
            if *slot == ABSENT {
                *slot = self.stats.len() as u32;
                self.stats.push(s);
            } else {
                self.stats[*slot as usize].merge(&s);
            }
        } else {
            self.sparse
                .entry(s.value)
                .and_modify(|t| t.merge(&s))
                .or_insert(s);
        }
    }

    fn merge(mut self, other: Tally) -> Tally {
        for s in other.stats {
            self.add(s);
        }
        for (_, s) in other.sparse {
            self.add(s);
        }
        self
    }
}

/// Voxels compared at once while following a run.
const RUN_BLOCK: usize = 16;

/// Count and bounding box of every non-zero label present, ascending by value.
pub fn label_stats<T: LabelValue>(grid: &LabelGrid<T>) -> Vec<LabelStats> {
    let [nx, ny, nz] = grid.dims;
    if nx == 0 || ny == 0 || nz == 0 {
        return Vec::new();
    }
    let tally = (0..nz)
        .into_par_iter()
        .with_min_len(16)
        .fold(Tally::new, |mut tally, k| {
            for j in 0..ny {
                let row = &grid.data[nx * (j + ny * k)..][..nx];
                // Runs of one value are tallied at once (label rows are long runs).
                let mut i = 0;
                while i < nx {
                    let v = row[i];
                    let start = i;
                    // Whole blocks first (compared without branches, so vectorised), then
                    // one voxel at a time.
                    while i + RUN_BLOCK <= nx
                        && row[i..i + RUN_BLOCK]
                            .iter()
                            .fold(true, |same, &x| same & (x == v))
                    {
                        i += RUN_BLOCK;
                    }
                    while i < nx && row[i] == v {
                        i += 1;
                    }
                    let value = v.to_u32();
                    if value != 0 {
                        let mut s = LabelStats::first(value, [start, j, k], (i - start) as u64);
                        s.max[0] = i - 1;
                        tally.add(s);
                    }
                }
            }
            tally
        })
        .reduce(Tally::new, Tally::merge);
    let mut out: Vec<LabelStats> = tally.stats;
    out.extend(tally.sparse.into_values());
    out.sort_by_key(|s| s.value);
    out
}
