//! The cut segments near a point, for the opening ([`super::dffd`]).
//!
//! The opening asks, for every vertex within its support, which cut segments lie within the
//! support radius `r` (the nearest one decides its distance and frame, their ends' path
//! corrections are blended). A uniform grid of cell size `r` answers with the segments of the
//! 27 cells around the point's cell. The breadth-first walk of the opening visits neighbouring
//! vertices one after the other, mostly in the same cell, so the answer for the last cell is
//! kept: a visit usually costs no hashing at all (hashing the 27 cells per vertex was most of
//! the opening's time). Its queue also goes from one lip's vertices to another's (on a crossing
//! of two grooves, from one groove to the other), so the answer for every cell asked about is
//! kept too. The answers are kept by whoever asks ([`Near`]), not by the grid: a walk and the
//! thread that blends its path corrections beside it ([`super::blend`]) each keep their own,
//! for the grid as it is during the walk.
//!
//! The live opening ([`super::live_opening`]) keeps one grid between steps and moves only the
//! segments a step changed ([`CutGrid::insert`], [`CutGrid::remove`]).

use glam::DVec3;

use super::nearest_cut::{BLOCK, Ball, Balls};
use super::step::CutSegment;
use csg::fast_hash::{FastMap, FastSet};

/// A grid cell: the point's coordinates divided by the cell size, rounded down.
pub type Cell = (i64, i64, i64);

/// The cell of size `size` that holds `p`.
#[inline]
pub fn cell_of(p: DVec3, size: f64) -> Cell {
    let c = p / size;
    (floor_i64(c.x), floor_i64(c.y), floor_i64(c.z))
}

/// `x.floor() as i64`, without the library's `floor`: on the baseline x86-64 target (no
/// SSE4.1 rounding instruction) it is a software routine, and the opening's walks find the
/// cell of every vertex they visit and of each of its neighbours (a tenth of a step on a
/// crossing of two grooves).
#[inline]
fn floor_i64(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// Adds to `cells` every cell of size `size` that holds a point within `radius` of `p`: the
/// cells whose box comes that near (a ball, not the cube of cells around `p`'s: around a crack
/// tip the cube held three times the cells, and the live opening recomputed all their vertices).
/// Measured in cell units as [`cell_of`] divides, with a little slack, so that no cell holding
/// such a point is missed to rounding.
pub fn cells_within(cells: &mut FastSet<Cell>, p: DVec3, radius: f64, size: f64) {
    let q = p / size;
    let reach = radius / size * (1.0 + 1e-9) + 1e-9;
    let (lo, hi) = (cell_of(q - reach, 1.0), cell_of(q + reach, 1.0));
    for x in lo.0..=hi.0 {
        for y in lo.1..=hi.1 {
            for z in lo.2..=hi.2 {
                let corner = DVec3::new(x as f64, y as f64, z as f64);
                let gap = (corner - q).max(q - (corner + 1.0)).max(DVec3::ZERO);
                if gap.length_squared() <= reach * reach {
                    cells.insert((x, y, z));
                }
            }
        }
    }
}

/// Answers [`InCells`] remembers, at most (a power of two).
const REMEMBERED: usize = 64;

/// Whether points lie in a set of cells (every point when there is no set), remembering the
/// answers for the last cells asked about (a small table indexed by the cell): the opening's
/// walks ask about every vertex they visit and its neighbours, and hashing a cell for each was
/// a good part of a walk. The walk's queue goes from one lip's vertices to another's, so one
/// remembered answer was not enough.
pub struct InCells<'a> {
    cells: Option<&'a FastSet<Cell>>,
    size: f64,
    remembered: Box<[Option<(Cell, bool)>; REMEMBERED]>,
}

impl<'a> InCells<'a> {
    pub fn new(cells: Option<&'a FastSet<Cell>>, size: f64) -> InCells<'a> {
        InCells {
            cells,
            size,
            remembered: Box::new([None; REMEMBERED]),
        }
    }

    /// Whether `p`'s cell is one of the cells.
    #[inline]
    pub fn contains(&mut self, p: DVec3) -> bool {
        self.cells.is_none() || self.contains_cell(cell_of(p, self.size))
    }

    /// Whether cell `c` is one of the cells.
    #[inline]
    pub fn contains_cell(&mut self, c: Cell) -> bool {
        let Some(cells) = self.cells else {
            return true;
        };
        let slot = (c.0.wrapping_mul(73_856_093)
            ^ c.1.wrapping_mul(19_349_663)
            ^ c.2.wrapping_mul(83_492_791)) as usize
            % REMEMBERED;
        match self.remembered[slot] {
            Some((l, answer)) if l == c => answer,
            _ => {
                let answer = cells.contains(&c);
                self.remembered[slot] = Some((c, answer));
                answer
            }
        }
    }
}

/// Segments by grid cell (see the module doc).
pub struct CutGrid {
    size: f64,
    cells: FastMap<Cell, Vec<usize>>,
}

/// The segments around the cells one walker asked a [`CutGrid`] about, kept for its next
/// questions while the grid stays as it is (see the module doc). Each thread of a walk keeps
/// its own.
#[derive(Default)]
pub struct Near {
    /// The cell last asked for, the segments around it (each once, in index order) and the
    /// balls of their runs ([`Balls::blocks`], when asked with balls).
    last: Option<Cell>,
    near: Vec<usize>,
    blocks: Vec<Ball>,
    /// The same for each cell asked for: the walk's queue goes from one lip's vertices to
    /// another's, so consecutive questions are often about other cells than the last, and
    /// gathering and sorting 27 cells' lists again each time was a good part of a walk.
    by_cell: FastMap<Cell, (Vec<usize>, Vec<Ball>)>,
}

impl Near {
    /// The segments of `grid` in the 27 cells around `p`'s (every segment within the cell size
    /// of `p` among them), each once, in index order. `grid` must be the grid of every earlier
    /// question.
    pub fn near(&mut self, grid: &CutGrid, p: DVec3) -> &[usize] {
        self.lists(grid, p, None);
        &self.near
    }

    /// [`Near::near`], with the balls of its runs of segments ([`Balls::blocks`]). A walker
    /// asks with the same `balls` every time.
    pub(crate) fn near_in_blocks(
        &mut self,
        grid: &CutGrid,
        p: DVec3,
        balls: &Balls,
    ) -> (&[usize], &[Ball]) {
        self.lists(grid, p, Some(balls));
        (&self.near, &self.blocks)
    }

    fn lists(&mut self, grid: &CutGrid, p: DVec3, balls: Option<&Balls>) {
        let c0 = grid.cell(p);
        if self.last == Some(c0) {
            return;
        }
        let (near, blocks) = self.by_cell.entry(c0).or_insert_with(|| {
            let mut near = Vec::new();
            for x in c0.0 - 1..=c0.0 + 1 {
                for y in c0.1 - 1..=c0.1 + 1 {
                    for z in c0.2 - 1..=c0.2 + 1 {
                        if let Some(list) = grid.cells.get(&(x, y, z)) {
                            near.extend_from_slice(list);
                        }
                    }
                }
            }
            near.sort_unstable();
            near.dedup();
            (near, Vec::new())
        });
        // The runs' balls, made the first time they are asked for.
        if let Some(balls) = balls
            && blocks.len() != near.len().div_ceil(BLOCK)
        {
            *blocks = balls.blocks(near);
        }
        self.near.clear();
        self.near.extend_from_slice(near);
        self.blocks.clear();
        self.blocks.extend_from_slice(blocks);
        self.last = Some(c0);
    }
}

impl CutGrid {
    /// The segments of `segments` whose both ends are below `vertex_count`, in cells of `size`.
    pub fn new(segments: &[CutSegment], vertex_count: u32, size: f64) -> CutGrid {
        let mut grid = CutGrid {
            size,
            cells: FastMap::default(),
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
    }

    /// The segments listed in `cells`, each once, in index order.
    pub fn segments_in(&self, cells: &FastSet<Cell>) -> Vec<usize> {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_i64_is_the_library_floor() {
        let mut rng = csg::testkit::SplitMix(99);
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1e-300,
            1e-300,
            4503599627370495.5,
            -4503599627370495.5,
            9007199254740993.0,
            -9007199254740993.0,
            1e30,
            -1e30,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for _ in 0..10_000 {
            let x = (rng.next_f64() - 0.5) * 2e3;
            xs.extend([x, x.floor(), x.floor() - f64::EPSILON * x.abs()]);
        }
        for x in xs {
            assert_eq!(floor_i64(x), x.floor() as i64, "{x}");
        }
    }

    #[test]
    fn cells_within_hold_every_point_of_the_ball_and_fewer_cells_than_the_cube() {
        let size = 6.0;
        let mut rng = csg::testkit::SplitMix(12345);
        let mut random = || rng.next_f64();
        for _ in 0..200 {
            let p = DVec3::new(random(), random(), random()) * 40.0 - 20.0;
            let radius = 8.0 * random();
            let mut cells = FastSet::default();
            cells_within(&mut cells, p, radius, size);
            for _ in 0..200 {
                let d = DVec3::new(random(), random(), random()) * 2.0 - 1.0;
                let x = p + d.normalize_or_zero() * radius * random().sqrt();
                assert!(
                    cells.contains(&cell_of(x, size)),
                    "{x:?} within {radius} of {p:?}, its cell missing"
                );
                // Points on the sphere itself too (the farthest the ball reaches).
                let y = p + d.normalize_or_zero() * radius;
                assert!(cells.contains(&cell_of(y, size)));
            }
            let reach = (radius / size).ceil() as usize + 1;
            assert!(cells.len() <= (2 * reach + 1).pow(3));
        }
        // A ball of 8 around a cell's centre, cells of 6: not the 125 of the cube around it.
        let mut cells = FastSet::default();
        cells_within(&mut cells, DVec3::splat(3.0), 8.0, size);
        assert!(cells.len() < 60, "{} cells", cells.len());
        assert!(cells.contains(&(0, 0, 0)) && cells.contains(&(1, 0, 0)));
        assert!(!cells.contains(&(2, 2, 2)));
    }

    #[test]
    fn a_cells_list_asked_for_without_balls_gets_them_when_asked_with() {
        // A path of 40 short segments through a few cells.
        let segments: Vec<CutSegment> = (0..40)
            .map(|k| {
                let x = 0.5 * k as f64;
                CutSegment::between(DVec3::new(x, 1.0, 1.0), DVec3::new(x + 0.5, 1.0, 1.0))
            })
            .collect();
        let grid = CutGrid::new(&segments, 2, 6.0);
        let balls = Balls::new(&segments);
        let p = DVec3::new(9.0, 1.0, 1.0);
        let mut near = Near::default();
        let plain = near.near(&grid, p).to_vec();
        assert!(plain.len() > BLOCK);
        // Another cell in between, so that the first cell's list comes from the kept lists.
        near.near(&grid, DVec3::new(40.0, 1.0, 1.0));
        let (list, blocks) = near.near_in_blocks(&grid, p, &balls);
        assert_eq!(list, &plain[..]);
        assert_eq!(blocks.len(), list.len().div_ceil(BLOCK));
        assert_eq!(blocks, &balls.blocks(list)[..]);
    }
}
