//! The side of the cut each vertex took in the opening's walk ([`super::side_walk::walk`]), by
//! vertex id.
//!
//! The walk asks, for every neighbour of every vertex it visits, whether the neighbour has a
//! side yet: several questions per vertex, for thousands of vertices per step. Kept in a hash
//! map those questions were a good part of a step on a crossing of two grooves. Here they are
//! an array read; the array is kept between walks (the live opening keeps one) and only the
//! entries a walk set are cleared after it, so a walk costs what it visits, not the mesh.

/// Per vertex, the side (`±1`) a walk gave it, `0` for none (see the module doc).
#[derive(Default)]
pub(crate) struct Sides {
    side: Vec<i8>,
    /// The vertices with a side, to clear them.
    set: Vec<u32>,
}

impl Sides {
    /// Ready for a walk over vertices below `vertex_count`: no vertex has a side.
    pub fn start(&mut self, vertex_count: usize) {
        self.clear();
        if self.side.len() < vertex_count {
            self.side.resize(vertex_count, 0);
        }
    }

    /// Forgets every side given.
    pub fn clear(&mut self) {
        for &v in &self.set {
            self.side[v as usize] = 0;
        }
        self.set.clear();
    }

    /// The side of `v`, `None` when it has none yet.
    #[inline]
    pub fn get(&self, v: u32) -> Option<f64> {
        match self.side[v as usize] {
            0 => None,
            s => Some(f64::from(s)),
        }
    }

    #[inline]
    pub fn contains(&self, v: u32) -> bool {
        self.side[v as usize] != 0
    }

    /// Gives `v` the side `sigma` (`±1`).
    #[inline]
    pub fn insert(&mut self, v: u32, sigma: f64) {
        debug_assert!(sigma == 1.0 || sigma == -1.0);
        let s = &mut self.side[v as usize];
        if *s == 0 {
            self.set.push(v);
        }
        *s = if sigma > 0.0 { 1 } else { -1 };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_given_in_one_walk_are_gone_in_the_next() {
        let mut sides = Sides::default();
        sides.start(10);
        sides.insert(3, 1.0);
        sides.insert(7, -1.0);
        assert_eq!(
            (sides.get(3), sides.get(7), sides.get(4)),
            (Some(1.0), Some(-1.0), None)
        );
        sides.start(20);
        assert!((0..20).all(|v| !sides.contains(v)));
        sides.insert(15, -1.0);
        assert_eq!(sides.get(15), Some(-1.0));
    }
}
