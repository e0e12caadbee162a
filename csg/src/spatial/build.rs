//! Building a [`SpatialIndex`]: the faces' `f32` boxes rounded outward, their Morton order, and
//! the linear BVH split top-down at the first differing code bit (subtrees of large ranges on
//! rayon's workers). The tree's layout ([`Node`]) is shared with the queries in the parent module.

use glam::DVec3;

use super::{LEAF_SIZE, MORTON_BITS, PARALLEL_RANGE, SpatialIndex};
use crate::aabb::Aabb;
use crate::mesh::Mesh;

/// An axis-aligned box in `f32` (min corner, max corner).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct FBox {
    pub(super) min: [f32; 3],
    pub(super) max: [f32; 3],
}

impl FBox {
    /// The union of two boxes.
    #[inline]
    pub(super) fn union(&self, o: &FBox) -> FBox {
        FBox {
            min: std::array::from_fn(|k| self.min[k].min(o.min[k])),
            max: std::array::from_fn(|k| self.max[k].max(o.max[k])),
        }
    }

    /// The box in `f64` (exact conversion).
    #[inline(always)]
    pub(super) fn to_f64(self) -> (DVec3, DVec3) {
        (
            DVec3::new(self.min[0] as f64, self.min[1] as f64, self.min[2] as f64),
            DVec3::new(self.max[0] as f64, self.max[1] as f64, self.max[2] as f64),
        )
    }

    /// The box in `f64`, widened by `slack`.
    #[inline(always)]
    pub(super) fn widened(self, slack: f64) -> (DVec3, DVec3) {
        let (min, max) = self.to_f64();
        (min - DVec3::splat(slack), max + DVec3::splat(slack))
    }

    /// The `f64` box `[min, max]` rounded outward to `f32`.
    #[inline]
    pub(super) fn outward(min: DVec3, max: DVec3) -> FBox {
        FBox {
            min: [round_down(min.x), round_down(min.y), round_down(min.z)],
            max: [round_up(max.x), round_up(max.y), round_up(max.z)],
        }
    }
}

/// A tree node (32 bytes): a leaf when `count > 0` (slots `first..first + count` of
/// [`SpatialIndex::faces`]), otherwise an inner node with
/// children `first` and `first + 1`, which come after it in the node array.
#[derive(Clone, Copy, Debug)]
pub(super) struct Node {
    pub(super) bounds: FBox,
    pub(super) first: u32,
    pub(super) count: u32,
}

impl Node {
    #[inline(always)]
    pub(super) fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The slots of a leaf's faces.
    #[inline(always)]
    pub(super) fn slots(&self) -> std::ops::Range<usize> {
        self.first as usize..(self.first + self.count) as usize
    }
}

/// Largest `f32` not above `x` (clamped to the finite `f32` range).
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    let f = if f as f64 > x { f.next_down() } else { f };
    f.max(-f32::MAX)
}

/// Smallest `f32` not below `x` (clamped to the finite `f32` range).
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    let f = if (f as f64) < x { f.next_up() } else { f };
    f.min(f32::MAX)
}

/// Spreads the low 10 bits of `x` to every third bit (bit `i` goes to bit `3i`).
#[inline]
fn spread_bits(x: u32) -> u64 {
    let mut x = (x & 0x3ff) as u64;
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    x = (x | (x << 2)) & 0x0924_9249;
    x
}

/// Stable LSD radix sort of `keys` by their bits `32..32 + 3 * MORTON_BITS` (the Morton code).
fn radix_sort_codes(keys: &mut Vec<u64>) {
    const BUCKETS: usize = 1 << MORTON_BITS;
    let mut buffer: Vec<u64> = vec![0; keys.len()];
    for pass in 0..3 {
        let shift = 32 + pass * MORTON_BITS;
        let digit = |k: u64| ((k >> shift) as usize) & (BUCKETS - 1);
        let mut start = [0usize; BUCKETS];
        for &k in keys.iter() {
            start[digit(k)] += 1;
        }
        let mut sum = 0;
        for s in start.iter_mut() {
            let count = *s;
            *s = sum;
            sum += count;
        }
        for &k in keys.iter() {
            let d = digit(k);
            buffer[start[d]] = k;
            start[d] += 1;
        }
        std::mem::swap(keys, &mut buffer);
    }
}

/// Number of nodes of the subtree over the sorted `codes` (see [`split_point`]).
fn count_nodes(codes: &[u64]) -> usize {
    match split_point(codes) {
        None => 1,
        Some(mid) => 1 + count_nodes(&codes[..mid]) + count_nodes(&codes[mid..]),
    }
}

/// Where the tree splits the sorted `codes` (None: a leaf): at the first code with the highest
/// bit in which the first and last codes differ set, or in the middle when they are equal.
#[inline]
fn split_point(codes: &[u64]) -> Option<usize> {
    let m = codes.len();
    if m <= LEAF_SIZE {
        return None;
    }
    let (first, last) = (codes[0] >> 32, codes[m - 1] >> 32);
    if first == last {
        return Some(m / 2);
    }
    let bit = 63 - (first ^ last).leading_zeros();
    Some(codes.partition_point(|&k| (k >> 32) >> bit & 1 == 0))
}

/// A subtree built by one worker: its root is node `root` of the top part of the array, its
/// faces are slots `start..start + len`, its descendants a block of the array.
struct Task {
    root: usize,
    start: usize,
    len: usize,
}

/// Splits the faces at slots `start..start + codes.len()` top-down (the node `slot` of `top`
/// covers them) until ranges are smaller than [`PARALLEL_RANGE`]; those become [`Task`]s. Top
/// nodes get their children at the end of `top` (so after themselves).
fn plan(codes: &[u64], start: usize, slot: usize, top: &mut Vec<Node>, tasks: &mut Vec<Task>) {
    let split = match split_point(codes) {
        Some(split) if codes.len() >= PARALLEL_RANGE => split,
        _ => {
            tasks.push(Task {
                root: slot,
                start,
                len: codes.len(),
            });
            return;
        }
    };
    let children = top.len();
    top[slot].first = children as u32;
    top.extend([top[slot]; 2]);
    plan(&codes[..split], start, children, top, tasks);
    plan(&codes[split..], start + split, children + 1, top, tasks);
}

/// Builds the subtree over `codes` (faces at slots `offset..`; `boxes` by face id) and returns its
/// root; descendants are written to `block` from `*cursor` on (children first, then the left
/// child's descendants, then the right child's), `block[0]` being node `block_index`.
fn build_range(
    codes: &[u64],
    boxes: &[FBox],
    offset: u32,
    block: &mut [Node],
    block_index: u32,
    cursor: &mut usize,
) -> Node {
    let Some(split) = split_point(codes) else {
        let bounds = codes[1..]
            .iter()
            .fold(boxes[codes[0] as u32 as usize], |acc, &k| {
                acc.union(&boxes[k as u32 as usize])
            });
        return Node {
            bounds,
            first: offset,
            count: codes.len() as u32,
        };
    };
    let slot = *cursor;
    *cursor += 2;
    let left = build_range(&codes[..split], boxes, offset, block, block_index, cursor);
    let right = build_range(
        &codes[split..],
        boxes,
        offset + split as u32,
        block,
        block_index,
        cursor,
    );
    block[slot] = left;
    block[slot + 1] = right;
    Node {
        bounds: left.bounds.union(&right.bounds),
        first: block_index + slot as u32,
        count: 0,
    }
}

/// The tree over the sorted `codes` (`boxes`: the faces' boxes by face id). The top levels are
/// split sequentially ([`plan`]); the subtrees below are counted, then built, on rayon's
/// workers, each into its own block of the node array; the top boxes are filled in last.
fn build_tree(codes: &[u64], boxes: &[FBox]) -> Vec<Node> {
    use rayon::prelude::*;
    let placeholder = Node {
        bounds: boxes[0],
        first: 0,
        count: 0,
    };
    let mut top = vec![placeholder];
    let mut tasks = Vec::new();
    plan(codes, 0, 0, &mut top, &mut tasks);
    let sizes: Vec<usize> = tasks
        .par_iter()
        .map(|t| count_nodes(&codes[t.start..t.start + t.len]) - 1)
        .collect();
    let top_len = top.len();
    let mut nodes = top;
    nodes.resize(top_len + sizes.iter().sum::<usize>(), placeholder);
    let (top, mut rest) = nodes.split_at_mut(top_len);
    let mut blocks = Vec::with_capacity(tasks.len());
    let mut block_index = top_len;
    for (task, &size) in tasks.iter().zip(&sizes) {
        let (block, tail) = rest.split_at_mut(size);
        blocks.push((task, block, block_index as u32));
        block_index += size;
        rest = tail;
    }
    let roots: Vec<Node> = blocks
        .into_par_iter()
        .map(|(task, block, block_index)| {
            let range = task.start..task.start + task.len;
            let mut cursor = 0;
            let root = build_range(
                &codes[range],
                boxes,
                task.start as u32,
                block,
                block_index,
                &mut cursor,
            );
            debug_assert_eq!(cursor, block.len());
            root
        })
        .collect();
    let mut is_task_root = vec![false; top_len];
    for (task, root) in tasks.iter().zip(roots) {
        top[task.root] = root;
        is_task_root[task.root] = true;
    }
    // Children come after their parent, so a reverse sweep sees them first.
    for i in (0..top_len).rev() {
        if !is_task_root[i] {
            let first = top[i].first as usize;
            top[i].bounds = top[first].bounds.union(&top[first + 1].bounds);
        }
    }
    nodes
}

impl SpatialIndex {
    /// Builds the index for `mesh`.
    ///
    /// Requires a structurally valid mesh ([`Mesh::sanity_check`]).
    pub fn build(mesh: &Mesh) -> SpatialIndex {
        use rayon::prelude::*;
        let n = mesh.triangles.len();
        let mut index = SpatialIndex {
            nodes: Vec::new(),
            faces: Vec::new(),
            face_boxes: Vec::new(),
            triangle_count: n,
            slack: 0.0,
        };
        if n == 0 {
            return index;
        }
        let bbox = Aabb::from_points(&mesh.positions);
        index.slack = 16.0 * f64::EPSILON * bbox.min.abs().max(bbox.max.abs()).max_element();
        // Morton codes of the box centres on a 2^MORTON_BITS grid over the vertices' box.
        let cells = (1u32 << MORTON_BITS) as f64;
        let to_cells = DVec3::splat(cells) / bbox.size().max(DVec3::splat(f64::MIN_POSITIVE));
        // One pass in face order (cache-friendly: neighbouring faces share vertices): each
        // face's box, and the Morton code of its centre.
        let (face_boxes, mut codes): (Vec<FBox>, Vec<u64>) = (0..n)
            .into_par_iter()
            .with_min_len(1 << 14)
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                let (min, max) = (a.min(b).min(c), a.max(b).max(c));
                let q = (((min + max) * 0.5 - bbox.min) * to_cells)
                    .clamp(DVec3::ZERO, DVec3::splat(cells - 1.0));
                let code = spread_bits(q.x as u32)
                    | (spread_bits(q.y as u32) << 1)
                    | (spread_bits(q.z as u32) << 2);
                (FBox::outward(min, max), (code << 32) | t as u64)
            })
            .unzip();
        // Stable: faces with the same code stay in index order, so the tree depends on the mesh
        // alone.
        radix_sort_codes(&mut codes);
        index.face_boxes = face_boxes;
        index.faces = codes.par_iter().map(|&k| k as u32).collect();
        let nodes = build_tree(&codes, &index.face_boxes);
        index.nodes = nodes;
        index
    }
}
