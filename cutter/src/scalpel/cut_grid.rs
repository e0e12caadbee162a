//! The cut segments near a point, for the opening ([`super::dffd`]).
//!
//! The opening asks, for every vertex within its support, which cut segments lie within the
//! support radius `r` (the nearest one decides its distance and frame, their ends' path
//! corrections are blended). A uniform grid of cell size `r` answers with the segments of the
//! 27 cells around the point's cell. The breadth-first walk of the opening visits neighbouring
//! vertices one after the other, mostly in the same cell, so the answer for the last cell is
//! kept: a visit usually costs no hashing at all (hashing the 27 cells per vertex was most of
//! the opening's time).
//!
//! The live opening ([`super::live_opening`]) keeps one grid between steps and moves only the
//! segments a step changed ([`CutGrid::insert`], [`CutGrid::remove`]).

use std::collections::{HashMap, HashSet};

use glam::DVec3;

use super::step::CutSegment;

/// A grid cell: the point's coordinates divided by the cell size, rounded down.
pub type Cell = (i64, i64, i64);

/// The cell of size `size` that holds `p`.
pub fn cell_of(p: DVec3, size: f64) -> Cell {
    let c = (p / size).floor();
    (c.x as i64, c.y as i64, c.z as i64)
}

/// Segments by grid cell (see the module doc).
pub struct CutGrid {
    size: f64,
    cells: HashMap<Cell, Vec<usize>>,
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
            grid.insert(i, s, vertex_count);
        }
        grid
    }

    /// The cell size.
    pub fn size(&self) -> f64 {
        self.size
    }

    fn cell(&self, p: DVec3) -> Cell {
        cell_of(p, self.size)
    }

    /// The cells segment `s` is listed in (its bounding box's).
    fn cells_of(&self, s: &CutSegment) -> impl Iterator<Item = Cell> + use<> {
        let (lo, hi) = (self.cell(s.pa.min(s.pb)), self.cell(s.pa.max(s.pb)));
        (lo.0..=hi.0).flat_map(move |x| {
            (lo.1..=hi.1).flat_map(move |y| (lo.2..=hi.2).map(move |z| (x, y, z)))
        })
    }

    /// Lists segment `i`, `s`, when both its ends are below `vertex_count`.
    pub fn insert(&mut self, i: usize, s: &CutSegment, vertex_count: u32) {
        if s.a >= vertex_count || s.b >= vertex_count {
            return;
        }
        for c in self.cells_of(s) {
            self.cells.entry(c).or_default().push(i);
        }
        self.last = None;
    }

    /// Unlists segment `i`, which was `s` when listed.
    pub fn remove(&mut self, i: usize, s: &CutSegment) {
        for c in self.cells_of(s) {
            if let Some(list) = self.cells.get_mut(&c) {
                list.retain(|&j| j != i);
                if list.is_empty() {
                    self.cells.remove(&c);
                }
            }
        }
        self.last = None;
    }

    /// The segments listed in `cells`, each once, in index order.
    pub fn segments_in(&self, cells: &HashSet<Cell>) -> Vec<usize> {
        let mut out: Vec<usize> = cells
            .iter()
            .filter_map(|c| self.cells.get(c))
            .flatten()
            .copied()
            .collect();
        out.sort_unstable();
        out.dedup();
        out
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
