//! The cut segments near a point, for the opening ([`super::dffd`]).
//!
//! The opening asks, for every vertex within its support, which cut segments lie within the
//! support radius `r` (the nearest one decides its distance and frame, their ends' path
//! corrections are blended). A uniform grid of cell size `r` answers with the segments of the
//! 27 cells around the point's cell. The breadth-first walk of the opening visits neighbouring
//! vertices one after the other, mostly in the same cell, so the answer for the last cell is
//! kept: a visit usually costs no hashing at all (hashing the 27 cells per vertex was most of
//! the opening's time).

use std::collections::HashMap;

use glam::DVec3;

use super::step::CutSegment;

/// Segments by grid cell (see the module doc).
pub struct CutGrid {
    size: f64,
    cells: HashMap<(i64, i64, i64), Vec<usize>>,
    /// The cell last asked for and the segments around it (each once, in index order).
    last: Option<(i64, i64, i64)>,
    near: Vec<usize>,
}

impl CutGrid {
    /// The segments of `segments` whose both ends are below `vertex_count`, in cells of `size`.
    pub fn new(segments: &[CutSegment], vertex_count: u32, size: f64) -> CutGrid {
        let mut grid = CutGrid {
            size,
            cells: HashMap::new(),
            last: None,
            near: Vec::new(),
        };
        for (i, s) in segments.iter().enumerate() {
            if s.a >= vertex_count || s.b >= vertex_count {
                continue;
            }
            let (lo, hi) = (grid.cell(s.pa.min(s.pb)), grid.cell(s.pa.max(s.pb)));
            for x in lo.0..=hi.0 {
                for y in lo.1..=hi.1 {
                    for z in lo.2..=hi.2 {
                        grid.cells.entry((x, y, z)).or_default().push(i);
                    }
                }
            }
        }
        grid
    }

    fn cell(&self, p: DVec3) -> (i64, i64, i64) {
        let c = (p / self.size).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    }

    /// The segments in the 27 cells around `p`'s (every segment within `size` of `p` among
    /// them), each once, in index order.
    pub fn near(&mut self, p: DVec3) -> &[usize] {
        let c0 = self.cell(p);
        if self.last != Some(c0) {
            self.near.clear();
            for x in c0.0 - 1..=c0.0 + 1 {
                for y in c0.1 - 1..=c0.1 + 1 {
                    for z in c0.2 - 1..=c0.2 + 1 {
                        if let Some(list) = self.cells.get(&(x, y, z)) {
                            self.near.extend_from_slice(list);
                        }
                    }
                }
            }
            self.near.sort_unstable();
            self.near.dedup();
            self.last = Some(c0);
        }
        &self.near
    }
}
