//! The field of the opening ([`FieldAt`]) kept between steps, by vertex and by grid cell.
//!
//! The live opening ([`super::live_opening`]) recomputes the cells around what a step changed.
//! Most of those cells are there only because a segment near them opened a little further (its
//! ramp grew with the clock): their vertices' nearest segments, sides, tapers and path
//! corrections are what they were, and walking to them and measuring them again was nearly all
//! of a step's opening. So the field of every vertex the walk reaches is kept here, listed by
//! the cell of its rest position; a step walks again only the cells where the field itself may
//! have changed ([`FieldCache::replace`]) and evaluates the kept field of the others at the new
//! clock. A vertex whose rest position changed is found here by its id
//! ([`FieldCache::cell_of_vertex`]) so that its old cell is walked again too.
//!
//! Even in the walked cells most vertices' field is the one kept: the walk is needed for the
//! sides (a cut changes which lip reaches a vertex first), but a vertex's nearest segment,
//! taper and path correction only change when a cut segment within the support of it changed
//! (cut, undone, or given another frame or path correction), when a crack tip within the taper
//! length of its nearest cut point appeared or went, or when the vertex itself moved.
//! [`Changes`] holds those and [`FieldCache::kept`] gives a vertex's kept field when none of
//! them reaches it, with the side the walk gives it now (the side only multiplies the field).

use glam::DVec3;

use super::cut_grid::{Cell, cell_of};
use super::field::FieldAt;
use super::step::CutSegment;
use csg::fast_hash::{FastMap, FastSet};

/// Relative slack of the reach tests of [`Changes`] (times the distance and the coordinates):
/// a vertex at the edge of a reach is measured again.
const SLACK: f64 = 1e-9;

/// The field of the opening by vertex and cell (see the module doc).
#[derive(Default)]
pub(crate) struct FieldCache {
    fields: FastMap<u32, FieldAt>,
    /// The vertices kept by the cell of their rest position (may hold ids since listed
    /// elsewhere: [`FieldCache::in_cells`] checks).
    cells: FastMap<Cell, Vec<u32>>,
    /// The cell size.
    size: f64,
}

/// What changed between the field kept and the field now, apart from the mesh and the sides
/// (see the module doc).
#[derive(Default)]
pub(crate) struct Changes {
    /// Balls holding every point within the support of a changed segment (before and after).
    pub balls: Vec<(DVec3, f64)>,
    /// Crack tips that appeared or went.
    pub tips: Vec<DVec3>,
    pub taper_len: f64,
}

impl Changes {
    /// Adds the segment `s`, changed, whose support reaches `r` from it.
    pub fn segment(&mut self, s: &CutSegment, r: f64) {
        self.balls
            .push((s.pa.midpoint(s.pb), r + 0.5 * s.pa.distance(s.pb)));
    }

    /// Whether the field at rest position `p` with nearest cut point `c` may differ from the
    /// one kept.
    fn reach(&self, p: DVec3, c: DVec3) -> bool {
        let slack = |d: f64, x: DVec3| d * (1.0 + SLACK) + SLACK * (1.0 + x.abs().max_element());
        self.balls.iter().any(|&(m, reach)| {
            let lim = slack(reach, p);
            m.distance_squared(p) <= lim * lim
        }) || self.tips.iter().any(|&t| {
            let lim = slack(self.taper_len, c);
            t.distance_squared(c) <= lim * lim
        })
    }
}

impl FieldCache {
    pub fn clear(&mut self) {
        self.fields.clear();
        self.cells.clear();
    }

    /// The cell vertex `v`'s field is kept in, if it is kept.
    pub fn cell_of_vertex(&self, v: u32) -> Option<Cell> {
        self.fields.get(&v).map(|f| cell_of(f.rest, self.size))
    }

    /// The field kept for vertex `v` at rest position `p`, on side `sigma` now, when `changes`
    /// cannot have changed it (see the module doc).
    #[inline]
    pub fn kept(&self, v: u32, p: DVec3, sigma: f64, changes: &Changes) -> Option<FieldAt> {
        let f = self.fields.get(&v)?;
        let same_place = f.rest.to_array().map(f64::to_bits) == p.to_array().map(f64::to_bits);
        (same_place && !changes.reach(p, f.nearest)).then(|| FieldAt { sigma, ..*f })
    }

    /// Replaces the field kept in `cells` by the entries of `field` whose rest position lies in
    /// them (cells of `size`); the other entries of `field` are ignored. With `cells` `None`,
    /// everything kept is replaced by `field`.
    pub fn replace(&mut self, cells: Option<&FastSet<Cell>>, field: Vec<FieldAt>, size: f64) {
        match cells {
            None => {
                self.clear();
                self.size = size;
            }
            Some(cells) => {
                for c in cells {
                    for v in self.cells.remove(c).into_iter().flatten() {
                        if self.cell_of_vertex(v) == Some(*c) {
                            self.fields.remove(&v);
                        }
                    }
                }
            }
        }
        for f in field {
            let c = cell_of(f.rest, size);
            if cells.is_none_or(|cells| cells.contains(&c)) {
                self.fields.insert(f.vertex, f);
                self.cells.entry(c).or_default().push(f.vertex);
            }
        }
    }

    /// The field kept in `cells`.
    pub fn in_cells<'a>(&'a self, cells: &'a FastSet<Cell>) -> impl Iterator<Item = &'a FieldAt> {
        cells.iter().flat_map(move |c| {
            self.cells
                .get(c)
                .into_iter()
                .flatten()
                .filter_map(move |v| self.fields.get(v))
                .filter(move |f| cell_of(f.rest, self.size) == *c)
        })
    }
}
