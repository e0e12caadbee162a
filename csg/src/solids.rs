//! The solids a cut classifies the cutter against: one per closed region, plus the open regions
//! together.
//!
//! Each closed region of the target ([`crate::cavities`]) is cut as its own solid, so a point of
//! the cutter can lie in several solids at once (a brain inside the skin: both). A cutter point's
//! status is the set of solids it lies in, and crossing a target face toggles that face's solid.
//! The walls of a cut are the cutter pieces inside each solid, once per solid: nested outward
//! regions each get their own closed walls, and a cavity (an inward shell of the same region)
//! bounds its region's material like the outer shell does.
//!
//! Open regions bound no solid; together they form one more "solid", [`OPEN_PART`], classified
//! by the generalized winding number as before.
//!
//! Sets are interned: a cut sees a handful of distinct sets, so a status is one `u32` and
//! toggling a solid is a memoized table lookup.

use crate::intersect::FxMap;
use crate::target::TargetIndex;

/// The solid of the open regions of a target, taken together.
pub const OPEN_PART: u32 = u32::MAX;

/// The solid face `t` of `target` bounds: its region when that is closed, else [`OPEN_PART`].
#[inline]
pub(crate) fn solid_of_face(target: &TargetIndex, t: u32) -> u32 {
    let c = target.components.region_of_triangle[t as usize] as usize;
    if target.component_closed[c] {
        target.regions.region_of_component[c]
    } else {
        OPEN_PART
    }
}

/// Interned sets of solids; set 0 is the empty set.
pub(crate) struct SolidSets {
    sets: Vec<Vec<u32>>,
    ids: FxMap<Vec<u32>, u32>,
    toggled: FxMap<(u32, u32), u32>,
}

impl SolidSets {
    pub(crate) fn new() -> SolidSets {
        let mut ids: FxMap<Vec<u32>, u32> = Default::default();
        ids.insert(Vec::new(), 0);
        SolidSets {
            sets: vec![Vec::new()],
            ids,
            toggled: Default::default(),
        }
    }

    /// The id of the set of solids `sorted` (ascending, no repeats).
    pub(crate) fn intern(&mut self, sorted: Vec<u32>) -> u32 {
        if let Some(&id) = self.ids.get(&sorted) {
            return id;
        }
        let id = self.sets.len() as u32;
        self.sets.push(sorted.clone());
        self.ids.insert(sorted, id);
        id
    }

    /// The set `set` with `solid` added or removed.
    pub(crate) fn toggle(&mut self, set: u32, solid: u32) -> u32 {
        if let Some(&id) = self.toggled.get(&(set, solid)) {
            return id;
        }
        let mut s = self.sets[set as usize].clone();
        match s.binary_search(&solid) {
            Ok(i) => {
                s.remove(i);
            }
            Err(i) => s.insert(i, solid),
        }
        let id = self.intern(s);
        self.toggled.insert((set, solid), id);
        id
    }

    /// The solids of set `set`, ascending.
    #[inline]
    pub(crate) fn solids(&self, set: u32) -> &[u32] {
        &self.sets[set as usize]
    }

    /// Does set `set` hold `solid`?
    #[inline]
    pub(crate) fn contains(&self, set: u32, solid: u32) -> bool {
        self.sets[set as usize].binary_search(&solid).is_ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toggling_interns_sets() {
        let mut s = SolidSets::new();
        let a = s.toggle(0, 3);
        let b = s.toggle(a, 1);
        assert_eq!(s.solids(b), &[1, 3]);
        assert!(s.contains(b, 1) && s.contains(b, 3) && !s.contains(b, 2));
        let c = s.toggle(b, 3);
        assert_eq!(s.toggle(c, 1), 0);
        assert_eq!(s.intern(vec![1, 3]), b);
        let open = s.toggle(0, OPEN_PART);
        assert_eq!(open, s.intern(vec![OPEN_PART]));
    }
}
