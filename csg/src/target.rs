//! The cached target: everything about a target mesh that does not depend on the cutter.
//!
//! Built once per model ([`TargetIndex::build`], O(N log N)) and reused by every cut, so that a
//! cut only ever touches what the cutter overlaps. It holds the mesh itself, its edge adjacency
//! and regions (from the mesh core), per-region closedness and bounding boxes, the integer
//! lattice coordinates of every vertex (see [`crate::lattice`]) and a bounding-volume hierarchy
//! over the triangles in lattice coordinates.
//!
//! The broad phase queries the core's [`SpatialIndex`] (`obvhs`, conservative `f32` boxes) with
//! the query box widened by two lattice steps, then keeps only the faces whose exact integer box
//! overlaps the query: no pair can be missed by rounding, and no extra pair survives. The small
//! integer [`Bvh`] here serves the cutter (its self-intersection check).

use std::sync::Arc;

use crate::aabb::Aabb;
use crate::adjacency::EdgeAdjacency;
use crate::exact::LPoint;
use crate::lattice::Lattice;
use crate::mesh::{Mesh, MeshError};
use crate::regions::Regions;
use crate::spatial::SpatialIndex;

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
        (0..3).all(|k| self.min[k] <= o.max[k] && o.min[k] <= self.max[k])
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

/// Per-cut scratch indexed by face and by vertex. Entries are valid only when their stamp equals
/// the current epoch, so a cut never clears (or allocates) anything of the target's size.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    epoch: u32,
    face_stamp: Vec<u32>,
    face_value: Vec<u32>,
    vertex_stamp: Vec<u32>,
    vertex_value: Vec<u32>,
}

impl Scratch {
    /// Starts a cut on a target of `faces` faces and `vertices` vertices.
    pub fn begin(&mut self, faces: usize, vertices: usize) {
        if self.face_stamp.len() != faces || self.vertex_stamp.len() != vertices {
            *self = Scratch {
                epoch: 0,
                face_stamp: vec![0; faces],
                face_value: vec![0; faces],
                vertex_stamp: vec![0; vertices],
                vertex_value: vec![0; vertices],
            };
        }
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            // Once every 2^32 cuts.
            self.face_stamp.fill(0);
            self.vertex_stamp.fill(0);
            self.epoch = 1;
        }
    }

    #[inline]
    pub fn face(&self, t: u32) -> Option<u32> {
        (self.face_stamp[t as usize] == self.epoch).then(|| self.face_value[t as usize])
    }

    #[inline]
    pub fn set_face(&mut self, t: u32, value: u32) {
        self.face_stamp[t as usize] = self.epoch;
        self.face_value[t as usize] = value;
    }

    #[inline]
    pub fn vertex(&self, v: u32) -> Option<u32> {
        (self.vertex_stamp[v as usize] == self.epoch).then(|| self.vertex_value[v as usize])
    }

    #[inline]
    pub fn set_vertex(&mut self, v: u32, value: u32) {
        self.vertex_stamp[v as usize] = self.epoch;
        self.vertex_value[v as usize] = value;
    }
}

/// The scratch of a [`TargetIndex`]: one per index, used by one cut at a time (a concurrent cut
/// on the same index uses its own). Cloning an index gives the clone a fresh scratch.
#[derive(Debug, Default)]
pub(crate) struct ScratchCell(pub std::sync::Mutex<Scratch>);

impl Clone for ScratchCell {
    fn clone(&self) -> Self {
        ScratchCell::default()
    }
}

/// The cached, cutter-independent part of a target (see the module doc).
#[derive(Clone, Debug)]
pub struct TargetIndex {
    /// The target mesh (shared, never modified by a cut).
    pub mesh: Arc<Mesh>,
    /// Edge → faces adjacency of `mesh`.
    pub adjacency: EdgeAdjacency,
    /// Connected regions of `mesh`.
    pub regions: Regions,
    /// Per region: every edge of the region has exactly two faces. Indexed by region id.
    pub region_closed: Vec<bool>,
    /// Per region: lattice bounding box. Indexed by region id.
    pub region_boxes: Vec<IBox>,
    /// Per region: one of its triangles (the first). Indexed by region id.
    pub region_first_face: Vec<u32>,
    /// The lattice every predicate of a cut on this target uses.
    pub lattice: Lattice,
    /// Lattice coordinates of every vertex; same length as `mesh.positions`.
    pub lpoints: Vec<LPoint>,
    /// Lattice box of the whole target.
    pub bounds: IBox,
    /// Spatial index over the faces (world coordinates, conservative).
    pub spatial: SpatialIndex,
    /// Per face: its lattice box (the BVH leaves' contents). Same length as `mesh.triangles`.
    pub face_boxes: Vec<IBox>,
    /// Reusable per-cut scratch (epoch-stamped).
    pub(crate) scratch: ScratchCell,
}

impl TargetIndex {
    /// Builds the index of `mesh` (checked with [`Mesh::sanity_check`] first).
    pub fn build(mesh: impl Into<Arc<Mesh>>) -> Result<TargetIndex, MeshError> {
        let mesh: Arc<Mesh> = mesh.into();
        mesh.sanity_check()?;
        let bbox: Aabb = Aabb::from_points(&mesh.positions);
        let lattice = Lattice::for_box(&bbox);
        // Inside the box every point quantizes (the box spans a quarter of the lattice range).
        let lpoints: Vec<LPoint> = mesh
            .positions
            .iter()
            .map(|&p| lattice.quantize(p).unwrap_or([0, 0, 0]))
            .collect();
        let ((adjacency, regions), (face_boxes, spatial)) = rayon::join(
            || {
                let adjacency = EdgeAdjacency::build(&mesh);
                let regions = Regions::build(&mesh, &adjacency);
                (adjacency, regions)
            },
            || {
                rayon::join(
                    || {
                        mesh.triangles
                            .iter()
                            .map(|t| {
                                IBox::of_triangle([
                                    &lpoints[t[0] as usize],
                                    &lpoints[t[1] as usize],
                                    &lpoints[t[2] as usize],
                                ])
                            })
                            .collect::<Vec<_>>()
                    },
                    || SpatialIndex::build(&mesh),
                )
            },
        );
        let mut region_closed = vec![true; regions.count];
        for e in 0..adjacency.edge_count() as u32 {
            let faces = adjacency.faces_of_edge(e);
            if faces.len() != 2 {
                for &f in faces {
                    region_closed[regions.region_of_triangle[f as usize] as usize] = false;
                }
            }
        }
        let mut region_boxes = vec![IBox::EMPTY; regions.count];
        let mut region_first_face = vec![u32::MAX; regions.count];
        let mut bounds = IBox::EMPTY;
        for (t, b) in face_boxes.iter().enumerate() {
            let r = regions.region_of_triangle[t] as usize;
            region_boxes[r] = region_boxes[r].union(b);
            if region_first_face[r] == u32::MAX {
                region_first_face[r] = t as u32;
            }
            bounds = bounds.union(b);
        }
        Ok(TargetIndex {
            mesh,
            adjacency,
            regions,
            region_closed,
            region_boxes,
            region_first_face,
            lattice,
            lpoints,
            bounds,
            spatial,
            face_boxes,
            scratch: ScratchCell::default(),
        })
    }

    /// The target mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Calls `visit` for every face whose exact lattice box overlaps `query` (inclusive).
    pub fn faces_in_box(&self, query: &IBox, mut visit: impl FnMut(u32)) {
        let widen = |p: &LPoint, d: i64| [(p[0] + d) as f64, (p[1] + d) as f64, (p[2] + d) as f64];
        let aabb = Aabb {
            min: self.lattice.to_world(widen(&query.min, -2)),
            max: self.lattice.to_world(widen(&query.max, 2)),
        };
        let mut found = Vec::new();
        self.spatial.faces_in_box(&aabb, &mut found);
        for f in found {
            if self.face_boxes[f as usize].overlaps(query) {
                visit(f);
            }
        }
    }

    /// True when every region is closed (every edge has exactly two faces).
    pub fn is_closed(&self) -> bool {
        self.region_closed.iter().all(|&c| c)
    }

    /// Lattice corners of face `t`.
    #[inline]
    pub fn face_points(&self, t: u32) -> [&LPoint; 3] {
        let tri = &self.mesh.triangles[t as usize];
        [
            &self.lpoints[tri[0] as usize],
            &self.lpoints[tri[1] as usize],
            &self.lpoints[tri[2] as usize],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    #[test]
    fn bvh_query_matches_brute_force() {
        let mesh = testkit::icosphere(3, 10.0);
        let index = TargetIndex::build(mesh).unwrap();
        let q = IBox {
            min: [-1 << 24, -1 << 22, 0],
            max: [1 << 23, 1 << 24, 1 << 25],
        };
        let mut got = Vec::new();
        index.faces_in_box(&q, |f| got.push(f));
        got.sort_unstable();
        let want: Vec<u32> = (0..index.face_boxes.len() as u32)
            .filter(|&f| index.face_boxes[f as usize].overlaps(&q))
            .collect();
        assert!(!want.is_empty());
        assert_eq!(got, want);
        assert!(index.is_closed());
        assert_eq!(index.regions.count, 1);
    }
}
