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
//! sides (a cut changes which lip reaches a vertex first, a segment's frame decides its lips'
//! sides), but of a vertex's field (the frame's lateral is read when it is evaluated)
//! - the nearest segment changes only when a segment cut, undone or moved is that segment or
//!   comes as near (then everything is measured again);
//! - the taper only when a crack tip within the taper length of its nearest cut point
//!   appeared or went;
//! - the path correction only when a segment with an end within the support was cut, undone
//!   or moved, or a segment within the support got other path corrections (those near the tool
//!   follow the path drawn past them).
//!
//! [`Changes`] holds those and [`FieldCache::kept`] gives a vertex's kept field, with the side
//! the walk gives it now (the side only multiplies the field) and what of it to measure again;
//! nothing when the vertex itself moved.

use glam::DVec3;

use super::cut_grid::{Cell, cell_of};
use super::field::{FieldAt, taper_at};
use super::nearest_cut::point_on;
use super::step::CutSegment;
use csg::fast_hash::{FastMap, FastSet};

/// Relative slack of the reach tests of [`Changes`] (times the distance and the coordinates):
/// a vertex at the edge of a reach is measured again.
const SLACK: f64 = 1e-9;

/// The field of the opening by vertex and cell (see the module doc). Each cell's fields lie
/// together in one list, in the order the walk gave them: a step evaluates every field of the
/// cells around it one after another, and the walk looks one up for each vertex it reaches, so
/// a map of whole fields by vertex (their slots in hash order) had each of those fetch its own
/// memory.
#[derive(Default)]
pub(crate) struct FieldCache {
    /// Per slot, a cell and the fields kept in it (a slot stays with its cell until
    /// [`FieldCache::clear`]).
    slots: Vec<(Cell, Vec<FieldAt>)>,
    /// The slot of each cell given one.
    slot_of: FastMap<Cell, u32>,
    /// Where each kept vertex's field is: its slot and its index there.
    at: FastMap<u32, (u32, u32)>,
    /// Per vertex, whether a field is kept for it (bits): the walk asks this of every vertex of
    /// its margin, where a field kept is one still valid (see [`FieldCache::holds`]), and a
    /// table of bits answers from the cache where the map would fetch from memory.
    held: Vec<u64>,
}

/// What changed between the field kept and the field now, apart from the mesh and the sides
/// (see the module doc).
#[derive(Default)]
pub(crate) struct Changes {
    /// The segments cut, undone or moved, by index (as they were and as they are), with a ball
    /// holding every point within the support of each.
    pub segments: Vec<(u32, CutSegment, (DVec3, f64))>,
    /// Balls holding every point within the support of the segments that only changed their
    /// path corrections.
    pub correction_balls: Vec<(DVec3, f64)>,
    /// Crack tips that appeared or went.
    pub tips: Vec<DVec3>,
    pub taper_len: f64,
    /// The support radius.
    pub r: f64,
}

impl Changes {
    /// Adds segment `i` as it was or is now, `s`, changed (its support reaches `r` from it).
    pub fn segment(&mut self, i: usize, s: &CutSegment, r: f64) {
        self.segments.push((i as u32, *s, ball(s, r)));
    }

    /// Adds the segment `s`, in place but with other path corrections at its ends.
    pub fn corrections(&mut self, s: &CutSegment, r: f64) {
        self.correction_balls.push(ball(s, r));
    }

    /// What of the field `f` kept at rest position `p` may differ now: `None` when its nearest
    /// segment may have (a changed segment is it, or comes as near), else whether its taper and
    /// its path correction may have.
    fn reach(&self, p: DVec3, f: &FieldAt) -> Option<(bool, bool)> {
        let within = |m: DVec3, reach: f64| {
            let lim = slack(reach, p);
            m.distance_squared(p) <= lim * lim
        };
        let mut correction = self
            .correction_balls
            .iter()
            .any(|&(m, reach)| within(m, reach));
        for (i, s, (m, reach)) in &self.segments {
            if !within(*m, *reach) {
                continue;
            }
            let (d2, _) = point_on(s, p);
            if *i == f.segment || d2.sqrt() <= slack(f.dist, p) {
                return None;
            }
            // Its ends' path corrections are blended at `p` when within the support.
            correction |= within(s.pa, self.r) || within(s.pb, self.r);
        }
        let taper = self.tips.iter().any(|&t| {
            let lim = slack(self.taper_len, f.nearest);
            t.distance_squared(f.nearest) <= lim * lim
        });
        Some((taper, correction))
    }
}

/// A ball holding every point within `r` of segment `s`.
fn ball(s: &CutSegment, r: f64) -> (DVec3, f64) {
    (s.pa.midpoint(s.pb), r + 0.5 * s.pa.distance(s.pb))
}

/// `d` with the slack of [`SLACK`] at `x`.
fn slack(d: f64, x: DVec3) -> f64 {
    d * (1.0 + SLACK) + SLACK * (1.0 + x.abs().max_element())
}

/// A kept field as a walk may use it: with the side the walk gives now, its taper and its
/// path correction to be measured again where a change may have changed them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Kept {
    pub field_at: FieldAt,
    pub taper: bool,
    pub correction: bool,
}

impl FieldCache {
    pub fn clear(&mut self) {
        self.slots.clear();
        self.slot_of.clear();
        self.at.clear();
        self.held.clear();
    }

    /// Whether a field is kept for vertex `v`, whatever its rest position now (the walk's
    /// margin holds no vertex edited since it was kept: the cells of those are walked).
    #[inline]
    pub fn holds(&self, v: u32) -> bool {
        self.held
            .get((v / 64) as usize)
            .is_some_and(|w| w & (1 << (v % 64)) != 0)
    }

    fn hold(&mut self, v: u32, held: bool) {
        let word = (v / 64) as usize;
        if word >= self.held.len() {
            self.held.resize(word + 1, 0);
        }
        if held {
            self.held[word] |= 1 << (v % 64);
        } else {
            self.held[word] &= !(1 << (v % 64));
        }
    }

    /// The cell vertex `v`'s field is kept in, if it is kept.
    pub fn cell_of_vertex(&self, v: u32) -> Option<Cell> {
        self.at.get(&v).map(|&(s, _)| self.slots[s as usize].0)
    }

    /// The field kept for vertex `v` at rest position `p`, on side `sigma` now, when `changes`
    /// cannot have changed it, or changed only its path correction (see the module doc);
    /// `changes` `None` when none can reach `p`.
    #[inline]
    pub fn kept(&self, v: u32, p: DVec3, sigma: f64, changes: Option<&Changes>) -> Option<Kept> {
        let &(s, i) = self.at.get(&v)?;
        let f = &self.slots[s as usize].1[i as usize];
        if f.rest.to_array().map(f64::to_bits) != p.to_array().map(f64::to_bits) {
            return None;
        }
        let (taper, correction) = match changes {
            Some(changes) => changes.reach(p, f)?,
            None => (false, false),
        };
        Some(Kept {
            field_at: FieldAt { sigma, ..*f },
            taper,
            correction,
        })
    }

    /// Replaces the field kept in `cells` by the entries of `field` whose rest position lies in
    /// them (cells of `size`); the other entries of `field` are ignored. With `cells` `None`,
    /// everything kept is replaced by `field`.
    pub fn replace(&mut self, cells: Option<&FastSet<Cell>>, field: Vec<FieldAt>, size: f64) {
        match cells {
            None => self.clear(),
            Some(cells) => {
                for c in cells {
                    if let Some(&s) = self.slot_of.get(c) {
                        let mut list = std::mem::take(&mut self.slots[s as usize].1);
                        for f in list.drain(..) {
                            self.at.remove(&f.vertex);
                            self.hold(f.vertex, false);
                        }
                        self.slots[s as usize].1 = list;
                    }
                }
            }
        }
        for f in field {
            let c = cell_of(f.rest, size);
            if cells.is_some_and(|cells| !cells.contains(&c)) {
                continue;
            }
            // Kept elsewhere still: its rest position moved out of a cell not replaced.
            if let Some((s, i)) = self.at.remove(&f.vertex) {
                let list = &mut self.slots[s as usize].1;
                list.swap_remove(i as usize);
                if let Some(g) = list.get(i as usize) {
                    self.at.insert(g.vertex, (s, i));
                }
            }
            let slots = &mut self.slots;
            let s = *self.slot_of.entry(c).or_insert_with(|| {
                slots.push((c, Vec::new()));
                (slots.len() - 1) as u32
            });
            let list = &mut self.slots[s as usize].1;
            self.at.insert(f.vertex, (s, list.len() as u32));
            let v = f.vertex;
            list.push(f);
            self.hold(v, true);
        }
    }

    /// Measures again the taper of the field kept in `cells`, from the crack tips `tips` (their
    /// nearest cut points stay: only tips changed near them).
    pub fn retaper(&mut self, cells: &FastSet<Cell>, tips: &[DVec3], taper_len: f64) {
        for c in cells {
            if let Some(&s) = self.slot_of.get(c) {
                for f in &mut self.slots[s as usize].1 {
                    f.taper = taper_at(tips, f.nearest, taper_len);
                }
            }
        }
    }

    /// The field kept in `cells`.
    pub fn in_cells<'a>(&'a self, cells: &'a FastSet<Cell>) -> impl Iterator<Item = &'a FieldAt> {
        cells
            .iter()
            .filter_map(|c| self.slot_of.get(c))
            .flat_map(|&s| self.slots[s as usize].1.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(vertex: u32, rest: DVec3) -> FieldAt {
        FieldAt {
            vertex,
            segment: 0,
            rest,
            nearest: rest + DVec3::X,
            dist: 1.0,
            sigma: 1.0,
            taper: 1.0,
            falloff: 0.5,
            correction: DVec3::ZERO,
        }
    }

    #[test]
    fn a_vertex_is_kept_once_in_the_cell_of_its_rest_position_now() {
        let size = 2.0;
        let mut cache = FieldCache::default();
        let (a, b) = (DVec3::new(0.5, 0.5, 0.5), DVec3::new(4.5, 0.5, 0.5));
        cache.replace(None, vec![field(7, a), field(8, a)], size);
        let (ca, cb) = (cell_of(a, size), cell_of(b, size));
        assert_eq!(cache.cell_of_vertex(7), Some(ca));
        // Vertex 7 moved to another cell, which alone is walked again.
        let walked: FastSet<Cell> = [cb].into_iter().collect();
        cache.replace(Some(&walked), vec![field(7, b), field(9, a)], size);
        assert_eq!(cache.cell_of_vertex(7), Some(cb));
        // 8 took 7's place in the first cell's list: still found by its id.
        let found = |v: u32, p: DVec3| cache.kept(v, p, 1.0, None).map(|k| k.field_at.vertex);
        assert_eq!(
            (found(8, a), found(7, b), found(7, a)),
            (Some(8), Some(7), None)
        );
        // 9 lies outside the walked cells: not kept.
        assert_eq!(cache.cell_of_vertex(9), None);
        let both: FastSet<Cell> = [ca, cb].into_iter().collect();
        let mut kept: Vec<(u32, DVec3)> =
            cache.in_cells(&both).map(|f| (f.vertex, f.rest)).collect();
        kept.sort_by_key(|k| k.0);
        assert_eq!(kept, vec![(7, b), (8, a)]);
        // Walking the first cell again drops what it held.
        let first: FastSet<Cell> = [ca].into_iter().collect();
        cache.replace(Some(&first), Vec::new(), size);
        assert_eq!(cache.cell_of_vertex(8), None);
        assert_eq!(cache.cell_of_vertex(7), Some(cb));
        // Whether a field is kept, by vertex, follows.
        assert_eq!(
            (cache.holds(7), cache.holds(8), cache.holds(9)),
            (true, false, false)
        );
        assert!(!cache.holds(1 << 20));
        cache.clear();
        assert!(!cache.holds(7));
    }

    #[test]
    fn a_kept_field_is_given_only_where_no_change_reaches_and_the_vertex_did_not_move() {
        let mut cache = FieldCache::default();
        let p = DVec3::new(10.0, 0.0, 0.0);
        // Its nearest cut point one away (segment 0).
        cache.replace(None, vec![field(1, p)], 6.0);
        let r = 3.0;
        let mut changes = Changes {
            taper_len: 0.5,
            r,
            ..Changes::default()
        };
        let parts = |k: Option<Kept>| k.map(|k| (k.taper, k.correction));
        // No change: the kept field, on the side the walk gives now.
        let k = cache.kept(1, p, -1.0, Some(&changes)).unwrap();
        assert_eq!((k.field_at.sigma, k.field_at.rest), (-1.0, p));
        assert_eq!((k.taper, k.correction), (false, false));
        // The vertex moved.
        assert!(
            cache
                .kept(1, p + DVec3::Z * 1e-12, 1.0, Some(&changes))
                .is_none()
        );
        let across = |m: DVec3| CutSegment::between(m - DVec3::Z * 0.1, m + DVec3::Z * 0.1);
        // A segment changed out of the support of it: nothing to measure again.
        changes.segment(5, &across(p + DVec3::Y * (r + 0.5)), r);
        assert_eq!(
            parts(cache.kept(1, p, 1.0, Some(&changes))),
            Some((false, false))
        );
        // One within the support but farther than its nearest cut point: the path correction
        // (its ends are blended).
        changes.segment(6, &across(p + DVec3::Y * 2.0), r);
        assert_eq!(
            parts(cache.kept(1, p, 1.0, Some(&changes))),
            Some((false, true))
        );
        // One as near as its nearest cut point, or its nearest segment itself: all of it.
        changes.segment(7, &across(p - DVec3::Y), r);
        assert!(cache.kept(1, p, 1.0, Some(&changes)).is_none());
        changes.segments.clear();
        changes.segment(0, &across(p + DVec3::Y * 2.5), r);
        assert!(cache.kept(1, p, 1.0, Some(&changes)).is_none());
        changes.segments.clear();
        // A segment in place whose path corrections changed, within the support.
        changes.corrections(&across(p + DVec3::Y * 2.0), r);
        assert_eq!(
            parts(cache.kept(1, p, 1.0, Some(&changes))),
            Some((false, true))
        );
        changes.correction_balls.clear();
        // A crack tip within the taper length of the nearest cut point: the taper.
        let c = p + DVec3::X;
        changes.tips.push(c + DVec3::Y * 0.6);
        assert_eq!(
            parts(cache.kept(1, p, 1.0, Some(&changes))),
            Some((false, false))
        );
        changes.tips.push(c + DVec3::Y * 0.4);
        assert_eq!(
            parts(cache.kept(1, p, 1.0, Some(&changes))),
            Some((true, false))
        );
        // No change can reach it (a margin vertex): kept as it is.
        assert_eq!(parts(cache.kept(1, p, 1.0, None)), Some((false, false)));
    }
}
