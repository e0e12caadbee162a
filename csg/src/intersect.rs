//! Stages 1–2 of the boolean: the prepared cutter, and the exact intersection of its faces with
//! the target faces its boxes overlap.
//!
//! # Notation
//! - `t`: target face, `f`: cutter face, `e`: target edge (adjacency id), `g`: cutter edge.
//! - EF point `(e, f)`: target edge `e` crosses cutter face `f`. FE point `(g, t)`: cutter edge
//!   `g` crosses target face `t`. Under the tie-break rule ([`crate::exact`]) these are the only
//!   kinds of contact, each transversal, so a point is identified by its key and computed once:
//!   every face that uses it gets the same id (neighbours weld bit for bit).
//! - Segment `(t, f)`: `t ∩ f`, exactly two endpoints (EF points on t's edges, FE points on f's
//!   edges), or empty.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use glam::DVec3;

use crate::adjacency::NO_EDGE;
use crate::exact::{self, HPoint, LPoint, Sign};
use crate::target::{Bvh, IBox, TargetIndex};

/// A small, fast, non-cryptographic hasher for integer keys (FxHash's multiply-rotate).
#[derive(Default, Clone, Copy)]
pub(crate) struct FxHasher(u64);

impl Hasher for FxHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
}

pub(crate) type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// The cutter after validation: lattice coordinates, edges, components, boxes.
#[derive(Clone, Debug)]
pub(crate) struct PreparedCutter {
    /// World positions (exact input coordinates).
    pub positions: Vec<DVec3>,
    /// Lattice coordinates; same length as `positions`.
    pub lpoints: Vec<LPoint>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Undirected edges `[lo, hi]`, `lo < hi`.
    pub edges: Vec<[u32; 2]>,
    /// Per triangle: edge id of corner `k → k+1`.
    pub tri_edges: Vec<[u32; 3]>,
    /// Per face: sub-cutter id.
    pub face_component: Vec<u32>,
    /// Number of sub-cutters.
    pub components: u32,
    /// Per face: lattice box.
    pub face_boxes: Vec<IBox>,
    /// Lattice box of the whole cutter.
    pub bounds: IBox,
}

impl PreparedCutter {
    pub fn face_points(&self, f: u32) -> [&LPoint; 3] {
        let t = &self.triangles[f as usize];
        [
            &self.lpoints[t[0] as usize],
            &self.lpoints[t[1] as usize],
            &self.lpoints[t[2] as usize],
        ]
    }
}

/// Key of an intersection point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum PointKey {
    /// Target edge × cutter face.
    Ef { edge: u32, face: u32 },
    /// Cutter edge × target face.
    Fe { edge: u32, face: u32 },
}

/// A crossing found on an edge: the point id and the side of the edge's `lo` vertex relative to
/// the other mesh's face (+1 above, −1 below).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossing {
    pub point: u32,
    pub lo_side: Sign,
}

/// One piece of contour: `t ∩ f` from point `a` to point `b` (unordered).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment {
    pub f: u32,
    pub a: u32,
    pub b: u32,
}

/// Everything stage 2 finds.
#[derive(Default)]
pub(crate) struct Intersections {
    /// Exact points; ids index this.
    pub points: Vec<HPoint>,
    /// Key of each point.
    pub keys: Vec<PointKey>,
    /// Memo of EF tests: `(target edge, cutter face)`.
    pub ef: FxMap<(u32, u32), Option<Crossing>>,
    /// Memo of FE tests: `(cutter edge, target face)`.
    pub fe: FxMap<(u32, u32), Option<Crossing>>,
    /// All segments.
    pub segments: Vec<Segment>,
    /// Target face → its segment ids (only touched faces appear), in first-touch order.
    pub target_faces: FxMap<u32, Vec<u32>>,
    /// Touched target faces in first-touch order (deterministic iteration).
    pub target_order: Vec<u32>,
    /// Cutter face → its segment ids. Indexed by cutter face.
    pub cutter_faces: Vec<Vec<u32>>,
    /// Target edge → EF crossings, sorted from `lo` to `hi`.
    pub target_edges: FxMap<u32, Vec<Crossing>>,
    /// Cutter edge → FE crossings, sorted from `lo` to `hi`. Indexed by cutter edge.
    pub cutter_edges: Vec<Vec<Crossing>>,
    /// Candidate pairs examined.
    pub candidate_pairs: usize,
}

/// Stage 2: exact intersection of the cutter with the target faces its boxes overlap.
pub(crate) fn intersect(
    target: &TargetIndex,
    cutter: &PreparedCutter,
) -> Result<Intersections, String> {
    let mut out = Intersections {
        cutter_faces: vec![Vec::new(); cutter.triangles.len()],
        cutter_edges: vec![Vec::new(); cutter.edges.len()],
        ..Default::default()
    };
    let tris = &target.mesh.triangles;
    let broad = target.broad_phase(&cutter.face_boxes, |f| cutter.face_points(f));
    // Room for the memos up front (growing them rehashed every entry several times).
    let pairs: usize = broad.iter().map(Vec::len).sum();
    out.ef.reserve(2 * pairs);
    out.fe.reserve(2 * pairs);
    for f in 0..cutter.triangles.len() as u32 {
        let candidates = &broad[f as usize];
        let [a, b, c] = cutter.face_points(f);
        let plane = exact::CutterPlane::new(a, b, c);
        for &t in candidates {
            out.candidate_pairs += 1;
            let tri = tris[t as usize];
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
                continue; // repeated index: no area, no edges of its own (see the robustness contract)
            }
            let [u, v, w] = target.face_points(t);
            // Early-out: the target face strictly on one side of the cutter plane, or the
            // cutter face strictly on one side of the target plane.
            let s = [u, v, w].map(|p| plane.side(a, b, c, p));
            if s[0] != 0 && s[0] == s[1] && s[1] == s[2] {
                continue;
            }
            let r = [a, b, c].map(|p| exact::cutter_point_vs_target_plane(u, v, w, p));
            if r[0] != 0 && r[0] == r[1] && r[1] == r[2] {
                continue;
            }
            let mut ends: [u32; 2] = [u32::MAX; 2];
            let mut n_ends = 0usize;
            let mut push = |p: u32| -> Result<(), String> {
                if n_ends >= 2 {
                    return Err(format!(
                        "target face {t} and cutter face {f} meet in more than two points"
                    ));
                }
                ends[n_ends] = p;
                n_ends += 1;
                Ok(())
            };
            for k in 0..3 {
                let e = target.adjacency.triangle_edges[t as usize][k];
                if e == NO_EDGE {
                    continue;
                }
                if let Some(x) = edge_face(target, cutter, &mut out, e, f) {
                    push(x.point)?;
                }
            }
            for k in 0..3 {
                let g = cutter.tri_edges[f as usize][k];
                if let Some(x) = face_edge(target, cutter, &mut out, g, t) {
                    push(x.point)?;
                }
            }
            match n_ends {
                0 => {}
                2 => {
                    let id = out.segments.len() as u32;
                    out.segments.push(Segment {
                        f,
                        a: ends[0],
                        b: ends[1],
                    });
                    out.target_faces
                        .entry(t)
                        .or_insert_with(|| {
                            out.target_order.push(t);
                            Vec::new()
                        })
                        .push(id);
                    out.cutter_faces[f as usize].push(id);
                }
                _ => {
                    return Err(format!(
                        "target face {t} and cutter face {f} meet in {n_ends} point(s)"
                    ));
                }
            }
        }
    }
    // Sort the crossings along every edge (lo → hi).
    let points = &out.points;
    for (&e, list) in out.target_edges.iter_mut() {
        if list.len() > 1 {
            let [lo, hi] = target.adjacency.edges[e as usize];
            let (p, q) = (&target.lpoints[lo as usize], &target.lpoints[hi as usize]);
            let dir = [
                (q[0] - p[0]) as i128,
                (q[1] - p[1]) as i128,
                (q[2] - p[2]) as i128,
            ];
            list.sort_by(|x, y| {
                exact::cmp_along(&points[x.point as usize], &points[y.point as usize], &dir)
            });
        }
    }
    for (g, list) in out.cutter_edges.iter_mut().enumerate() {
        if list.len() > 1 {
            let [lo, hi] = cutter.edges[g];
            let (p, q) = (&cutter.lpoints[lo as usize], &cutter.lpoints[hi as usize]);
            let dir = [
                (q[0] - p[0]) as i128,
                (q[1] - p[1]) as i128,
                (q[2] - p[2]) as i128,
            ];
            list.sort_by(|x, y| {
                exact::cmp_along(&points[x.point as usize], &points[y.point as usize], &dir)
            });
        }
    }
    Ok(out)
}

/// EF test of target edge `e` against cutter face `f`, memoized.
fn edge_face(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    out: &mut Intersections,
    e: u32,
    f: u32,
) -> Option<Crossing> {
    if let Some(r) = out.ef.get(&(e, f)) {
        return *r;
    }
    let [lo, hi] = target.adjacency.edges[e as usize];
    let (p, q) = (&target.lpoints[lo as usize], &target.lpoints[hi as usize]);
    let [a, b, c] = cutter.face_points(f);
    let r = exact::target_edge_crosses_cutter_face(p, q, a, b, c).map(|lo_side| {
        let point = out.points.len() as u32;
        out.points.push(HPoint::edge_face(p, q, a, b, c));
        out.keys.push(PointKey::Ef { edge: e, face: f });
        let x = Crossing { point, lo_side };
        out.target_edges.entry(e).or_default().push(x);
        x
    });
    out.ef.insert((e, f), r);
    r
}

/// FE test of cutter edge `g` against target face `t`, memoized.
fn face_edge(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    out: &mut Intersections,
    g: u32,
    t: u32,
) -> Option<Crossing> {
    if let Some(r) = out.fe.get(&(g, t)) {
        return *r;
    }
    let [lo, hi] = cutter.edges[g as usize];
    let (a, b) = (&cutter.lpoints[lo as usize], &cutter.lpoints[hi as usize]);
    let [u, v, w] = target.face_points(t);
    let r = exact::cutter_edge_crosses_target_face(a, b, u, v, w).map(|lo_side| {
        let point = out.points.len() as u32;
        out.points.push(HPoint::face_edge(a, b, u, v, w));
        out.keys.push(PointKey::Fe { edge: g, face: t });
        let x = Crossing { point, lo_side };
        out.cutter_edges[g as usize].push(x);
        x
    });
    out.fe.insert((g, t), r);
    r
}

/// Builds the BVH of the cutter faces (for its self-intersection check).
pub(crate) fn cutter_bvh(cutter: &PreparedCutter) -> Bvh {
    Bvh::build(&cutter.face_boxes)
}
