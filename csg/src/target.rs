//! The cached target: everything about a target mesh that does not depend on the cutter.
//!
//! Built once per model ([`TargetIndex::build`], O(N log N)) and reused by every cut, so that a
//! cut only ever touches what the cutter overlaps. It holds the mesh itself, its edge adjacency
//! and regions (from the mesh core), per-region closedness and bounding boxes, the integer
//! lattice coordinates of every vertex (see [`crate::lattice`]) and the core's
//! [`SpatialIndex`] over the triangles.
//!
//! The broad phase queries the [`SpatialIndex`] (conservative `f32` boxes) with the query box
//! widened by two lattice steps, then keeps only the faces whose exact integer box
//! ([`TargetIndex::face_box`], from the lattice points) overlaps the query: no pair can be missed
//! by rounding, and no extra pair survives. The small integer [`Bvh`] here serves the cutter
//! (its self-intersection check).
//!
//! Building the index of a 2M-triangle target is the "cold" cost of the first cut
//! (`benches/boolean.rs` prints it per phase, from [`TargetIndex::build_timed`]).

use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;

use crate::aabb::Aabb;
use crate::adjacency::EdgeAdjacency;
use crate::cavities::{self, SolidRegions};
use crate::exact::LPoint;
use crate::lattice::Lattice;
use crate::mesh::{Mesh, MeshError};
use crate::regions::Regions;
use crate::spatial::SpatialIndex;
use crate::winding::WindingTree;

pub use crate::lattice_bvh::{Bvh, IBox};
pub(crate) use crate::scratch::{Scratch, ScratchCell};

/// Entry of [`TargetIndex::face_neighbors`]: no face across this side (a boundary edge, or a
/// side whose corners are the same vertex).
pub const NO_NEIGHBOR: u32 = u32::MAX;
/// Entry of [`TargetIndex::face_neighbors`]: a non-manifold edge (three faces or more); its
/// faces are in the adjacency.
pub const MANY_NEIGHBORS: u32 = u32::MAX - 1;

/// Wall time of each phase of [`TargetIndex::build_timed`], in milliseconds. Phases that run
/// side by side on rayon's workers are listed as indented "(task)" entries (each task's own
/// wall time) followed by the wall time of the whole join.
#[derive(Clone, Debug, Default)]
pub struct BuildTimes {
    /// `(phase, ms)` in the order they ran.
    pub phases: Vec<(&'static str, f64)>,
    /// Wall time of the whole build.
    pub total_ms: f64,
}

impl BuildTimes {
    fn push(&mut self, phase: &'static str, ms: f64) {
        self.phases.push((phase, ms));
    }

    fn lap(&mut self, phase: &'static str, since: &mut Instant) {
        let now = Instant::now();
        self.push(phase, (now - *since).as_secs_f64() * 1e3);
        *since = now;
    }
}

impl std::fmt::Display for BuildTimes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "index build {:.1} ms:", self.total_ms)?;
        for (phase, ms) in &self.phases {
            writeln!(f, "  {phase:<48} {ms:8.1} ms")?;
        }
        Ok(())
    }
}

/// Runs `f`, returning its result and its wall time in milliseconds.
fn timed<R>(f: impl FnOnce() -> R) -> (R, f64) {
    let t = Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64() * 1e3)
}

/// The cached, cutter-independent part of a target (see the module doc).
#[derive(Clone, Debug)]
pub struct TargetIndex {
    /// The target mesh (shared, never modified by a cut).
    pub mesh: Arc<Mesh>,
    /// Edge → faces adjacency of `mesh`.
    pub adjacency: EdgeAdjacency,
    /// Edge-connected components of `mesh` (what the flood fill of a cut spreads over).
    pub components: Regions,
    /// Per component: every edge of the component has exactly two faces.
    pub component_closed: Vec<bool>,
    /// Per component: lattice bounding box.
    pub component_boxes: Vec<IBox>,
    /// Per component: one of its triangles (the first).
    pub component_first_face: Vec<u32>,
    /// The regions (components with their cavities, [`crate::cavities`]): each is cut as its
    /// own solid.
    pub regions: SolidRegions,
    /// The lattice every predicate of a cut on this target uses.
    pub lattice: Lattice,
    /// Lattice coordinates of every vertex; same length as `mesh.positions`.
    pub lpoints: Vec<LPoint>,
    /// Lattice box of the whole target.
    pub bounds: IBox,
    /// Spatial index over the faces (world coordinates, conservative).
    pub spatial: SpatialIndex,
    /// Per face, per side `k` (the edge `adjacency.triangle_edges[t][k]`): the other face of
    /// that edge when it has exactly two, else [`NO_NEIGHBOR`] or [`MANY_NEIGHBORS`]. The flood
    /// fill of a cut reads this instead of the CSR adjacency: one load per face.
    pub face_neighbors: Vec<[u32; 3]>,
    /// Fast winding-number tree of the mesh, built only when some region is open (the walls of
    /// open targets are classified by the generalized winding number; closed ones by exact ray
    /// parity).
    pub winding: Option<WindingTree>,
    /// Reusable per-cut scratch (allocated here).
    pub(crate) scratch: ScratchCell,
}

/// The cutter-independent topology of a target, from one pass over its edges, and its lattice
/// points.
struct Topology {
    lpoints: Vec<LPoint>,
    adjacency: EdgeAdjacency,
    components: Regions,
    component_closed: Vec<bool>,
    component_boxes: Vec<IBox>,
    component_first_face: Vec<u32>,
    face_neighbors: Vec<[u32; 3]>,
    times: Vec<(&'static str, f64)>,
}

/// Builds the edge adjacency of `mesh` and, while it visits each edge once, the face neighbours
/// (see [`TargetIndex::face_neighbors`]), the union-find of the regions (every edge joins its
/// faces, as [`Regions::build`] does) and the faces on edges without exactly two faces (which
/// open their region); then the regions' lattice boxes and first faces from `lpoints`.
fn build_topology(mesh: &Mesh, lattice: &Lattice) -> Topology {
    use rayon::prelude::*;
    let n = mesh.triangles.len();
    let mut times = Vec::new();
    let mut lap = Instant::now();
    let mut face_neighbors = vec![[NO_NEIGHBOR; 3]; n];
    // parent[t] <= t (see `regions::union`).
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut open_faces: Vec<u32> = Vec::new();
    let adjacency = EdgeAdjacency::build_visiting(mesh, |half_edges| {
        let side = |h: u32| ((h / 3) as usize, (h % 3) as usize);
        match *half_edges {
            [h1, h2] => {
                let ((f1, k1), (f2, k2)) = (side(h1), side(h2));
                face_neighbors[f1][k1] = f2 as u32;
                face_neighbors[f2][k2] = f1 as u32;
                crate::regions::union(&mut parent, f1 as u32, f2 as u32);
            }
            [h] => open_faces.push(h / 3),
            _ => {
                let first = half_edges[0] / 3;
                for &h in half_edges {
                    let (f, k) = side(h);
                    face_neighbors[f][k] = MANY_NEIGHBORS;
                    open_faces.push(f as u32);
                    crate::regions::union(&mut parent, first, f as u32);
                }
            }
        }
    });
    let mut t = Instant::now();
    times.push((
        "  adjacency + neighbours + union-find (task)",
        (t - lap).as_secs_f64() * 1e3,
    ));
    lap = t;
    let regions = Regions::from_parents(parent);
    let mut component_closed = vec![true; regions.count];
    for &f in &open_faces {
        component_closed[regions.region_of_triangle[f as usize] as usize] = false;
    }
    t = Instant::now();
    times.push(("  regions (task)", (t - lap).as_secs_f64() * 1e3));
    lap = t;
    // Region ids are numbered in order of first face, so a region's first face is where the
    // count of regions seen so far first passes its id.
    // Quantized here rather than before the spatial index starts: the index does not need the
    // lattice points, and this task has time to spare while the index builds.
    // Inside the box every point quantizes (the box spans a quarter of the lattice range).
    let lpoint_vec: Vec<LPoint> = mesh
        .positions
        .par_iter()
        .with_min_len(1 << 14)
        .map(|&p| lattice.quantize(p).unwrap_or([0, 0, 0]))
        .collect();
    let lpoints = &lpoint_vec[..];
    t = Instant::now();
    times.push(("  quantize (task)", (t - lap).as_secs_f64() * 1e3));
    lap = t;
    let mut component_first_face = Vec::with_capacity(regions.count);
    for (t, &r) in regions.region_of_triangle.iter().enumerate() {
        if r as usize == component_first_face.len() {
            component_first_face.push(t as u32);
        }
    }
    let grow = |mut boxes: Vec<IBox>, t: usize| {
        let b = &mut boxes[regions.region_of_triangle[t] as usize];
        for &v in &mesh.triangles[t] {
            b.grow(&lpoints[v as usize]);
        }
        boxes
    };
    // Per-worker box lists are merged at the end: worth it for a few regions only.
    let component_boxes = if regions.count == 1 {
        // One region: the box of the vertices some face uses. Marking them in a bitmap (in
        // cache) and then scanning `lpoints` in order is much cheaper than gathering three
        // points per face.
        let mut used = vec![0u64; lpoints.len().div_ceil(64)];
        for tri in &mesh.triangles {
            for &v in tri {
                used[v as usize >> 6] |= 1 << (v & 63);
            }
        }
        let bounds = lpoints
            .par_iter()
            .enumerate()
            .with_min_len(1 << 16)
            .filter(|&(v, _)| used[v >> 6] & (1 << (v & 63)) != 0)
            .fold(
                || IBox::EMPTY,
                |mut b, (_, p)| {
                    b.grow(p);
                    b
                },
            )
            .reduce(|| IBox::EMPTY, |a, b| a.union(&b));
        vec![bounds]
    } else if regions.count <= 64 {
        (0..n)
            .into_par_iter()
            .with_min_len(1 << 16)
            .fold(|| vec![IBox::EMPTY; regions.count], grow)
            .reduce(
                || vec![IBox::EMPTY; regions.count],
                |a, b| a.iter().zip(&b).map(|(a, b)| a.union(b)).collect(),
            )
    } else {
        (0..n).fold(vec![IBox::EMPTY; regions.count], grow)
    };
    times.push(("  region boxes (task)", lap.elapsed().as_secs_f64() * 1e3));
    Topology {
        lpoints: lpoint_vec,
        adjacency,
        components: regions,
        component_closed,
        component_boxes,
        component_first_face,
        face_neighbors,
        times,
    }
}

impl TargetIndex {
    /// Builds the index of `mesh` (checked with [`Mesh::sanity_check`] first).
    pub fn build(mesh: impl Into<Arc<Mesh>>) -> Result<TargetIndex, MeshError> {
        Self::build_timed(mesh).map(|(index, _)| index)
    }

    /// [`TargetIndex::build`], also returning how long each phase took (for benchmarks).
    ///
    /// Two tasks run side by side on rayon's workers once the lattice is chosen: the topology
    /// (edge adjacency, with face neighbours, regions and closedness derived in the same pass
    /// over its edges, then the lattice points and the region boxes) and the spatial index (with
    /// the per-cut scratch). On the 2-core machines most of the cost is first-touching fresh
    /// memory (about 0.6 ms per MB), so the index keeps no array it can derive cheaply (face
    /// boxes come from `lpoints`).
    pub fn build_timed(mesh: impl Into<Arc<Mesh>>) -> Result<(TargetIndex, BuildTimes), MeshError> {
        Self::build_in(mesh, &Aabb::EMPTY)
    }

    /// [`TargetIndex::build`] on a lattice that also spans `room`: a cutter anywhere in `room`
    /// then fits it (see [`crate::lattice`]). The lattice step grows with the box, so this is
    /// for a cutter that reaches far beyond a small target, not for every cut.
    pub fn build_with_room(
        mesh: impl Into<Arc<Mesh>>,
        room: &Aabb,
    ) -> Result<TargetIndex, MeshError> {
        Self::build_in(mesh, room).map(|(index, _)| index)
    }

    fn build_in(
        mesh: impl Into<Arc<Mesh>>,
        room: &Aabb,
    ) -> Result<(TargetIndex, BuildTimes), MeshError> {
        let mut times = BuildTimes::default();
        let clock = Instant::now();
        let mesh: Arc<Mesh> = mesh.into();
        let mut lap = Instant::now();
        mesh.sanity_check()?;
        times.lap("sanity_check", &mut lap);
        let bbox: Aabb = Aabb::from_points(&mesh.positions);
        let lattice = Lattice::for_box(&bbox.union(room));
        times.lap("bbox", &mut lap);
        let (topology, ((spatial, t_spatial), (scratch, t_scratch))) = rayon::join(
            || build_topology(&mesh, &lattice),
            || {
                rayon::join(
                    || timed(|| SpatialIndex::build(&mesh)),
                    || timed(|| Scratch::for_faces(mesh.triangles.len())),
                )
            },
        );
        let Topology {
            lpoints,
            adjacency,
            components,
            component_closed,
            component_boxes,
            component_first_face,
            face_neighbors,
            times: topology_times,
        } = topology;
        times.phases.extend(topology_times);
        times.push("  spatial bvh (task)", t_spatial);
        times.push("  scratch (task)", t_scratch);
        times.lap("join (topology | bvh | scratch)", &mut lap);
        // Only open targets need the winding-number tree (walls of closed ones use ray parity).
        let open = component_closed.iter().any(|&closed| !closed);
        let winding = open.then(|| WindingTree::build(&mesh));
        times.lap("winding (open targets only)", &mut lap);
        let bounds = component_boxes
            .iter()
            .fold(IBox::EMPTY, |acc, b| acc.union(b));
        let mut index = TargetIndex {
            mesh,
            adjacency,
            components,
            component_closed,
            component_boxes,
            component_first_face,
            lattice,
            lpoints,
            bounds,
            spatial,
            face_neighbors,
            winding,
            scratch: ScratchCell(std::sync::Mutex::new(scratch)),
            regions: SolidRegions::default(),
        };
        index.regions = cavities::solid_regions(
            &index.mesh,
            &index.lpoints,
            &index.bounds,
            &index.components,
            &index.component_closed,
            &|query, visit| index.faces_in_box(query, visit),
        );
        times.lap("regions (cavities)", &mut lap);
        times.total_ms = clock.elapsed().as_secs_f64() * 1e3;
        Ok((index, times))
    }

    /// Lattice box of face `t`.
    #[inline]
    pub fn face_box(&self, t: u32) -> IBox {
        IBox::of_triangle(self.face_points(t))
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
            if self.face_box(f).overlaps(query) {
                visit(f);
            }
        }
    }

    /// [`TargetIndex::faces_in_box`] for the box `query` of the cutter triangle `tri` (lattice
    /// points), also skipping every subtree whose box lies strictly on one side of the
    /// triangle's plane by more than a lattice step. A skipped face has all its corners strictly
    /// on one side of the plane, so the broad phase's first exact test would reject it anyway:
    /// the pairs that matter are the same, with far fewer candidates for large slanted cutter
    /// faces. The plane test is in `f64` with a margin that covers its rounding (see below).
    pub fn faces_near_triangle(&self, query: &IBox, tri: [&LPoint; 3], mut visit: impl FnMut(u32)) {
        let f = |p: &LPoint| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
        let (a, b, c) = (f(tri[0]), f(tri[1]), f(tri[2]));
        // Lattice coordinates are below 2^29 in magnitude, so `b - a` and `c - a` are exact
        // (below 2^30) and each normal component is a difference of two products below 2^60,
        // computed with an absolute error below 2^7 + 2^7 + 2^8 = 512 (`NORMAL_ERROR`).
        const NORMAL_ERROR: f64 = 512.0;
        let n = (b - a).cross(c - a);
        let n_abs = n.abs();
        let widen = |p: &LPoint, k: i64| [(p[0] + k) as f64, (p[1] + k) as f64, (p[2] + k) as f64];
        let aabb = Aabb {
            min: self.lattice.to_world(widen(&query.min, -2)),
            max: self.lattice.to_world(widen(&query.max, 2)),
        };
        let (origin, scale) = (self.lattice.origin, self.lattice.scale);
        let mut found = Vec::new();
        self.spatial.faces_where(
            |min, max| {
                if !(min.cmple(aabb.max).all() && aabb.min.cmple(max).all()) {
                    return false;
                }
                // The node box in lattice units, widened by two steps (a vertex's lattice point
                // is its rounded position, half a step away at most; world → lattice rounds a
                // little more).
                let lo = (min - origin) * scale - DVec3::splat(2.0);
                let hi = (max - origin) * scale + DVec3::splat(2.0);
                let centre = (lo + hi) * 0.5;
                let half = (hi - lo) * 0.5;
                let rel = centre - a;
                let s = n.dot(rel);
                let r = n_abs.dot(half);
                // Bound on |s − s*| + |r − r*| (s*, r* with the exact normal): the normal's error
                // times the lever arms, plus the rounding of the products and sums (a few 2^-53
                // of their magnitudes; 1e-12 is generous), plus one.
                let err = NORMAL_ERROR * (rel.abs().element_sum() + half.element_sum())
                    + 1e-12 * n_abs.dot(rel.abs() + half)
                    + 1.0;
                s.abs() <= r + err
            },
            &mut found,
        );
        for t in found {
            if self.face_box(t).overlaps(query) {
                visit(t);
            }
        }
    }

    /// The broad phase of a cut: for every cutter face `f` (lattice box `boxes[f]`, corners
    /// `corners(f)`), the target faces of [`TargetIndex::faces_near_triangle`], ascending. Runs
    /// over the cutter faces in parallel when there are several.
    pub(crate) fn broad_phase<'a>(
        &self,
        boxes: &[IBox],
        corners: impl Fn(u32) -> [&'a LPoint; 3] + Sync,
    ) -> Vec<Vec<u32>> {
        use rayon::prelude::*;
        let one = |f: usize| {
            let mut found = Vec::new();
            self.faces_near_triangle(&boxes[f], corners(f as u32), |t| found.push(t));
            found.sort_unstable();
            found
        };
        if boxes.len() >= 8 {
            (0..boxes.len()).into_par_iter().map(one).collect()
        } else {
            (0..boxes.len()).map(one).collect()
        }
    }

    /// Region of face `t` (see [`TargetIndex::regions`]).
    #[inline]
    pub fn region_of_face(&self, t: u32) -> u32 {
        let c = self.components.region_of_triangle[t as usize];
        self.regions.region_of_component[c as usize]
    }

    /// Per region: closed (every component of it is).
    pub fn regions_closed(&self) -> Vec<bool> {
        let mut closed = vec![true; self.regions.count];
        for (c, &r) in self.regions.region_of_component.iter().enumerate() {
            closed[r as usize] &= self.component_closed[c];
        }
        closed
    }

    /// The region of every triangle, as a [`Regions`] labelling.
    pub fn region_labels(&self) -> Regions {
        self.regions.label(&self.components)
    }

    /// True when every region is closed (every edge has exactly two faces).
    pub fn is_closed(&self) -> bool {
        self.component_closed.iter().all(|&c| c)
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
        let want: Vec<u32> = (0..index.mesh.triangles.len() as u32)
            .filter(|&f| index.face_box(f).overlaps(&q))
            .collect();
        assert!(!want.is_empty());
        assert_eq!(got, want);
        assert!(index.is_closed());
        assert_eq!(index.regions.count, 1);
        assert!(index.winding.is_none());
    }

    /// An open target: walls come from the winding-number tree (a cutter inside the sphere's
    /// volume, away from the hole, is all wall; one outside changes nothing).
    #[test]
    fn open_target_walls_follow_the_winding_number() {
        let mut mesh = testkit::icosphere(3, 10.0);
        let positions = mesh.positions.clone();
        mesh.triangles.retain(|t| positions[t[0] as usize].z < 8.0);
        let index = TargetIndex::build(mesh).unwrap();
        assert!(!index.is_closed());
        let tree = index.winding.as_ref().expect("tree of an open target");
        tree.sanity_check(&index.mesh).unwrap();
        let inside = testkit::cube(DVec3::splat(-2.0), DVec3::splat(2.0));
        let r = crate::subtract(&index, &inside).unwrap();
        assert_eq!(r.walls.mesh.triangles.len(), inside.triangles.len());
        assert!(r.removed_faces.is_empty() && r.removed.mesh.is_empty());
        let outside = testkit::cube(DVec3::splat(20.0), DVec3::splat(22.0));
        assert!(crate::subtract(&index, &outside).unwrap().is_empty());
        // A cutter crossing the open surface away from the hole: walls, removed and kept.
        let across = testkit::cube(DVec3::new(-3.0, -3.0, -12.0), DVec3::new(3.0, 3.0, -8.0));
        let r = crate::subtract(&index, &across).unwrap();
        assert!(!r.walls.mesh.is_empty() && !r.removed.mesh.is_empty());
    }

    /// The fused build (neighbours, regions and closedness from the adjacency pass, region boxes
    /// from `lpoints`) gives exactly what the separate definitions give, on meshes with several
    /// regions, boundaries, a non-manifold fin, degenerate and duplicate triangles.
    #[test]
    fn fused_build_matches_the_definitions() {
        let mut open_sphere = testkit::icosphere(3, 10.0);
        let positions = open_sphere.positions.clone();
        open_sphere
            .triangles
            .retain(|t| positions[t[0] as usize].z < 8.0);
        let mut messy = testkit::cube(DVec3::ZERO, DVec3::ONE);
        messy.append(&testkit::torus(3.0, 1.0, 8, 6));
        messy.append(&testkit::icosphere(1, 0.5));
        messy.append(&testkit::bow_tie());
        let v = messy.positions.len() as u32;
        messy.positions.extend([
            DVec3::new(9.0, 0.0, 0.0),
            DVec3::new(9.0, 1.0, 0.0),
            DVec3::new(9.0, 0.0, 1.0),
            DVec3::new(8.0, 0.0, 0.0),
            DVec3::new(10.0, 0.5, 0.5),
            DVec3::splat(-7.0),
        ]);
        messy.triangles.extend([
            // A fin: three faces on the edge v..v+1, then degenerate and duplicate faces.
            [v, v + 1, v + 2],
            [v + 1, v, v + 3],
            [v, v + 1, v + 4],
            [v + 2, v + 2, v + 4],
            [v + 3, v + 4, v + 3],
            [v + 5, v + 5, v + 5],
            [v, v + 1, v + 2],
        ]);
        // Interleave the regions' faces.
        let last = messy.triangles.len() - 1;
        messy.triangles.swap(3, last - 8);
        for mesh in [
            testkit::icosphere(2, 1.0),
            open_sphere,
            messy,
            Mesh::default(),
        ] {
            let index = TargetIndex::build(mesh.clone()).unwrap();
            let adjacency = EdgeAdjacency::build(&mesh);
            adjacency.sanity_check(&mesh).unwrap();
            assert_eq!(index.adjacency.edges, adjacency.edges);
            assert_eq!(index.adjacency.edge_faces, adjacency.edge_faces);
            assert_eq!(
                index.adjacency.edge_face_offsets,
                adjacency.edge_face_offsets
            );
            assert_eq!(index.adjacency.triangle_edges, adjacency.triangle_edges);
            let regions = Regions::components(&mesh, &adjacency);
            regions.sanity_check(&mesh).unwrap();
            assert_eq!(
                index.components.region_of_triangle,
                regions.region_of_triangle
            );
            assert_eq!(index.components.count, regions.count);
            let mut closed = vec![true; regions.count];
            for e in 0..adjacency.edge_count() as u32 {
                let faces = adjacency.faces_of_edge(e);
                if faces.len() != 2 {
                    for &f in faces {
                        closed[regions.region_of_triangle[f as usize] as usize] = false;
                    }
                }
            }
            assert_eq!(index.component_closed, closed);
            assert_eq!(index.winding.is_some(), closed.iter().any(|c| !c));
            let neighbors: Vec<[u32; 3]> = (0..mesh.triangles.len())
                .map(|t| {
                    adjacency.triangle_edges[t].map(|e| {
                        if e == crate::adjacency::NO_EDGE {
                            return NO_NEIGHBOR;
                        }
                        match *adjacency.faces_of_edge(e) {
                            [a, b] => {
                                if a as usize == t {
                                    b
                                } else {
                                    a
                                }
                            }
                            [_] => NO_NEIGHBOR,
                            _ => MANY_NEIGHBORS,
                        }
                    })
                })
                .collect();
            assert_eq!(index.face_neighbors, neighbors);
            let mut boxes = vec![IBox::EMPTY; regions.count];
            let mut first = vec![u32::MAX; regions.count];
            let mut bounds = IBox::EMPTY;
            for t in 0..mesh.triangles.len() as u32 {
                let r = regions.region_of_triangle[t as usize] as usize;
                let b = index.face_box(t);
                boxes[r] = boxes[r].union(&b);
                first[r] = first[r].min(t);
                bounds = bounds.union(&b);
            }
            assert_eq!(index.component_boxes, boxes);
            assert_eq!(index.component_first_face, first);
            assert_eq!(index.bounds, bounds);
            index.spatial.sanity_check(&mesh).unwrap();
        }
    }

    #[test]
    fn scratch_gives_marked_faces_in_order_and_cleans_up() {
        let mut s = Scratch::for_faces(10_000);
        for round in 0..3u32 {
            s.begin(10_000);
            let faces = [9_999u32, 5, 4_096, 64, 63, 4_000 + round];
            s.mark_touched(faces[0]);
            for &t in &faces[1..] {
                s.mark_with(t, t + round);
            }
            assert_eq!(s.marked_count(), faces.len());
            let mut got = Vec::new();
            s.drain_marked(|t, touched, value| got.push((t, touched, value)));
            // A touched face's value is meaningless: compare it as 0.
            for g in got.iter_mut().filter(|g| g.1) {
                g.2 = 0;
            }
            let mut want: Vec<(u32, bool, u32)> =
                faces[1..].iter().map(|&t| (t, false, t + round)).collect();
            want.push((9_999, true, 0));
            want.sort_unstable_by_key(|w| w.0);
            assert_eq!(got, want);
            s.clear_touched(&faces[..1]);
            assert!(
                s.bits
                    .iter()
                    .chain(&s.summary)
                    .chain(&s.touched)
                    .all(|&w| w == 0)
            );
        }
    }
}
