//! The small integer BVH of the boolean: boxes in lattice coordinates (exact, no rounding),
//! median split on the longest axis. It serves the cutter's self-intersection check and the
//! region nesting test; the target's broad phase uses the larger `f32` [`crate::SpatialIndex`].

use crate::exact::LPoint;

/// An integer box `[min, max]` (inclusive) in lattice coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IBox {
    pub min: LPoint,
    pub max: LPoint,
}

impl IBox {
    /// The empty box (growing it by a point gives that point's box).
    pub const EMPTY: IBox = IBox {
        min: [i64::MAX; 3],
        max: [i64::MIN; 3],
    };

    /// Grows the box to contain `p`.
    #[inline]
    pub fn grow(&mut self, p: &LPoint) {
        for k in 0..3 {
            self.min[k] = self.min[k].min(p[k]);
            self.max[k] = self.max[k].max(p[k]);
        }
    }

    /// The union of two boxes.
    #[inline]
    pub fn union(&self, o: &IBox) -> IBox {
        IBox {
            min: std::array::from_fn(|k| self.min[k].min(o.min[k])),
            max: std::array::from_fn(|k| self.max[k].max(o.max[k])),
        }
    }

    /// Inclusive overlap test.
    #[inline]
    pub fn overlaps(&self, o: &IBox) -> bool {
        // Written out: `(0..3).all(..)` did not fully inline in the broad phase.
        (self.min[0] <= o.max[0] && o.min[0] <= self.max[0])
            & (self.min[1] <= o.max[1] && o.min[1] <= self.max[1])
            & (self.min[2] <= o.max[2] && o.min[2] <= self.max[2])
    }

    /// The box of a triangle.
    #[inline]
    pub fn of_triangle(p: [&LPoint; 3]) -> IBox {
        let mut b = IBox::EMPTY;
        for q in p {
            b.grow(q);
        }
        b
    }
}

/// A node of the [`Bvh`]: a leaf when `count > 0` (faces `items[start..start + count]`),
/// otherwise an inner node with children `start` and `start + 1`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: IBox,
    start: u32,
    count: u32,
}

/// Binary BVH over integer triangle boxes (median split on the longest axis).
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// Nodes; node 0 is the root (absent for an empty mesh).
    nodes: Vec<Node>,
    /// Face ids, grouped by leaf.
    items: Vec<u32>,
}

const LEAF_SIZE: usize = 4;

impl Bvh {
    /// Builds the tree over `boxes` (one per face).
    pub fn build(boxes: &[IBox]) -> Bvh {
        if boxes.is_empty() {
            return Bvh::default();
        }
        let mut items: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = vec![Node {
            bounds: IBox::EMPTY,
            start: 0,
            count: 0,
        }];
        // Explicit stack: (node index, item range).
        let mut stack = vec![(0usize, 0usize, items.len())];
        while let Some((node, lo, hi)) = stack.pop() {
            let slice = &mut items[lo..hi];
            let mut bounds = IBox::EMPTY;
            let mut cmin = [i64::MAX; 3];
            let mut cmax = [i64::MIN; 3];
            for &f in slice.iter() {
                let b = &boxes[f as usize];
                bounds = bounds.union(b);
                for k in 0..3 {
                    let c = b.min[k] / 2 + b.max[k] / 2;
                    cmin[k] = cmin[k].min(c);
                    cmax[k] = cmax[k].max(c);
                }
            }
            nodes[node].bounds = bounds;
            if slice.len() <= LEAF_SIZE {
                nodes[node].start = lo as u32;
                nodes[node].count = slice.len() as u32;
                continue;
            }
            let axis = (0..3).max_by_key(|&k| cmax[k] - cmin[k]).unwrap_or(0);
            let mid = slice.len() / 2;
            slice.select_nth_unstable_by_key(mid, |&f| {
                let b = &boxes[f as usize];
                b.min[axis] / 2 + b.max[axis] / 2
            });
            let first_child = nodes.len();
            for _ in 0..2 {
                nodes.push(Node {
                    bounds: IBox::EMPTY,
                    start: 0,
                    count: 0,
                });
            }
            nodes[node].start = first_child as u32;
            nodes[node].count = 0;
            stack.push((first_child, lo, lo + mid));
            stack.push((first_child + 1, lo + mid, hi));
        }
        Bvh { nodes, items }
    }

    /// Calls `visit` for every face whose box (`boxes`, the boxes the tree was built from)
    /// overlaps `query` (inclusive).
    pub fn query(&self, query: &IBox, boxes: &[IBox], mut visit: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !node.bounds.overlaps(query) {
                continue;
            }
            if node.count > 0 {
                let s = node.start as usize;
                for &f in &self.items[s..s + node.count as usize] {
                    if boxes[f as usize].overlaps(query) {
                        visit(f);
                    }
                }
            } else if top + 2 <= stack.len() {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
            }
        }
    }
}
