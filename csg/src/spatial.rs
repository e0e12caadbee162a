//! Spatial index over a mesh's triangles: a bounding-volume hierarchy in `f32`, queried in `f64`.
//!
//! * **Conservative boxes.** Every triangle's `f64` box is rounded *outward* to `f32`, so each
//!   node box contains its triangles exactly. Traversal happens in `f64` with box tests widened
//!   by a few ulps, so no query can miss a triangle because of rounding. The triangle tests
//!   themselves run on the mesh's `f64` data.
//! * **Mesh face ids.** Every answer names a triangle by its index in the mesh.
//! * **Built for a fast first cut.** The tree is a linear BVH (faces sorted by the Morton code of
//!   their box centre, split top-down at the first differing code bit; Lauterbach et al. 2009,
//!   Karras 2012) with up to [`LEAF_SIZE`] faces per leaf, each with its own box. At 2M faces it
//!   builds with less than half the CPU time of `obvhs`'s PLOC "fastest" preset (which this
//!   module wrapped before; 185 against 405 ms on one thread, and its subtrees build on rayon's
//!   workers) and takes half the memory (32-byte nodes, no one-face leaves; on the 2-core
//!   machines writing fresh memory costs about 0.6 ms per MB, much of a build). A cut's broad
//!   phase is no slower on it (the peerbench strip on the 2M sphere: 0.56 against 0.75 ms, best
//!   of 300). Box queries answer the same sets
//!   (a face is reported when its own box passes the test), so the tree's shape changes only the
//!   order of [`SpatialIndex::faces_in_box`]'s answer and the time queries take.
//!
//! Queries take the same `&Mesh` the index was built from (its triangle count is checked in debug
//! builds); the index stores no copy of the geometry, only the tree and the faces' boxes.
//!
//! Ray casting uses the watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013) in
//! `f64`: a ray through a shared edge or vertex hits at least one of the triangles around it,
//! which parity counts and "pick the surface under the mouse" rely on. Closest-point queries are a
//! depth-first traversal that visits the nearer child first and prunes boxes farther than the best
//! point found, with the closest point on a triangle from Ericson (Real-Time Collision Detection,
//! 5.1.5), made safe for degenerate triangles.
//!
//! Coordinates beyond the `f32` range (about 3.4e38) are clamped there, and triangles out there may
//! be missed.

use std::fmt;

use glam::DVec3;

use crate::aabb::Aabb;
use crate::mesh::Mesh;

/// A ray's first hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Triangle index in the mesh.
    pub face: u32,
    /// Ray parameter: the hit is `origin + t * direction`.
    pub t: f64,
    /// Barycentric weights of the triangle's corners 0, 1, 2 (sum 1).
    pub bary: DVec3,
    /// The hit point.
    pub point: DVec3,
}

/// The point of the surface closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    /// Triangle index in the mesh.
    pub face: u32,
    /// The closest point (on triangle `face`, up to rounding).
    pub point: DVec3,
    /// Barycentric weights of the triangle's corners 0, 1, 2 (each in `0..=1`, sum 1).
    pub bary: DVec3,
    /// Distance from the query point to `point`.
    pub distance: f64,
}

/// Most faces in one leaf. Small leaves keep the per-face box tests few; fewer, larger leaves
/// mean fewer nodes to build and to write.
pub const LEAF_SIZE: usize = 4;

/// Bits per axis of the Morton codes that order the faces.
const MORTON_BITS: u32 = 10;

/// Ranges of at least this many faces are split on two rayon workers.
const PARALLEL_RANGE: usize = 1 << 15;

/// An axis-aligned box in `f32` (min corner, max corner).
#[derive(Clone, Copy, Debug, PartialEq)]
struct FBox {
    min: [f32; 3],
    max: [f32; 3],
}

impl FBox {
    /// The union of two boxes.
    #[inline]
    fn union(&self, o: &FBox) -> FBox {
        FBox {
            min: std::array::from_fn(|k| self.min[k].min(o.min[k])),
            max: std::array::from_fn(|k| self.max[k].max(o.max[k])),
        }
    }

    /// The box in `f64` (exact conversion).
    #[inline(always)]
    fn to_f64(self) -> (DVec3, DVec3) {
        (
            DVec3::new(self.min[0] as f64, self.min[1] as f64, self.min[2] as f64),
            DVec3::new(self.max[0] as f64, self.max[1] as f64, self.max[2] as f64),
        )
    }

    /// The box in `f64`, widened by `slack`.
    #[inline(always)]
    fn widened(self, slack: f64) -> (DVec3, DVec3) {
        let (min, max) = self.to_f64();
        (min - DVec3::splat(slack), max + DVec3::splat(slack))
    }

    /// The `f64` box `[min, max]` rounded outward to `f32`.
    #[inline]
    fn outward(min: DVec3, max: DVec3) -> FBox {
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
struct Node {
    bounds: FBox,
    first: u32,
    count: u32,
}

impl Node {
    #[inline(always)]
    fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The slots of a leaf's faces.
    #[inline(always)]
    fn slots(&self) -> std::ops::Range<usize> {
        self.first as usize..(self.first + self.count) as usize
    }
}

/// A BVH over the triangles of one mesh.
#[derive(Clone)]
pub struct SpatialIndex {
    /// The tree; node 0 is the root. Empty (no node) for a mesh without triangles. Every node's
    /// box contains its children's boxes, and a leaf's box its faces' boxes.
    nodes: Vec<Node>,
    /// Mesh face ids in leaf order (each face exactly once); a leaf holds a contiguous run.
    faces: Vec<u32>,
    /// Per mesh face (indexed by face id): its `f64` box rounded outward to `f32`.
    face_boxes: Vec<FBox>,
    /// Number of triangles of the mesh the index was built from.
    triangle_count: usize,
    /// Absolute widening of node boxes during traversal, covering the rounding of `f64`
    /// arithmetic on coordinates of the mesh's magnitude (a few ulps of its largest coordinate).
    slack: f64,
}

impl fmt::Debug for SpatialIndex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SpatialIndex")
            .field("triangle_count", &self.triangle_count)
            .field("nodes", &self.nodes.len())
            .field("slack", &self.slack)
            .finish()
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

/// Squared distance from `p` to the box `[min, max]` (0 inside).
#[inline(always)]
fn box_distance_squared(p: DVec3, (min, max): (DVec3, DVec3)) -> f64 {
    let d = (min - p).max(p - max).max(DVec3::ZERO);
    d.length_squared()
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

    /// Number of triangles indexed.
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// First hit of the ray `origin + t * direction`, `0 <= t <= t_max` (both faces of a triangle hit).
    ///
    /// Watertight: a ray through a shared edge or vertex hits one of the triangles there. A ray
    /// lying in a triangle's plane does not hit it. Of several hits at the same `t`, the lowest
    /// face index wins. Returns `None` for a zero or non-finite direction.
    pub fn ray_cast(
        &self,
        mesh: &Mesh,
        origin: DVec3,
        direction: DVec3,
        t_max: f64,
    ) -> Option<RayHit> {
        debug_assert_eq!(
            mesh.triangles.len(),
            self.triangle_count,
            "index of another mesh"
        );
        let ray = WatertightRay::new(origin, direction)?;
        if self.nodes.is_empty() || t_max.is_nan() || t_max < 0.0 {
            return None;
        }
        let inv = DVec3::ONE / direction;
        // Relative widening of slab parameters: two roundings each, compared across axes.
        let widen = 1.0 + 4.0 * f64::EPSILON;
        // Entry parameter of the ray into a box, None when it misses the box or the box lies
        // behind the origin.
        let enter_box = |(min, max): (DVec3, DVec3)| -> Option<f64> {
            let mut near = 0.0f64;
            let mut far = f64::INFINITY;
            for axis in 0..3 {
                if direction[axis] == 0.0 {
                    if origin[axis] < min[axis] || origin[axis] > max[axis] {
                        return None;
                    }
                    continue;
                }
                let t0 = (min[axis] - origin[axis]) * inv[axis];
                let t1 = (max[axis] - origin[axis]) * inv[axis];
                near = near.max(t0.min(t1));
                far = far.min(t0.max(t1));
            }
            (near <= far * widen).then_some(near)
        };
        let enter = |node: &Node| enter_box(node.bounds.widened(self.slack));

        let mut best: Option<RayHit> = None;
        let mut best_t = t_max;
        // (node, entry parameter); entries are re-checked when popped, as `best_t` shrinks.
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        if let Some(t) = enter(&self.nodes[0]) {
            stack.push((0, t));
        }
        while let Some((index, t_enter)) = stack.pop() {
            if t_enter > best_t * widen {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.is_leaf() {
                // Tested against `t_max`, not `best_t`, so that ties are decided by face index
                // on the computed `t` whatever order the tree visits them in.
                for slot in node.slots() {
                    let face = self.faces[slot];
                    let Some(t) = enter_box(self.face_boxes[face as usize].widened(self.slack))
                    else {
                        continue;
                    };
                    if t > best_t * widen {
                        continue;
                    }
                    if let Some(hit) = ray.intersect(mesh, face, t_max) {
                        let better = match best {
                            None => true,
                            Some(b) => hit.t < b.t || (hit.t == b.t && face < b.face),
                        };
                        if better {
                            best_t = hit.t;
                            best = Some(hit);
                        }
                    }
                }
                continue;
            }
            let limit = best_t * widen;
            let (l, r) = (node.first, node.first + 1);
            let hits = [l, r].map(|child| {
                enter(&self.nodes[child as usize])
                    .filter(|&t| t <= limit)
                    .map(|t| (child, t))
            });
            // Push the farther child first so the nearer one is visited first.
            match hits {
                [Some(a), Some(b)] => {
                    let (near, far) = if a.1 <= b.1 { (a, b) } else { (b, a) };
                    stack.push(far);
                    stack.push(near);
                }
                [Some(only), None] | [None, Some(only)] => stack.push(only),
                [None, None] => {}
            }
        }
        best
    }

    /// Appends to `out` every triangle whose bounding box overlaps `aabb` (inclusive; may include
    /// triangles whose box overlaps but the triangle itself does not).
    ///
    /// Conservative: every triangle whose exact `f64` box overlaps `aabb` is reported; a triangle
    /// whose box misses `aabb` by less than an `f32` ulp may be reported too. Order is the tree's.
    pub fn faces_in_box(&self, aabb: &Aabb, out: &mut Vec<u32>) {
        if aabb.is_empty() {
            return;
        }
        self.faces_where(
            |min, max| min.cmple(aabb.max).all() && aabb.min.cmple(max).all(),
            out,
        );
    }

    /// Appends to `out` every face whose own box passes `enter`, descending only into nodes whose
    /// box passes it (`min`, `max`: the `f32` box converted exactly to `f64`, not widened), so
    /// `enter` must pass every box that contains a box it passes (as box overlap does).
    /// [`SpatialIndex::faces_in_box`] is this with a box-overlap test; the boolean also prunes
    /// by the cutter face's plane. Order is the tree's.
    pub fn faces_where(&self, mut enter: impl FnMut(DVec3, DVec3) -> bool, out: &mut Vec<u32>) {
        let mut test = |b: &FBox| {
            let (min, max) = b.to_f64();
            enter(min, max)
        };
        if self.nodes.is_empty() || !test(&self.nodes[0].bounds) {
            return;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = &self.nodes[index as usize];
            if node.is_leaf() {
                for &face in &self.faces[node.slots()] {
                    if test(&self.face_boxes[face as usize]) {
                        out.push(face);
                    }
                }
                continue;
            }
            for child in [node.first, node.first + 1] {
                if test(&self.nodes[child as usize].bounds) {
                    stack.push(child);
                }
            }
        }
    }

    /// Closest surface point to `p` (None for an empty mesh).
    ///
    /// Of several faces at the same distance, the lowest face index wins.
    pub fn closest_point(&self, mesh: &Mesh, p: DVec3) -> Option<ClosestPoint> {
        self.closest_point_within(mesh, p, f64::INFINITY)
    }

    /// Closest surface point to `p` if it is at most `max_distance` away (None otherwise, or for
    /// an empty mesh, or a non-finite `p`). A small `max_distance` prunes most of the tree, so
    /// "is there surface near here" queries are cheaper than [`SpatialIndex::closest_point`].
    pub fn closest_point_within(
        &self,
        mesh: &Mesh,
        p: DVec3,
        max_distance: f64,
    ) -> Option<ClosestPoint> {
        debug_assert_eq!(
            mesh.triangles.len(),
            self.triangle_count,
            "index of another mesh"
        );
        if self.nodes.is_empty() || !p.is_finite() || max_distance.is_nan() || max_distance < 0.0 {
            return None;
        }
        // Relative widening for pruning on squared distances.
        let widen = 1.0 + 8.0 * f64::EPSILON;
        let mut best: Option<(u32, DVec3, DVec3)> = None;
        let mut best_d2 = max_distance * max_distance;
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        let root_d2 = box_distance_squared(p, self.nodes[0].bounds.widened(self.slack));
        if root_d2 <= best_d2 * widen {
            stack.push((0, root_d2));
        }
        while let Some((index, d2)) = stack.pop() {
            if d2 > best_d2 * widen {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.is_leaf() {
                for &face in &self.faces[node.slots()] {
                    let b = self.face_boxes[face as usize];
                    if box_distance_squared(p, b.widened(self.slack)) > best_d2 * widen {
                        continue;
                    }
                    let [a, b, c] = mesh.corners(face as usize);
                    let (q, bary) = closest_on_triangle(p, a, b, c);
                    let e2 = (p - q).length_squared();
                    let better = match best {
                        None => e2 <= best_d2,
                        Some((f, _, _)) => e2 < best_d2 || (e2 == best_d2 && face < f),
                    };
                    if better {
                        best_d2 = e2;
                        best = Some((face, q, bary));
                    }
                }
                continue;
            }
            let (l, r) = (node.first, node.first + 1);
            let dl = box_distance_squared(p, self.nodes[l as usize].bounds.widened(self.slack));
            let dr = box_distance_squared(p, self.nodes[r as usize].bounds.widened(self.slack));
            let limit = best_d2 * widen;
            let (first, d_first, second, d_second) = if dl <= dr {
                (l, dl, r, dr)
            } else {
                (r, dr, l, dl)
            };
            if d_second <= limit {
                stack.push((second, d_second));
            }
            if d_first <= limit {
                stack.push((first, d_first));
            }
        }
        best.map(|(face, point, bary)| ClosestPoint {
            face,
            point,
            bary,
            distance: best_d2.sqrt(),
        })
    }

    /// Checks the index against `mesh`: built for its triangle count, every face in exactly one
    /// leaf, leaves of 1 to [`LEAF_SIZE`] faces, every face's box containing its `f64` corners
    /// and every node box containing its children's (or its faces') boxes.
    pub fn sanity_check(&self, mesh: &Mesh) -> Result<(), String> {
        let SpatialIndex {
            nodes,
            faces,
            face_boxes,
            triangle_count,
            slack,
        } = self;
        if *triangle_count != mesh.triangles.len() {
            return Err(format!(
                "index built for {triangle_count} triangles, mesh has {}",
                mesh.triangles.len()
            ));
        }
        if !(slack.is_finite() && *slack >= 0.0) {
            return Err(format!("slack {slack} is not a finite non-negative number"));
        }
        if faces.len() != *triangle_count || face_boxes.len() != *triangle_count {
            return Err(format!(
                "{} face slots and {} boxes for {triangle_count} triangles",
                faces.len(),
                face_boxes.len()
            ));
        }
        if nodes.is_empty() {
            return if *triangle_count == 0 {
                Ok(())
            } else {
                Err("no tree for a non-empty mesh".into())
            };
        }
        let contains = |outer: &FBox, p: DVec3| {
            let (min, max) = outer.to_f64();
            min.cmple(p).all() && p.cmple(max).all()
        };
        let contains_box = |outer: &FBox, inner: &FBox| {
            let (min, max) = inner.to_f64();
            contains(outer, min) && contains(outer, max)
        };
        let mut seen = vec![false; *triangle_count];
        let mut stack = vec![0u32];
        while let Some(index) = stack.pop() {
            let node = nodes
                .get(index as usize)
                .ok_or_else(|| format!("node {index} out of range"))?;
            if node.is_leaf() {
                if node.count as usize > LEAF_SIZE {
                    return Err(format!("leaf {index} holds {} faces", node.count));
                }
                for slot in node.slots() {
                    let Some(&face) = faces.get(slot) else {
                        return Err(format!("leaf {index} slot {slot} out of range"));
                    };
                    let Some(b) = face_boxes.get(face as usize) else {
                        return Err(format!("leaf {index} names face {face}"));
                    };
                    let seen_slot = seen
                        .get_mut(face as usize)
                        .ok_or_else(|| format!("leaf {index} names face {face}"))?;
                    if std::mem::replace(seen_slot, true) {
                        return Err(format!("face {face} is in two leaves"));
                    }
                    if !mesh.corners(face as usize).iter().all(|&c| contains(b, c)) {
                        return Err(format!("the box of face {face} does not contain it"));
                    }
                    if !contains_box(&node.bounds, b) {
                        return Err(format!("leaf {index} box does not contain face {face}"));
                    }
                }
                continue;
            }
            for child in [node.first, node.first + 1] {
                if child <= index {
                    return Err(format!("child {child} of node {index} comes before it"));
                }
                let c = nodes
                    .get(child as usize)
                    .ok_or_else(|| format!("child {child} of node {index} out of range"))?;
                if !contains_box(&node.bounds, &c.bounds) {
                    return Err(format!("node {index} does not contain child {child}"));
                }
                stack.push(child);
            }
        }
        match seen.iter().position(|s| !s) {
            Some(face) => Err(format!("face {face} is in no leaf")),
            None => Ok(()),
        }
    }
}

/// A ray prepared for the watertight test: the axis of largest direction becomes "z" and the
/// ray is sheared to run along it, so each triangle edge is tested by a 2D edge function that is
/// computed identically (up to sign) for both triangles sharing it.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    origin: DVec3,
    direction: DVec3,
    /// Permuted axes: `kz` is the dominant direction axis; `kx`, `ky` keep the winding.
    kx: usize,
    ky: usize,
    kz: usize,
    /// Shear constants.
    shear: DVec3,
}

impl WatertightRay {
    /// Prepares the ray; None for a zero or non-finite direction or a non-finite origin.
    pub fn new(origin: DVec3, direction: DVec3) -> Option<WatertightRay> {
        if !origin.is_finite() || !direction.is_finite() || direction == DVec3::ZERO {
            return None;
        }
        let abs = direction.abs();
        let kz = if abs.x >= abs.y && abs.x >= abs.z {
            0
        } else if abs.y >= abs.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if direction[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let shear = DVec3::new(
            direction[kx] / direction[kz],
            direction[ky] / direction[kz],
            1.0 / direction[kz],
        );
        Some(WatertightRay {
            origin,
            direction,
            kx,
            ky,
            kz,
            shear,
        })
    }

    /// Hit of triangle `face` of `mesh` with `0 <= t <= t_max`, either side.
    pub fn intersect(&self, mesh: &Mesh, face: u32, t_max: f64) -> Option<RayHit> {
        let corners = mesh.corners(face as usize);
        let [a, b, c] = corners.map(|v| v - self.origin);
        let (kx, ky, kz, s) = (self.kx, self.ky, self.kz, self.shear);
        let ax = a[kx] - s.x * a[kz];
        let ay = a[ky] - s.y * a[kz];
        let bx = b[kx] - s.x * b[kz];
        let by = b[ky] - s.y * b[kz];
        let cx = c[kx] - s.x * c[kz];
        let cy = c[ky] - s.y * c[kz];
        // Edge functions; u belongs to corner 0 (edge b-c), v to corner 1, w to corner 2.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let (az, bz, cz) = (s.z * a[kz], s.z * b[kz], s.z * c[kz]);
        let t_scaled = u * az + v * bz + w * cz;
        // t = t_scaled / det must lie in [0, t_max]; compare without dividing.
        let (t_scaled, det_abs) = if det < 0.0 {
            (-t_scaled, -det)
        } else {
            (t_scaled, det)
        };
        if t_scaled < 0.0 || t_scaled > t_max * det_abs {
            return None;
        }
        let inv = 1.0 / det;
        let bary = DVec3::new(u * inv, v * inv, w * inv);
        let t = (t_scaled / det_abs).min(t_max);
        Some(RayHit {
            face,
            t,
            bary,
            point: self.origin + self.direction * t,
        })
    }
}

/// Closest point to `p` on triangle `abc` and its barycentric weights. Safe for degenerate
/// triangles (collinear or coincident corners): they fall back to the nearest of their sides.
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, DVec3) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, DVec3::X);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, DVec3::Y);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = ratio(d1, d1 - d3);
        return (a + ab * v, DVec3::new(1.0 - v, v, 0.0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, DVec3::Z);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = ratio(d2, d2 - d6);
        return (a + ac * w, DVec3::new(1.0 - w, 0.0, w));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, DVec3::new(0.0, 1.0 - w, w));
    }
    let denom = va + vb + vc;
    if denom > 0.0 {
        let v = vb / denom;
        let w = vc / denom;
        let q = a + ab * v + ac * w;
        if q.is_finite() && v >= 0.0 && w >= 0.0 && v + w <= 1.0 {
            return (q, DVec3::new(1.0 - v - w, v, w));
        }
    }
    // Degenerate (or rounding put us nowhere): the nearest point on the three sides.
    let sides = [
        closest_on_segment(p, a, b),
        closest_on_segment(p, b, c),
        closest_on_segment(p, c, a),
    ];
    let mut best = 0;
    for k in 1..3 {
        if (p - sides[k].0).length_squared() < (p - sides[best].0).length_squared() {
            best = k;
        }
    }
    let (q, s) = sides[best];
    let mut bary = DVec3::ZERO;
    bary[best] = 1.0 - s;
    bary[(best + 1) % 3] += s;
    (q, bary)
}

/// `n / d` clamped to `0..=1`, 0 when `d` is not positive.
fn ratio(n: f64, d: f64) -> f64 {
    if d > 0.0 {
        (n / d).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point on segment `ab` to `p` and its parameter in `0..=1`.
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (DVec3, f64) {
    let ab = b - a;
    let s = ratio((p - a).dot(ab), ab.length_squared());
    (a + ab * s, s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    #[test]
    fn empty_and_single() {
        let empty = Mesh::default();
        let index = SpatialIndex::build(&empty);
        index.sanity_check(&empty).unwrap();
        assert_eq!(index.closest_point(&empty, DVec3::ZERO), None);
        assert_eq!(index.ray_cast(&empty, DVec3::ZERO, DVec3::X, 1.0), None);
        let mut out = vec![];
        index.faces_in_box(
            &Aabb {
                min: DVec3::splat(-1.0),
                max: DVec3::ONE,
            },
            &mut out,
        );
        assert!(out.is_empty());

        let tri = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let index = SpatialIndex::build(&tri);
        index.sanity_check(&tri).unwrap();
        let hit = index
            .ray_cast(&tri, DVec3::new(0.25, 0.25, 1.0), DVec3::NEG_Z, 10.0)
            .unwrap();
        assert_eq!((hit.face, hit.t), (0, 1.0));
        assert_eq!(hit.bary, DVec3::new(0.5, 0.25, 0.25));
        assert_eq!(hit.point, DVec3::new(0.25, 0.25, 0.0));
        // From below too (both sides), and not beyond t_max.
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 10.0)
                .is_some()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 0.5)
                .is_none()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::NEG_Z, 10.0)
                .is_none()
        );
        assert!(
            index
                .ray_cast(&tri, DVec3::ZERO, DVec3::ZERO, 10.0)
                .is_none()
        );
        let cp = index
            .closest_point(&tri, DVec3::new(2.0, 2.0, 3.0))
            .unwrap();
        assert_eq!(cp.point, DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(cp.bary, DVec3::new(0.0, 0.5, 0.5));
        assert!(
            index
                .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.6)
                .is_none()
        );
        assert!(
            index
                .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.7)
                .is_some()
        );
    }

    /// Queries on a tree big enough for the parallel build (several workers' subtrees), with a
    /// pile of identical faces (one Morton code: split in the middle), answer exactly what a
    /// scan of every face answers.
    #[test]
    fn queries_match_brute_force_on_a_large_tree() {
        let mut m = testkit::geodesic_sphere(60, 5.0);
        assert!(m.triangles.len() >= 2 * PARALLEL_RANGE);
        let v = m.positions.len() as u32;
        m.positions.extend([
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.1, 0.3, 0.3),
            DVec3::new(0.1, 0.2, 0.4),
        ]);
        m.triangles
            .extend(std::iter::repeat_n([v, v + 1, v + 2], 3 * LEAF_SIZE + 1));
        let index = SpatialIndex::build(&m);
        index.sanity_check(&m).unwrap();
        let boxes: Vec<(DVec3, DVec3)> = (0..m.triangles.len())
            .map(|t| {
                let [a, b, c] = m.corners(t);
                FBox::outward(a.min(b).min(c), a.max(b).max(c)).to_f64()
            })
            .collect();
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..40 {
            let c = DVec3::new(next(), next(), next()) * 6.0;
            let h = DVec3::new(next(), next(), next()).abs() * 0.5;
            let query = Aabb {
                min: c - h,
                max: c + h,
            };
            let mut got = Vec::new();
            index.faces_in_box(&query, &mut got);
            got.sort_unstable();
            let want: Vec<u32> = (0..m.triangles.len() as u32)
                .filter(|&t| {
                    let (min, max) = boxes[t as usize];
                    min.cmple(query.max).all() && query.min.cmple(max).all()
                })
                .collect();
            assert_eq!(got, want);
            let origin = DVec3::new(next(), next(), next()) * 8.0;
            let direction = DVec3::new(next(), next(), next());
            let ray = WatertightRay::new(origin, direction).unwrap();
            let mut want_hit: Option<RayHit> = None;
            for t in 0..m.triangles.len() as u32 {
                if let Some(hit) = ray.intersect(&m, t, f64::INFINITY)
                    && want_hit.is_none_or(|b| hit.t < b.t)
                {
                    want_hit = Some(hit);
                }
            }
            let got_hit = index.ray_cast(&m, origin, direction, f64::INFINITY);
            assert_eq!(got_hit, want_hit);
            let p = DVec3::new(next(), next(), next()) * 7.0;
            let mut want_cp: Option<(f64, u32)> = None;
            for t in 0..m.triangles.len() {
                let [a, b, c] = m.corners(t);
                let d2 = (p - closest_on_triangle(p, a, b, c).0).length_squared();
                if want_cp.is_none_or(|(best, _)| d2 < best) {
                    want_cp = Some((d2, t as u32));
                }
            }
            let got_cp = index.closest_point(&m, p).unwrap();
            assert_eq!(Some(got_cp.face), want_cp.map(|(_, face)| face));
        }
    }

    #[test]
    fn rays_through_shared_edges_and_vertices_hit() {
        // Axis rays through every vertex and edge midpoint of an axis-aligned cube must hit.
        let m = testkit::cube(DVec3::splat(-1.0), DVec3::ONE);
        let index = SpatialIndex::build(&m);
        index.sanity_check(&m).unwrap();
        for x in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            for y in [-1.0, -0.5, 0.0, 0.5, 1.0] {
                let hit = index.ray_cast(&m, DVec3::new(x, y, 5.0), DVec3::NEG_Z, 100.0);
                let hit = hit.unwrap_or_else(|| panic!("ray at ({x}, {y}) missed"));
                assert_eq!(hit.t, 4.0);
            }
        }
    }

    #[test]
    fn degenerate_triangles_closest_point() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
        let (q, bary) = closest_on_triangle(DVec3::new(1.5, 1.0, 0.0), a, b, c);
        assert_eq!(q, DVec3::new(1.5, 0.0, 0.0));
        assert!((bary.x + bary.y + bary.z - 1.0).abs() < 1e-15);
        assert_eq!(a * bary.x + b * bary.y + c * bary.z, q);
        let (q, _) = closest_on_triangle(DVec3::ONE, a, a, a);
        assert_eq!(q, a);
    }

    #[test]
    fn icosphere_queries() {
        let m = testkit::icosphere(3, 2.0);
        let index = SpatialIndex::build(&m);
        index.sanity_check(&m).unwrap();
        let hit = index
            .ray_cast(&m, DVec3::new(0.0, 0.0, -10.0), DVec3::Z, f64::INFINITY)
            .unwrap();
        assert!((hit.t - 8.0).abs() < 0.05 && hit.point.z < 0.0);
        let cp = index.closest_point(&m, DVec3::new(0.0, 0.0, 0.1)).unwrap();
        assert!((cp.distance - 1.9).abs() < 0.05);
        let mut out = vec![];
        index.faces_in_box(&m.bbox(), &mut out);
        out.sort_unstable();
        assert_eq!(out, (0..m.triangle_count() as u32).collect::<Vec<_>>());
    }
}
