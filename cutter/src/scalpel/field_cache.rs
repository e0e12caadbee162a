//! The field of the opening ([`FieldAt`]) kept between steps, by grid cell.
//!
//! The live opening ([`super::live_opening`]) recomputes the cells around what a step changed.
//! Most of those cells are there only because a segment near them opened a little further (its
//! ramp grew with the clock): their vertices' nearest segments, sides, tapers and path
//! corrections are what they were, and walking to them and measuring them again was nearly all
//! of a step's opening. So the field of every vertex the walk reaches is kept here, by the cell
//! of its rest position; a step walks again only the cells where the field itself may have
//! changed ([`FieldCache::replace`]) and evaluates the kept field of the others at the new
//! clock. A vertex whose rest position changed is found here by its id
//! ([`FieldCache::cell_of_vertex`]) so that its old cell is walked again too.

use super::cut_grid::{Cell, cell_of};
use super::field::FieldAt;
use csg::fast_hash::{FastMap, FastSet};

/// The field of the opening by cell (see the module doc).
#[derive(Default)]
pub(crate) struct FieldCache {
    cells: FastMap<Cell, Vec<FieldAt>>,
    /// The cell each kept vertex is listed in.
    vertex_cell: FastMap<u32, Cell>,
}

impl FieldCache {
    pub fn clear(&mut self) {
        self.cells.clear();
        self.vertex_cell.clear();
    }

    /// The cell vertex `v`'s field is kept in, if it is kept.
    pub fn cell_of_vertex(&self, v: u32) -> Option<Cell> {
        self.vertex_cell.get(&v).copied()
    }

    /// Replaces the field kept in `cells` by the entries of `field` whose rest position lies in
    /// them (cells of `size`); the other entries of `field` are ignored. With `cells` `None`,
    /// everything kept is replaced by `field`.
    pub fn replace(&mut self, cells: Option<&FastSet<Cell>>, field: Vec<FieldAt>, size: f64) {
        match cells {
            None => self.clear(),
            Some(cells) => {
                for c in cells {
                    for f in self.cells.remove(c).into_iter().flatten() {
                        if self.vertex_cell.get(&f.vertex) == Some(c) {
                            self.vertex_cell.remove(&f.vertex);
                        }
                    }
                }
            }
        }
        for f in field {
            let c = cell_of(f.rest, size);
            if cells.is_none_or(|cells| cells.contains(&c)) {
                // Listed once: in the cell of its rest position now.
                if let Some(old) = self.vertex_cell.insert(f.vertex, c)
                    && old != c
                    && let Some(list) = self.cells.get_mut(&old)
                {
                    list.retain(|g| g.vertex != f.vertex);
                }
                self.cells.entry(c).or_default().push(f);
            }
        }
    }

    /// The field kept in `cells`.
    pub fn in_cells<'a>(&'a self, cells: &'a FastSet<Cell>) -> impl Iterator<Item = &'a FieldAt> {
        cells.iter().filter_map(|c| self.cells.get(c)).flatten()
    }

    /// How many vertices' field is kept.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.vertex_cell.len()
    }
}
