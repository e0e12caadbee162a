//! The local exact boolean: cut a closed cutter out of a cached target.
//!
//! # Robustness contract
//!
//! **Input.** The target is any [`Mesh`] that passed [`Mesh::sanity_check`], indexed once with
//! [`TargetIndex::build`]: closed or open, manifold or not, several regions, degenerate faces
//! allowed. The cutter must be closed, edge-manifold, consistently oriented outward (positive
//! volume), free of self-intersections (sub-cutters of [`subtract_many`] must also be disjoint
//! and not nested), finite, and lie within four target sizes of the target's centre. Anything
//! else is a typed [`CutError`]; a cut never panics and never modifies the target.
//!
//! **Decisions.** Coordinates are quantized once to an integer lattice (steps of about
//! 2⁻²⁷ × the target's size, see [`crate::lattice`]); every topological decision is an exact
//! integer predicate of [`crate::exact`], with one tie-break rule for all degeneracies: the
//! cutter is symbolically translated by δ = (ε, ε², ε³) (Simulation of Simplicity). No epsilon
//! enters anywhere. So a target point exactly on a cutter face plane lies on the side −δ points
//! to, and coplanar faces separate by the sign of their normal's first non-zero component (x,
//! then y, then z); collinearities that survive the perturbation are handled exactly by the
//! triangulation ([`crate::split`]).
//!
//! **Output** ([`CutResult`]):
//! - **kept** (target outside the cutter, as a delta against the target: `removed_faces` plus
//!   `kept_new_faces`), **removed** (target inside the cutter), **walls** (cutter inside the
//!   target, facing out of kept), **contours**, and the provenance of every output face.
//! - Every vertex the cut did not create keeps its exact input coordinates (same bits); the new
//!   contour vertices are rounded once from their exact lattice value. Each contour vertex has
//!   one id, shared by kept, removed, walls and contours, so they weld bit for bit.
//! - **Regions.** Every region of the target is cut as its own solid. A region is a connected
//!   component together with its cavities: a closed component oriented inward (negative
//!   volume) that lies inside another closed component is a cavity of the innermost such
//!   component; every other component is its own region (decided exactly when the index is
//!   built, [`crate::cavities`]). The walls of a closed region are the cutter inside that
//!   region's solid (non-zero winding: inside its outer shell, outside its cavities), split by
//!   that region's contour only; nested regions (a brain inside the skin, a cube inside a cube)
//!   each get their own walls, which overlap where the solids do. [`CutResult::walls_solid`]
//!   names each wall triangle's region and [`CutResult::region_parts`] splits a result by
//!   region.
//! - For a closed, edge-manifold target, per region: kept + walls and removed + reversed walls
//!   are each closed, edge-manifold and consistently oriented, without T-junctions, and the
//!   volumes add up to the region's up to the rounding of the new vertices; kept and removed
//!   together are exactly the target's faces, split along the contour (so their areas add up to
//!   the target's area); contours are closed loops.
//! - Self-intersecting targets (regions that interpenetrate, a region crossing itself): kept and
//!   removed are exact as above. Where the contour curves of two target sheets cross inside one
//!   cutter face, the three-plane crossing point is not constructed: that face is split by the
//!   topology-only fallback, its wall pieces may overlap or take the wrong side, and kept +
//!   walls has T-junctions there. Such faces usually show in [`crate::output::CutStats`]
//!   (`triangulation_fallbacks`, `status_fallbacks`; both 0 for every target that does not
//!   intersect itself), and [`crate::cutcheck::crossing_cutter_faces`] names them exactly.
//! - Open or non-manifold targets: kept and removed are exact as above (they are classified
//!   relative to the closed cutter). Walls are split along the contour wherever it runs through
//!   a cutter face as a simple path or loop; contour pieces that end or branch inside a cutter
//!   face (target boundary or non-manifold edge) do not split it. The seed status of each cutter
//!   component comes from the target's generalized winding number (≥ ½ is inside), which is a
//!   classifier, not an exact test; a fast winding-number tree ([`crate::winding`], built with
//!   the index of an open target) makes it about O(log N) per cutter component.
//! - A cutter identical to the target (or sharing faces with it) is decided by the same δ rule
//!   as every coplanar case: the target faces whose normal's first non-zero component (x, then
//!   y, then z) is negative lie outside the translated cutter and are kept, the others are
//!   removed, and the walls are the cutter's faces against the kept ones. So kept + walls is a
//!   double layer of zero volume (its two sides may be triangulated differently), and removed +
//!   reversed walls is the whole solid, closed.
//! - Target faces with a repeated vertex index have no area and no edges of their own: they are
//!   never split; if one is crossed it is dropped from both kept and removed.
//! - Geometry after rounding: new vertices move by at most half a lattice step plus one `f64`
//!   rounding, so tiny inversions of slivers next to the contour are possible, never topological
//!   defects. A new vertex is the exact intersection of the *quantized* inputs: it can differ
//!   from the intersection of the `f64` inputs by about a lattice step (more where an edge
//!   grazes a plane).
//!
//! [`crate::cutcheck`] checks this contract on a result; the property, differential (against
//! Manifold) and fuzz tests of `csg/tests/` run it on random and degenerate cuts.
//!
//! **Cost.** Only faces whose boxes overlap cutter faces, in BVH subtrees that straddle the
//! cutter face's plane, are examined; untouched faces are classified by flood fill from the
//! contour (inside the cutter only, so output-sensitive: the face-to-face neighbours and a
//! per-face bitmap are cached with the index) and at most one exact inside test per untouched
//! region whose box overlaps the cutter. No per-cut allocation, clear or first touch is
//! proportional to the target size. The kept part and the removed piece are returned as deltas
//! against the target (the removed piece is built into a mesh when first read, see
//! [`Removed`]). The broad phase, the exact pair tests, the splitting of faces and the placing
//! of new vertices run in parallel (rayon); the flood fill runs beside the assembly of the
//! output. Everything a thread decides is a pure function of its inputs and results are merged
//! in a fixed order, so a cut's output does not depend on the thread count or scheduling.
//!
//! # Stages
//! 1. Validate and quantize the cutter ([`prepare_cutter`]). Early-out: boxes disjoint.
//! 2. Exact intersection ([`crate::intersect`]).
//! 3. Cutter vertex statuses (the set of region solids each lies in, [`crate::solids`]): one
//!    inside test per cutter component, then crossings toggle their face's solid.
//! 4. Split touched target faces, and touched cutter faces once per solid they meet
//!    ([`crate::split`]); statuses of the pieces.
//! 5. Flood fill of untouched target faces inside the cutter; untouched regions.
//! 6. Assemble the output and the contours ([`crate::contour`]).

use glam::DVec3;
use rayon::prelude::*;

use crate::adjacency::NO_EDGE;
use crate::classify;
use crate::contour;
use crate::exact::{self, HPoint, LPoint};
use crate::intersect::{self, FxMap, PointKey, PreparedCutter};
use crate::lattice::Lattice;
use crate::mesh::{Mesh, MeshError};
use crate::output::{CutOptions, CutResult, CutStats, PartBuilder, Provenance, Removed};
use crate::solids::{SolidSets, solid_of_face};
use crate::split::{self, FaceInput, OUT, Piece, PieceStatus, UNKNOWN, Vx};
use crate::target::{IBox, MANY_NEIGHBORS, NO_NEIGHBOR, TargetIndex};

/// Below this many touched faces (or contour segments), the stages that could run in parallel
/// run on the calling thread: a rayon hand-off costs more than splitting a few faces.
const PARALLEL_MIN: usize = 64;

/// Per-stage wall times of one cut, printed to stderr when the environment variable
/// `CUTAWAY_CUT_PHASES` is set (for profiling the benchmark; never in tests). Off, it costs a
/// clock read per cut.
pub(crate) struct Phases {
    pub(crate) on: bool,
    start: std::time::Instant,
    last: std::time::Instant,
    marks: Vec<(&'static str, f64)>,
}

impl Phases {
    pub(crate) fn new() -> Phases {
        static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let on = *ON.get_or_init(|| std::env::var_os("CUTAWAY_CUT_PHASES").is_some());
        let now = std::time::Instant::now();
        Phases {
            on,
            start: now,
            last: now,
            marks: Vec::new(),
        }
    }

    /// Ends the stage `name` (started at the previous mark).
    pub(crate) fn mark(&mut self, name: &'static str) {
        if self.on {
            let now = std::time::Instant::now();
            self.marks
                .push((name, (now - self.last).as_secs_f64() * 1e3));
            self.last = now;
        }
    }

    /// Appends the stages of `other` (timed on another thread).
    fn append(&mut self, other: &Phases) {
        if self.on {
            self.marks.extend_from_slice(&other.marks);
        }
    }

    /// Records a duration measured elsewhere (a stage that ran beside another).
    fn record(&mut self, name: &'static str, ms: f64) {
        if self.on {
            self.marks.push((name, ms));
        }
    }

    fn print(&self) {
        if self.on {
            let total = self.start.elapsed().as_secs_f64() * 1e3;
            let parts: Vec<String> = self
                .marks
                .iter()
                .map(|(n, ms)| format!("{n} {ms:.3}"))
                .collect();
            eprintln!("cut phases ms: total {total:.3} | {}", parts.join(" | "));
        }
    }
}

/// Wall time of `f` in ms when `on`.
fn timed<R>(on: bool, f: impl FnOnce() -> R) -> (R, f64) {
    if on {
        let t = std::time::Instant::now();
        let r = f();
        (r, t.elapsed().as_secs_f64() * 1e3)
    } else {
        (f(), 0.0)
    }
}

/// Why a cut was refused. Each variant names the sub-cutter and what to fix.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CutError {
    /// The cutter has no triangles.
    #[error("cutter {sub_cutter} has no triangles")]
    EmptyCutter { sub_cutter: usize },
    /// Bad indices or a non-finite coordinate.
    #[error("cutter {sub_cutter}: {source}")]
    InvalidMesh {
        sub_cutter: usize,
        #[source]
        source: MeshError,
    },
    /// A cutter vertex is more than four target sizes from the target's centre.
    #[error(
        "cutter {sub_cutter}: vertex {vertex} at {position:?} is too far from the target (more than four target sizes from its centre)"
    )]
    OutOfRange {
        sub_cutter: usize,
        vertex: usize,
        position: [f64; 3],
    },
    /// A triangle uses one vertex twice.
    #[error("cutter {sub_cutter}: triangle {triangle} uses a vertex twice")]
    DegenerateTriangle { sub_cutter: usize, triangle: usize },
    /// An edge is not shared by exactly two triangles: the cutter is open (1) or non-manifold (3+).
    #[error(
        "cutter {sub_cutter} is not closed: edge ({a}, {b}) has {faces} triangle(s); a cutter must be a closed surface (every edge in exactly two triangles)"
    )]
    NotClosed {
        sub_cutter: usize,
        a: u32,
        b: u32,
        faces: usize,
    },
    /// The two triangles of an edge traverse it in the same direction.
    #[error(
        "cutter {sub_cutter} is not consistently oriented: both triangles of edge ({a}, {b}) run the same way"
    )]
    NotOriented { sub_cutter: usize, a: u32, b: u32 },
    /// Negative or zero enclosed volume (inward-facing or flat).
    #[error(
        "cutter {sub_cutter} encloses no positive volume (its triangles face inward, or it is flat); reverse its triangles or fix its shape"
    )]
    NotPositive { sub_cutter: usize },
    /// Two cutter triangles (of one sub-cutter, or of two sub-cutters) intersect.
    #[error(
        "cutter triangles {first} and {second} intersect (sub-cutters {first_sub} and {second_sub}); a cutter must not self-intersect and sub-cutters must be disjoint"
    )]
    SelfIntersecting {
        first: usize,
        second: usize,
        first_sub: usize,
        second_sub: usize,
    },
    /// An internal consistency check failed (a bug; the target is untouched).
    #[error("internal error in the boolean: {0}")]
    Internal(String),
}

/// Cuts `cutter` out of the target (see the robustness contract in the module doc): exact
/// topology for any sane target, closed and manifold kept + walls for closed targets that do not
/// intersect themselves, degeneracies resolved by translating the cutter by δ = (ε, ε², ε³), a
/// typed [`CutError`] for an invalid cutter, never a panic.
///
/// Each region of the target is cut as its own solid (non-zero winding). A region is a
/// connected component together with its cavities: a closed component oriented inward
/// (negative volume) that lies inside another closed component (decided exactly) is a cavity of
/// the innermost such one; every other component is its own region. So a cube of side 10 with
/// an inward cube of side 4 inside is one hollow solid (walls skip the cavity), while the same
/// inner cube oriented outward is a second solid, with walls of its own inside the first's. For
/// every closed region, kept + walls and removed + reversed walls are closed and the volume
/// identity holds; [`CutResult::region_parts`] gives each region's kept, walls and removed.
///
/// A cutter identical to the target keeps the faces whose normal's first non-zero component is
/// negative, with walls against them: a zero-volume double layer (module doc).
pub fn subtract(target: &TargetIndex, cutter: &Mesh) -> Result<CutResult, CutError> {
    subtract_many(target, &[cutter])
}

/// Cuts several disjoint sub-cutters (ribbons, slices) at once. Every output face carries the
/// id of its sub-cutter (`sub_cutter` of [`Part`] and [`crate::output::Contour`]); use
/// [`Part::of_sub_cutter`] for one sub-cutter's removed piece or walls.
pub fn subtract_many(target: &TargetIndex, cutters: &[&Mesh]) -> Result<CutResult, CutError> {
    subtract_with(target, cutters, &CutOptions::default())
}

/// [`subtract_many`] with options.
pub fn subtract_with(
    target: &TargetIndex,
    cutters: &[&Mesh],
    options: &CutOptions,
) -> Result<CutResult, CutError> {
    let mut phases = Phases::new();
    let cutter = prepare_cutter(target, cutters)?;
    phases.mark("prepare");
    // On a rayon worker: the parallel stages inside then hand work to the other workers through
    // their local queues, instead of each waking the pool from outside (which costs a scheduler
    // round trip per stage on a busy machine).
    let r = rayon::scope(|_| run(target, &cutter, options, &mut phases));
    phases.print();
    r
}

/// Stage 1: validation and quantization of the cutter(s).
pub(crate) fn prepare_cutter(
    target: &TargetIndex,
    cutters: &[&Mesh],
) -> Result<PreparedCutter, CutError> {
    let cutter = prepare_unchecked(&target.lattice, cutters)?;
    check_self_intersections(&cutter)?;
    Ok(cutter)
}

/// Checks a cutter on its own, before any target exists (the cutter editor validates every edit
/// with it): closed, consistently oriented, positive volume and free of self-intersections, with
/// the same exact predicates as [`subtract`], on the lattice of the cutter's own bounding box.
/// A target much larger than the cutter has a coarser lattice, so a cutter whose faces come within
/// a few of its lattice steps of each other can still be refused by the cut itself.
pub fn check_cutter(cutter: &Mesh) -> Result<(), CutError> {
    let prepared = prepare_unchecked(&Lattice::for_box(&cutter.bbox()), &[cutter])?;
    check_self_intersections(&prepared)
}

/// Every pair of intersecting triangles of `cutter` (at most `limit`; exact, touching counts, as
/// in [`check_cutter`]), or the first other defect [`check_cutter`] finds. Lets a caller repair
/// every offending place of a cutter at once instead of one pair per check.
pub fn cutter_self_intersections(
    cutter: &Mesh,
    limit: usize,
) -> Result<Vec<(usize, usize)>, CutError> {
    let prepared = prepare_unchecked(&Lattice::for_box(&cutter.bbox()), &[cutter])?;
    Ok(self_intersections(&prepared, limit))
}

/// Validation and quantization without the self-intersection check.
fn prepare_unchecked(lattice: &Lattice, cutters: &[&Mesh]) -> Result<PreparedCutter, CutError> {
    let mut positions = Vec::new();
    let mut lpoints = Vec::new();
    let mut triangles = Vec::new();
    let mut face_component = Vec::new();
    let mut sub_of_vertex = Vec::new();
    for (k, m) in cutters.iter().enumerate() {
        m.sanity_check().map_err(|source| CutError::InvalidMesh {
            sub_cutter: k,
            source,
        })?;
        if m.triangles.is_empty() {
            return Err(CutError::EmptyCutter { sub_cutter: k });
        }
        let base = positions.len() as u32;
        for (i, &p) in m.positions.iter().enumerate() {
            let q = lattice.quantize(p).ok_or(CutError::OutOfRange {
                sub_cutter: k,
                vertex: i,
                position: p.to_array(),
            })?;
            positions.push(p);
            lpoints.push(q);
            sub_of_vertex.push(k as u32);
        }
        for (i, t) in m.triangles.iter().enumerate() {
            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                return Err(CutError::DegenerateTriangle {
                    sub_cutter: k,
                    triangle: i,
                });
            }
            triangles.push(t.map(|v| v + base));
            face_component.push(k as u32);
        }
    }
    // Edges: every undirected edge in exactly two faces, traversed in opposite directions.
    let mut edge_map: FxMap<(u32, u32), u32> = Default::default();
    let mut edges: Vec<[u32; 2]> = Vec::new();
    let mut edge_dirs: Vec<[bool; 2]> = Vec::new();
    let mut edge_count: Vec<usize> = Vec::new();
    let mut tri_edges = Vec::with_capacity(triangles.len());
    for t in triangles.iter() {
        let mut te = [0u32; 3];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let id = *edge_map.entry(key).or_insert_with(|| {
                edges.push([key.0, key.1]);
                edge_dirs.push([false; 2]);
                edge_count.push(0);
                (edges.len() - 1) as u32
            });
            let c = edge_count[id as usize];
            if c < 2 {
                edge_dirs[id as usize][c] = a < b;
            }
            edge_count[id as usize] += 1;
            te[k] = id;
        }
        tri_edges.push(te);
    }
    for (e, &c) in edge_count.iter().enumerate() {
        let [a, b] = edges[e];
        let sub_cutter = sub_of_vertex[a as usize] as usize;
        let local = |v: u32| v - first_vertex(cutters, sub_cutter);
        if c != 2 {
            return Err(CutError::NotClosed {
                sub_cutter,
                a: local(a),
                b: local(b),
                faces: c,
            });
        }
        if edge_dirs[e][0] == edge_dirs[e][1] {
            return Err(CutError::NotOriented {
                sub_cutter,
                a: local(a),
                b: local(b),
            });
        }
    }
    let mut face_boxes = Vec::with_capacity(triangles.len());
    let mut bounds = IBox::EMPTY;
    for t in &triangles {
        let b = IBox::of_triangle(t.map(|v| &lpoints[v as usize]));
        bounds = bounds.union(&b);
        face_boxes.push(b);
    }
    let cutter = PreparedCutter {
        positions,
        lpoints,
        triangles,
        edges,
        tri_edges,
        face_component,
        components: cutters.len() as u32,
        face_boxes,
        bounds,
    };
    // Orientation: positive exact volume per sub-cutter.
    let mut vol = vec![0i128; cutters.len()];
    let o = [0i64; 3];
    for (f, t) in cutter.triangles.iter().enumerate() {
        let [a, b, c] = t.map(|v| &cutter.lpoints[v as usize]);
        let k = cutter.face_component[f] as usize;
        vol[k] = vol[k].saturating_add(exact::orient3d(&o, a, b, c));
    }
    if let Some(k) = vol.iter().position(|&v| v <= 0) {
        return Err(CutError::NotPositive { sub_cutter: k });
    }
    Ok(cutter)
}

fn first_vertex(cutters: &[&Mesh], k: usize) -> u32 {
    cutters[..k].iter().map(|m| m.positions.len() as u32).sum()
}

/// Exact self-intersection check of the cutter (touching counts). Triangles sharing an edge are
/// not compared; triangles sharing one vertex are compared through their opposite edges.
fn check_self_intersections(cutter: &PreparedCutter) -> Result<(), CutError> {
    match self_intersections(cutter, 1).first() {
        Some(&(a, b)) => Err(CutError::SelfIntersecting {
            first: a,
            second: b,
            first_sub: cutter.face_component[a] as usize,
            second_sub: cutter.face_component[b] as usize,
        }),
        None => Ok(()),
    }
}

/// Up to `limit` intersecting triangle pairs `(a, b)`, `a < b`, in the order of `a` (see
/// [`check_self_intersections`]).
fn self_intersections(cutter: &PreparedCutter, limit: usize) -> Vec<(usize, usize)> {
    let bvh = intersect::cutter_bvh(cutter);
    let mut found: Vec<(usize, usize)> = Vec::new();
    for f1 in 0..cutter.triangles.len() {
        if found.len() >= limit {
            break;
        }
        let t1 = cutter.triangles[f1];
        let mut hits = Vec::new();
        bvh.query(&cutter.face_boxes[f1], &cutter.face_boxes, |f2| {
            let f2 = f2 as usize;
            if f2 <= f1 {
                return;
            }
            let t2 = cutter.triangles[f2];
            let shared: Vec<u32> = t1.iter().copied().filter(|v| t2.contains(v)).collect();
            if shared.len() >= 2 {
                return;
            }
            let p1 = t1.map(|v| &cutter.lpoints[v as usize]);
            let p2 = t2.map(|v| &cutter.lpoints[v as usize]);
            let hit = |ta: &[u32; 3], pa: &[&LPoint; 3], pb: &[&LPoint; 3]| {
                (0..3).any(|k| {
                    let (i, j) = (k, (k + 1) % 3);
                    if shared.len() == 1 && (ta[i] == shared[0] || ta[j] == shared[0]) {
                        return false;
                    }
                    exact::segment_meets_triangle(pa[i], pa[j], pb[0], pb[1], pb[2])
                })
            };
            if hit(&t1, &p1, &p2) || hit(&t2, &p2, &p1) {
                hits.push(f2);
            }
        });
        hits.sort_unstable();
        found.extend(hits.into_iter().map(|f2| (f1, f2)));
    }
    found.truncate(limit);
    found
}

/// Stages 2–6 on a validated cutter.
pub(crate) fn run(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    options: &CutOptions,
    phases: &mut Phases,
) -> Result<CutResult, CutError> {
    let mesh = &target.mesh;
    let nt = mesh.positions.len() as u32;
    let mut stats = CutStats::default();
    let mut result = CutResult {
        target_vertex_count: nt as usize,
        ..Default::default()
    };
    // Stage 1b: early-out when the boxes are disjoint.
    if !cutter.bounds.overlaps(&target.bounds) {
        result.stats = stats;
        return Ok(result);
    }
    // Stage 2: intersections.
    let isect = intersect::intersect_timed(target, cutter, phases).map_err(CutError::Internal)?;
    stats.candidate_pairs = isect.candidate_pairs;
    let face_of_point = |p: u32| -> u32 {
        match isect.keys[p as usize] {
            PointKey::Ef { face, .. } => face,
            PointKey::Fe { face, .. } => face,
        }
    };

    // Stage 3: cutter vertex statuses: the set of region solids each lies in (see
    // `crate::solids`); crossing a target face toggles that face's solid.
    let nv = cutter.positions.len();
    let mut vertex_edges: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for (g, e) in cutter.edges.iter().enumerate() {
        vertex_edges[e[0] as usize].push(g as u32);
        vertex_edges[e[1] as usize].push(g as u32);
    }
    let solid_of_point = |p: u32| solid_of_face(target, face_of_point(p));
    let mut sets = SolidSets::new();
    let mut cutter_in: Vec<Option<u32>> = vec![None; nv];
    let closed = target.is_closed();
    for seed in 0..nv {
        if cutter_in[seed].is_some() {
            continue;
        }
        stats.inside_tests += 1;
        let s =
            classify::cutter_point_solids(target, &cutter.lpoints[seed], cutter.positions[seed]);
        cutter_in[seed] = Some(sets.intern(s));
        let mut stack = vec![seed];
        while let Some(v) = stack.pop() {
            let sv = cutter_in[v].unwrap_or(0);
            for &g in &vertex_edges[v] {
                let [a, b] = cutter.edges[g as usize];
                let other = if a as usize == v { b } else { a } as usize;
                let so = isect.cutter_edges[g as usize]
                    .iter()
                    .fold(sv, |set, x| sets.toggle(set, solid_of_point(x.point)));
                match cutter_in[other] {
                    None => {
                        cutter_in[other] = Some(so);
                        stack.push(other);
                    }
                    Some(x) if x != so && closed => {
                        return Err(CutError::Internal(format!(
                            "crossing parity disagrees around cutter vertex {other}"
                        )));
                    }
                    _ => {}
                }
            }
        }
    }
    let cutter_in: Vec<u32> = cutter_in.into_iter().map(|s| s.unwrap_or(0)).collect();
    let sets = &sets;
    phases.mark("cutter status");

    // Stage 4a: split the touched target faces.
    let target_corner = |v: Vx| match v {
        Vx::T(i) => HPoint::target_vertex(&target.lpoints[i as usize]),
        Vx::C(i) => HPoint::cutter_vertex(&cutter.lpoints[i as usize]),
        Vx::X(_) => unreachable_point(),
    };
    // Per touched face (in `isect.target_order`): its pieces, the statuses the crossings give
    // them (`UNKNOWN` otherwise), the triangulation fallbacks, the status of each corner's piece
    // when known, and which of its sides the contour crosses (bit k: side k).
    struct TargetFace {
        slot: usize,
        t: u32,
        pieces: Vec<Piece>,
        statuses: Vec<u32>,
        fallbacks: usize,
        corner_status: [u32; 3],
        crossed: u8,
    }
    // Buffers of one worker, reused from face to face.
    #[derive(Default)]
    struct Buffers {
        boundary: Vec<Vx>,
        arc_status: Vec<u32>,
        segments: Vec<(u32, u32, u32)>,
    }
    let split_target_face = |buf: &mut Buffers, slot: usize| -> Result<TargetFace, CutError> {
        let t = isect.target_order[slot];
        let tri = mesh.triangles[t as usize];
        let Buffers {
            boundary,
            arc_status,
            segments,
        } = buf;
        boundary.clear();
        arc_status.clear();
        segments.clear();
        let mut crossed = 0u8;
        for k in 0..3 {
            boundary.push(Vx::T(tri[k]));
            arc_status.push(UNKNOWN);
            let e = target.adjacency.triangle_edges[t as usize][k];
            if e == NO_EDGE {
                continue;
            }
            let Some(list) = isect.crossings_of_edge(e) else {
                continue;
            };
            crossed |= 1 << k;
            // The adjacency stores edges as `[lo, hi]` with `lo < hi`.
            let forward = tri[k] < tri[(k + 1) % 3];
            debug_assert_eq!(forward, target.adjacency.edges[e as usize][0] == tri[k]);
            let mut push = |x: &intersect::Crossing| {
                let u_side = if forward { x.lo_side } else { -x.lo_side };
                let f = face_of_point(x.point);
                boundary.push(Vx::X(x.point));
                arc_status.push(if u_side < 0 {
                    1 + cutter.face_component[f as usize]
                } else {
                    OUT
                });
            };
            if forward {
                list.iter().for_each(&mut push);
            } else {
                list.iter().rev().for_each(&mut push);
            }
        }
        segments.extend(isect.segments_of_face(slot).iter().map(|&s| {
            let seg = &isect.segments[s as usize];
            (seg.a, seg.b, 1 + cutter.face_component[seg.f as usize])
        }));
        let [u, v, w] = target.face_points(t);
        let input = FaceInput {
            boundary,
            arc_status,
            segments,
            points: &isect.points,
            corner_point: &target_corner,
            projection: exact::projection(&exact::normal(u, v, w)),
        };
        let split = split::split_face(&input)
            .map_err(|e| CutError::Internal(format!("target face {t}: {e}")))?;
        let statuses = split
            .pieces
            .iter()
            .map(|p| match p.status {
                PieceStatus::Known(s) => s,
                _ => UNKNOWN,
            })
            .collect();
        let mut face = TargetFace {
            slot,
            t,
            pieces: split.pieces,
            statuses,
            fallbacks: split.fallbacks,
            corner_status: [UNKNOWN; 3],
            crossed,
        };
        face.set_corner_statuses(&tri);
        Ok(face)
    };
    impl TargetFace {
        /// Gives each corner the status of the piece it belongs to (`UNKNOWN` while unknown).
        fn set_corner_statuses(&mut self, tri: &[u32; 3]) {
            for (p, &s) in self.pieces.iter().zip(&self.statuses) {
                if s != UNKNOWN {
                    for &c in &p.corners {
                        for k in 0..3 {
                            if tri[k] == c {
                                self.corner_status[k] = s;
                            }
                        }
                    }
                }
            }
        }
    }
    // Stage 4c (beside 4a): split the touched cutter faces, once per solid that the face meets
    // (its corners lie in, or its contour belongs to): each solid's walls are split by that
    // solid's contour only, so every region's kept + walls closes on its own.
    // Per cutter face: its wall triangles with their solid, whether the contour splits it, and
    // the fallbacks of the triangulation and of the statuses.
    type CutterFaceWalls = (Vec<([Vx; 3], u32, u32)>, bool, usize, usize);
    let split_cutter_face = |f: u32| -> Result<CutterFaceWalls, CutError> {
        let tri = cutter.triangles[f as usize];
        let seg_ids = &isect.cutter_faces[f as usize];
        let mut wall_tris = Vec::new();
        let mut solids: Vec<u32> = Vec::new();
        for &v in &tri {
            solids.extend_from_slice(sets.solids(cutter_in[v as usize]));
        }
        for &sg in seg_ids {
            solids.push(solid_of_face(target, isect.segments[sg as usize].t));
        }
        solids.sort_unstable();
        solids.dedup();
        let (mut fallbacks, mut status_fallbacks) = (0, 0);
        for solid in solids {
            let inside = |v: u32| sets.contains(cutter_in[v as usize], solid);
            let mut segments: Vec<(u32, u32, u32)> = seg_ids
                .iter()
                .map(|&sg| &isect.segments[sg as usize])
                .filter(|seg| solid_of_face(target, seg.t) == solid)
                .map(|seg| (seg.a, seg.b, 1))
                .collect();
            if segments.is_empty() {
                if inside(tri[0]) {
                    wall_tris.push(([Vx::C(tri[0]), Vx::C(tri[1]), Vx::C(tri[2])], f, solid));
                }
                continue;
            }
            let mut boundary = Vec::with_capacity(16);
            let mut arc_status = Vec::with_capacity(16);
            let mut on_boundary: FxMap<u32, ()> = Default::default();
            for k in 0..3 {
                boundary.push(Vx::C(tri[k]));
                arc_status.push(UNKNOWN);
                let g = cutter.tri_edges[f as usize][k];
                let list = &isect.cutter_edges[g as usize];
                let forward = cutter.edges[g as usize][0] == tri[k];
                let start_in = inside(tri[k]);
                let mut i = 0;
                let n = list.len();
                for j in 0..n {
                    let x = if forward { list[j] } else { list[n - 1 - j] };
                    if solid_of_point(x.point) != solid {
                        continue;
                    }
                    boundary.push(Vx::X(x.point));
                    on_boundary.insert(x.point, ());
                    // The arc before the i-th crossing has the start's status flipped i times.
                    arc_status.push(u32::from(start_in ^ (i % 2 == 1)));
                    i += 1;
                }
            }
            prune_segments(&mut segments, &on_boundary);
            let [a, b, c] = cutter.face_points(f);
            let input = FaceInput {
                boundary: &boundary,
                arc_status: &arc_status,
                segments: &segments,
                points: &isect.points,
                corner_point: &target_corner,
                projection: exact::projection(&exact::normal(a, b, c)),
            };
            let split = split::split_face(&input)
                .map_err(|e| CutError::Internal(format!("cutter face {f}: {e}")))?;
            let mut st = vec![UNKNOWN; split.pieces.len()];
            for (i, p) in split.pieces.iter().enumerate() {
                match p.status {
                    PieceStatus::Known(s) => st[i] = s,
                    PieceStatus::Default => st[i] = u32::from(inside(tri[0])),
                    PieceStatus::LoopOf { .. } => {}
                }
            }
            status_fallbacks += resolve_loops(&split.pieces, &mut st, 1)?;
            fallbacks += split.fallbacks;
            for (p, &s) in split.pieces.iter().zip(&st) {
                if s != OUT {
                    for t in &p.triangles {
                        wall_tris.push((*t, f, solid));
                    }
                }
            }
        }
        Ok((wall_tris, !seg_ids.is_empty(), fallbacks, status_fallbacks))
    };
    let split_walls = || -> Result<Vec<CutterFaceWalls>, CutError> {
        let cutter_faces = 0..cutter.triangles.len() as u32;
        if isect.segments.len() >= PARALLEL_MIN {
            cutter_faces
                .into_par_iter()
                .map(split_cutter_face)
                .collect()
        } else {
            cutter_faces.map(split_cutter_face).collect()
        }
    };

    // Faces split independently: in parallel when there are enough of them (the target faces
    // and the cutter faces at once, so that the threads share the work).
    let split_targets = || -> Result<Vec<TargetFace>, CutError> {
        if isect.target_order.len() >= PARALLEL_MIN {
            (0..isect.target_order.len())
                .into_par_iter()
                .map_init(Buffers::default, split_target_face)
                .collect()
        } else {
            let mut buf = Buffers::default();
            (0..isect.target_order.len())
                .map(|slot| split_target_face(&mut buf, slot))
                .collect()
        }
    };
    let (faces, split_cutter) = rayon::join(split_targets, split_walls);
    let mut faces = faces?;
    let split_cutter = split_cutter?;
    for face in &faces {
        stats.triangulation_fallbacks += face.fallbacks;
    }
    stats.touched_target_faces = faces.len();
    phases.mark("split faces");

    // Stage 4b: statuses of the target pieces the crossings leave open (rare: faces that only
    // contour loops cross). A piece without crossings on its boundary takes the status of one
    // of its corners known from another face (a vertex has one status), else one inside test;
    // a loop's inside is the flip of its container.
    let open = |f: &TargetFace| {
        f.pieces
            .iter()
            .zip(&f.statuses)
            .any(|(p, &s)| s == UNKNOWN && matches!(p.status, PieceStatus::Default))
    };
    if faces.iter().any(open) {
        let mut vertex_status: FxMap<u32, u32> = Default::default();
        for f in &faces {
            for (p, &s) in f.pieces.iter().zip(&f.statuses) {
                if s != UNKNOWN {
                    for &c in &p.corners {
                        vertex_status.insert(c, s);
                    }
                }
            }
        }
        for f in faces.iter_mut() {
            for (i, p) in f.pieces.iter().enumerate() {
                if matches!(p.status, PieceStatus::Default) && !p.corners.is_empty() {
                    let known = p.corners.iter().find_map(|c| vertex_status.get(c).copied());
                    let s = match known {
                        Some(s) => s,
                        None => {
                            stats.inside_tests += 1;
                            classify::target_point_status(
                                cutter,
                                &target.lpoints[p.corners[0] as usize],
                            )
                        }
                    };
                    f.statuses[i] = s;
                    for &c in &p.corners {
                        vertex_status.insert(c, s);
                    }
                }
            }
        }
    }
    for f in faces.iter_mut() {
        if f.pieces
            .iter()
            .all(|p| matches!(p.status, PieceStatus::Known(_)))
        {
            continue;
        }
        if f.statuses.contains(&UNKNOWN) {
            let inside = isect.segments_of_face(f.slot).first().map_or(1, |&sg| {
                1 + cutter.face_component[isect.segments[sg as usize].f as usize]
            });
            stats.status_fallbacks += resolve_loops(&f.pieces, &mut f.statuses, inside)?;
        }
        let tri = mesh.triangles[f.t as usize];
        f.set_corner_statuses(&tri);
    }
    phases.mark("piece status");
    // Stage 5 (on this thread while stage 6 runs on the others): flood fill of untouched
    // target faces inside the cutter. The scratch marks every face of `removed_faces` (touched
    // by the contour, or flooded) in a bitmap, which also gives them back in ascending order; a
    // flooded face's status is recorded only when there are several sub-cutters (with one it is
    // always 1).
    let flood = || {
        let mut inside_tests = 0;
        let many = cutter.components > 1;
        let mut local_scratch = None;
        let mut guard = target.scratch.0.try_lock();
        let scratch: &mut crate::target::Scratch = match guard.as_deref_mut() {
            Ok(s) => s,
            Err(_) => local_scratch.insert(crate::target::Scratch::for_faces(mesh.triangles.len())),
        };
        scratch.begin(mesh.triangles.len());
        for &t in &isect.target_order {
            scratch.mark_touched(t);
        }
        // Breadth-first: `queue` holds the flooded faces and their statuses in discovery order.
        // The faces of a large target are far apart in memory (on the peerbench sphere no
        // neighbour's index is within 4096), so each face's neighbour entry is a cache miss: the
        // loop below loads the entries of a batch of queued faces first (independent loads,
        // which the processor overlaps) and only then follows them.
        let mut queue: Vec<(u32, u32)> = Vec::new();
        let visit = |scratch: &mut crate::target::Scratch, queue: &mut Vec<(u32, u32)>, t2, s| {
            if !scratch.is_marked(t2) {
                if many {
                    scratch.mark_with(t2, s);
                } else {
                    scratch.mark(t2);
                }
                queue.push((t2, s));
            }
        };
        // Seeds: across every side the contour does not cross, the status of its first corner
        // (its piece's status: a vertex has one status).
        for face in &faces {
            let t = face.t;
            let neighbors = target.face_neighbors[t as usize];
            for k in 0..3 {
                let s = face.corner_status[k];
                if face.crossed & (1 << k) != 0 || s == OUT || s == UNKNOWN {
                    continue;
                }
                match neighbors[k] {
                    NO_NEIGHBOR => {}
                    MANY_NEIGHBORS => {
                        let e = target.adjacency.triangle_edges[t as usize][k];
                        for &t2 in target.adjacency.faces_of_edge(e) {
                            visit(scratch, &mut queue, t2, s);
                        }
                    }
                    t2 => visit(scratch, &mut queue, t2, s),
                }
            }
        }
        // Untouched regions whose box overlaps the cutter: one inside test each.
        let mut touched_regions: FxMap<u32, ()> = Default::default();
        for &t in &isect.target_order {
            touched_regions.insert(target.components.region_of_triangle[t as usize], ());
        }
        for r in 0..target.components.count {
            if touched_regions.contains_key(&(r as u32))
                || !target.component_boxes[r].overlaps(&cutter.bounds)
            {
                continue;
            }
            let t0 = target.component_first_face[r];
            if t0 == u32::MAX || scratch.is_marked(t0) {
                continue;
            }
            inside_tests += 1;
            let v0 = mesh.triangles[t0 as usize][0];
            let s = classify::target_point_status(cutter, &target.lpoints[v0 as usize]);
            if s != OUT {
                visit(scratch, &mut queue, t0, s);
            }
        }
        const BATCH: usize = 32;
        let mut head = 0;
        while head < queue.len() {
            let end = queue.len().min(head + BATCH);
            let mut neighbors = [[0u32; 3]; BATCH];
            for (n, &(t, _)) in neighbors.iter_mut().zip(&queue[head..end]) {
                *n = target.face_neighbors[t as usize];
            }
            for i in 0..end - head {
                let (t, s) = queue[head + i];
                for (k, &t2) in neighbors[i].iter().enumerate() {
                    if t2 < MANY_NEIGHBORS {
                        visit(scratch, &mut queue, t2, s);
                    } else if t2 == MANY_NEIGHBORS {
                        let e = target.adjacency.triangle_edges[t as usize][k];
                        for &t2 in target.adjacency.faces_of_edge(e) {
                            visit(scratch, &mut queue, t2, s);
                        }
                    }
                }
            }
            head = end;
        }
        // Every marked face, ascending: the touched ones and the flooded (whole) ones.
        let marked = scratch.marked_count();
        let mut removed_faces: Vec<u32> = Vec::with_capacity(marked);
        let mut whole_faces: Vec<u32> = Vec::with_capacity(marked);
        let mut whole_sub_cutter: Vec<u32> = Vec::with_capacity(marked);
        scratch.drain_marked(|t, touched, value| {
            removed_faces.push(t);
            if !touched {
                whole_faces.push(t);
                whole_sub_cutter.push(if many { value - 1 } else { 0 });
            }
        });
        scratch.clear_touched(&isect.target_order);
        drop(guard);
        (removed_faces, whole_faces, whole_sub_cutter, inside_tests)
    };
    // Stage 6 (on the other threads while the flood fill runs on this one): everything that
    // does not need the flood: the cutter faces' split, the new vertices, the kept pieces and
    // the removed pieces of split faces, the walls and the contours.
    let merge = options.merge_coincident;
    let output = || -> Result<Output, CutError> {
        let mut sub = Phases::new();
        let mut stats = CutStats::default();
        // A new vertex whose exact limit is the lattice point of one of its defining input
        // vertices (degenerate contact at a vertex) takes that vertex's exact input position, so
        // that it welds with it; otherwise it is its exact value rounded once.
        let place = |(h, key): (&HPoint, &PointKey)| -> DVec3 {
            if let Some(l) = may_be_lattice_point(h)
                .then(|| h.limit_lattice_point())
                .flatten()
            {
                let (tv, cv): (Vec<u32>, Vec<u32>) = match *key {
                    PointKey::Ef { edge, face } => (
                        target.adjacency.edges[edge as usize].to_vec(),
                        cutter.triangles[face as usize].to_vec(),
                    ),
                    PointKey::Fe { edge, face } => (
                        mesh.triangles[face as usize].to_vec(),
                        cutter.edges[edge as usize].to_vec(),
                    ),
                };
                if let Some(&v) = tv.iter().find(|&&v| target.lpoints[v as usize] == l) {
                    return mesh.positions[v as usize];
                }
                if let Some(&v) = cv.iter().find(|&&v| cutter.lpoints[v as usize] == l) {
                    return cutter.positions[v as usize];
                }
            }
            // Otherwise place it on the target's original geometry: on the original target edge
            // (EF) or inside the original target face (FE), with the parameters computed on the
            // lattice. Kept and removed then tile each target face up to f64 rounding.
            let l = h.limit();
            match *key {
                PointKey::Ef { edge, .. } => {
                    let [p, q] = target.adjacency.edges[edge as usize];
                    let (lp, lq) = (&target.lpoints[p as usize], &target.lpoints[q as usize]);
                    let d: [f64; 3] = std::array::from_fn(|k| (lq[k] - lp[k]) as f64);
                    let num: f64 = (0..3).map(|k| (l[k] - lp[k] as f64) * d[k]).sum();
                    let den: f64 = (0..3).map(|k| d[k] * d[k]).sum();
                    let t = if den > 0.0 {
                        (num / den).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let (wp, wq) = (mesh.positions[p as usize], mesh.positions[q as usize]);
                    wp + (wq - wp) * t
                }
                PointKey::Fe { face, .. } => {
                    let tri = mesh.triangles[face as usize];
                    let [u, v, w] = tri.map(|i| &target.lpoints[i as usize]);
                    match exact::projection(&exact::normal(u, v, w)) {
                        Some((axis, _)) => {
                            let (i, j) = exact::plane_axes(axis);
                            let area = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
                                (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                            };
                            let pr = |p: &LPoint| [p[i] as f64, p[j] as f64];
                            let x = [l[i], l[j]];
                            let whole = area(pr(u), pr(v), pr(w));
                            let beta = area(pr(u), x, pr(w)) / whole;
                            let gamma = area(pr(u), pr(v), x) / whole;
                            let [wu, wv, ww] = tri.map(|i| mesh.positions[i as usize]);
                            wu + (wv - wu) * beta + (ww - wu) * gamma
                        }
                        None => target.lattice.to_world(l),
                    }
                }
            }
        };
        let new_positions: Vec<DVec3> = if isect.points.len() >= PARALLEL_MIN {
            isect
                .points
                .par_iter()
                .zip(&isect.keys)
                .map(place)
                .collect()
        } else {
            isect.points.iter().zip(&isect.keys).map(place).collect()
        };
        sub.mark("place");
        let new_pos = &new_positions;
        let mut removed = Removed::new(target.mesh.clone(), new_pos.clone(), merge);
        // Kept ids: a new vertex whose rounded position equals (bit for bit) a corner of a touched
        // face or an earlier new vertex takes that id, and triangles that collapse are dropped
        // (they have no area; dropping them is an edge collapse, which keeps the surface closed).
        // The map holds the new vertices' positions only, each with the id it takes: the first
        // touched corner at that position (in the order of `faces`), else the first new vertex
        // there in the order of the loop below (`UNSET` until then).
        const UNSET: u32 = u32::MAX;
        let mut kept_new_faces = Vec::new();
        let mut kept_new_provenance = Vec::new();
        let mut kept_ids: FxMap<PositionBits, u32> = Default::default();
        let bits = position_bits;
        if merge {
            kept_ids.reserve(new_pos.len());
            for &p in new_pos.iter() {
                kept_ids.entry(bits(p)).or_insert(UNSET);
            }
            for face in &faces {
                for v in mesh.triangles[face.t as usize] {
                    if let Some(id) = kept_ids.get_mut(&bits(mesh.positions[v as usize]))
                        && *id == UNSET
                    {
                        *id = v;
                    }
                }
            }
        }
        sub.mark("kept ids");
        for TargetFace {
            t,
            pieces,
            statuses,
            ..
        } in &faces
        {
            for (p, &s) in pieces.iter().zip(statuses) {
                for tri in &p.triangles {
                    if s == OUT {
                        let ids = tri.map(|v| match v {
                            Vx::T(i) => i,
                            Vx::X(x) if merge => match kept_ids.get_mut(&bits(new_pos[x as usize]))
                            {
                                Some(id) => {
                                    if *id == UNSET {
                                        *id = nt + x;
                                    }
                                    *id
                                }
                                None => nt + x,
                            },
                            Vx::X(x) => nt + x,
                            Vx::C(_) => u32::MAX,
                        });
                        if ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0] {
                            continue;
                        }
                        kept_new_faces.push(ids);
                        kept_new_provenance.push(*t);
                    } else {
                        // Target pieces have target corners and contour points only.
                        let mut ids = [0u32; 3];
                        for (id, v) in ids.iter_mut().zip(tri) {
                            *id = match *v {
                                Vx::T(i) => i,
                                Vx::X(x) => nt + x,
                                Vx::C(c) => {
                                    return Err(CutError::Internal(format!(
                                        "target face {t} has a piece with cutter vertex {c}"
                                    )));
                                }
                            };
                        }
                        removed.piece_faces.push(ids);
                        removed.piece_provenance.push(*t);
                        removed.piece_sub_cutter.push(s - 1);
                    }
                }
            }
        }
        sub.mark("kept+pieces");
        let mut wall_tris: Vec<([Vx; 3], u32, u32)> = Vec::new();
        for (tris, touched, fallbacks, status_fallbacks) in split_cutter {
            wall_tris.extend(tris);
            stats.touched_cutter_faces += usize::from(touched);
            stats.triangulation_fallbacks += fallbacks;
            stats.status_fallbacks += status_fallbacks;
        }
        let mut walls = PartBuilder::new(merge);
        let mut walls_solid = Vec::with_capacity(wall_tris.len());
        for (tri, f, solid) in &wall_tris {
            // Reversed: walls face out of kept (into the cutter).
            let ids = [tri[0], tri[2], tri[1]]
                .map(|v| walls.vertex(v, &mesh.positions, &cutter.positions, new_pos));
            if walls.push(
                ids,
                Provenance::Cutter(*f),
                cutter.face_component[*f as usize],
            ) {
                walls_solid.push(*solid);
            }
        }
        let contours = contour::chain(&isect.segments, new_pos, |s| {
            cutter.face_component[isect.segments[s].f as usize]
        });
        sub.mark("walls+contours");
        Ok(Output {
            new_positions,
            kept_new_faces,
            kept_new_provenance,
            removed,
            walls: walls.finish(),
            walls_solid,
            contours,
            stats,
            phases: sub,
        })
    };
    let on = phases.on;
    let (
        ((removed_faces, whole_faces, whole_sub_cutter, inside_tests), flood_ms),
        (output, output_ms),
    ) = rayon::join(
        || timed(on, flood),
        || {
            // When the other thread took this branch (0 when at once; the flood fill's time
            // when no other thread was free and this one ran it after the flood fill).
            let start = if on {
                phases.last.elapsed().as_secs_f64() * 1e3
            } else {
                0.0
            };
            let (r, ms) = timed(on, output);
            (r, (start, ms))
        },
    );
    let output = output?;
    phases.record("(flood)", flood_ms);
    phases.record("(output starts)", output_ms.0);
    phases.record("(output)", output_ms.1);
    phases.append(&output.phases);
    phases.mark("flood+output");
    stats.inside_tests += inside_tests;
    stats.touched_cutter_faces += output.stats.touched_cutter_faces;
    stats.triangulation_fallbacks += output.stats.triangulation_fallbacks;
    stats.status_fallbacks += output.stats.status_fallbacks;
    let mut removed = output.removed;
    removed.whole_faces = whole_faces;
    removed.whole_sub_cutter = whole_sub_cutter;
    result.removed_faces = removed_faces;
    result.removed = removed;
    result.new_positions = output.new_positions;
    result.kept_new_faces = output.kept_new_faces;
    result.kept_new_provenance = output.kept_new_provenance;
    result.walls = output.walls;
    result.walls_solid = output.walls_solid;
    result.contours = output.contours;
    result.stats = stats;
    Ok(result)
}

/// A position's bits (`-0.0` as `0.0`), as a key for "the same rounded position". A tuple, not
/// an array: arrays hash as one byte slice, which the integer hasher digests byte by byte.
pub(crate) type PositionBits = (u64, u64, u64);

/// See [`PositionBits`].
#[inline]
pub(crate) fn position_bits(p: DVec3) -> PositionBits {
    let b = p.to_array().map(|c| (c + 0.0).to_bits());
    (b[0], b[1], b[2])
}

/// False when the unperturbed limit of `h` is certainly not a lattice point (then
/// [`HPoint::limit_lattice_point`] is `None`), decided in `f64`: with a non-zero constant
/// weight the limit is `x / w`; a quotient below 2³⁰ in magnitude (a point on a target face
/// is below 2²⁸) is computed with an absolute error below 2³⁰ · 3 · 2⁻⁵³ < 10⁻⁶, so one
/// farther than that from every integer is not one. Saves the exact 128-bit divisions for
/// almost every new vertex.
fn may_be_lattice_point(h: &HPoint) -> bool {
    if h.w[0] == 0 {
        return true;
    }
    let w = h.w[0] as f64;
    h.x.iter().all(|x| {
        let q = x[0] as f64 / w;
        q.abs() > (1u64 << 30) as f64 || (q - q.round()).abs() <= 1e-6
    })
}

/// What stage 6 gives back (see `run`).
struct Output {
    new_positions: Vec<DVec3>,
    kept_new_faces: Vec<[u32; 3]>,
    kept_new_provenance: Vec<u32>,
    /// The removed pieces of split faces (the whole faces come from the flood fill).
    removed: Removed,
    walls: crate::output::Part,
    walls_solid: Vec<u32>,
    contours: Vec<crate::output::Contour>,
    /// The cutter-face counters.
    stats: CutStats,
    phases: Phases,
}

fn unreachable_point() -> HPoint {
    // Intersection points are looked up by id in `split`, never through the corner callback.
    HPoint::target_vertex(&[0, 0, 0])
}

/// Resolves `LoopOf` statuses (a loop's inside is the flip of its container).
fn resolve_loops(pieces: &[Piece], st: &mut [u32], inside_default: u32) -> Result<usize, CutError> {
    for _ in 0..pieces.len() + 1 {
        let mut pending = false;
        for (i, p) in pieces.iter().enumerate() {
            if let PieceStatus::LoopOf { container, inside } = p.status
                && st[i] == UNKNOWN
            {
                let c = st[container];
                if c == UNKNOWN {
                    pending = true;
                } else {
                    st[i] = if c == OUT { inside } else { OUT };
                }
            }
        }
        if !pending {
            break;
        }
    }
    // Safety net (counted in `CutStats::status_fallbacks`, 0 in every test case): a piece whose
    // status the rules above leave open (a loop whose two traversals were not paired) takes the
    // flip of a resolved piece of the same face.
    let mut fallbacks = 0;
    if st.contains(&UNKNOWN) {
        let known = st.iter().copied().find(|&x| x != UNKNOWN).unwrap_or(OUT);
        for x in st.iter_mut().filter(|x| **x == UNKNOWN) {
            *x = if known == OUT { inside_default } else { OUT };
            fallbacks += 1;
        }
    }
    Ok(fallbacks)
}

/// Drops contour segments of a cutter face that end or branch inside it (open or non-manifold
/// targets), repeatedly, so that the rest forms simple paths and loops.
fn prune_segments(segments: &mut Vec<(u32, u32, u32)>, on_boundary: &FxMap<u32, ()>) {
    loop {
        let mut deg: FxMap<u32, u32> = Default::default();
        for &(a, b, _) in segments.iter() {
            *deg.entry(a).or_default() += 1;
            *deg.entry(b).or_default() += 1;
        }
        let bad = |p: u32| {
            let d = deg[&p];
            if on_boundary.contains_key(&p) {
                d != 1
            } else {
                d != 2
            }
        };
        let before = segments.len();
        segments.retain(|&(a, b, _)| !bad(a) && !bad(b));
        if segments.len() == before {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit;

    /// Everything a cut returns, with positions as bits, for exact comparison.
    fn fingerprint(r: &CutResult) -> String {
        let bits =
            |p: &[DVec3]| -> Vec<PositionBits> { p.iter().map(|&q| position_bits(q)).collect() };
        format!(
            "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
            r.removed_faces,
            bits(&r.new_positions),
            r.kept_new_faces,
            r.kept_new_provenance,
            r.walls.mesh.triangles,
            bits(&r.walls.mesh.positions),
            r.walls.provenance,
            r.removed.whole_faces,
            r.removed.piece_faces,
            r.removed.mesh.triangles,
            r.contours
                .iter()
                .map(|c| (bits(&c.points), c.closed, c.sub_cutter))
                .collect::<Vec<_>>(),
            r.removed.sub_cutter,
            r.stats,
        )
    }

    /// The parallel stages merge their results in a fixed order: one thread and four threads
    /// give the same cut, bit for bit (one cutter and two sub-cutters, each large enough for
    /// every stage to run in parallel).
    #[test]
    fn cut_does_not_depend_on_the_thread_count() {
        let index = TargetIndex::build(testkit::geodesic_sphere(40, 10.0)).unwrap();
        let slab = testkit::cube(DVec3::new(-12.0, -3.1, 2.05), DVec3::new(12.0, 3.3, 12.0));
        let a = testkit::cube(DVec3::new(-12.0, -12.0, -4.0), DVec3::new(12.0, 12.0, -3.0));
        let b = testkit::cube(DVec3::new(-2.0, -12.0, -1.0), DVec3::new(2.5, 12.0, 1.5));
        let cut = |threads: usize, cutters: &[&Mesh]| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| subtract_many(&index, cutters).unwrap())
        };
        for cutters in [vec![&slab], vec![&a, &b]] {
            let one = cut(1, &cutters);
            assert!(one.stats.touched_target_faces >= 2 * PARALLEL_MIN);
            assert!(one.removed.whole_faces.len() > 1000);
            assert_eq!(fingerprint(&one), fingerprint(&cut(4, &cutters)));
        }
    }
}
