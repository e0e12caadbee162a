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

use glam::DVec3;

use crate::adjacency::NO_EDGE;
use crate::exact::{self, HPoint, LPoint, Sign};
use crate::phases::Phases;
use crate::target::{Bvh, IBox, TargetIndex};

pub(crate) use crate::fast_hash::FastMap as FxMap;

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
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Crossing {
    pub point: u32,
    pub lo_side: Sign,
}

/// One piece of contour: `t ∩ f` from point `a` to point `b` (unordered).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment {
    pub t: u32,
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
    /// All segments.
    pub segments: Vec<Segment>,
    /// Touched target faces in first-touch order (deterministic iteration); a face's index here
    /// is its slot.
    pub target_order: Vec<u32>,
    /// Segment ids of the touched face in slot `i`: `face_segments[face_segment_start[i]..
    /// face_segment_start[i + 1]]`, in the order found. `face_segment_start` has one more entry
    /// than `target_order`.
    pub face_segments: Vec<u32>,
    pub face_segment_start: Vec<u32>,
    /// Cutter face → its segment ids. Indexed by cutter face.
    pub cutter_faces: Vec<Vec<u32>>,
    /// Crossed target edge → its slot in `edge_crossing_start`.
    pub edge_slot: FxMap<u32, u32>,
    /// EF crossings of the crossed target edge in slot `i`, sorted from `lo` to `hi`:
    /// `edge_crossings[edge_crossing_start[i]..edge_crossing_start[i + 1]]`.
    pub edge_crossings: Vec<Crossing>,
    pub edge_crossing_start: Vec<u32>,
    /// Cutter edge → FE crossings, sorted from `lo` to `hi`. Indexed by cutter edge.
    pub cutter_edges: Vec<Vec<Crossing>>,
    /// Candidate pairs examined.
    pub candidate_pairs: usize,
}

impl Intersections {
    /// Segment ids of the touched target face in slot `slot` (see `target_order`).
    #[inline]
    pub fn segments_of_face(&self, slot: usize) -> &[u32] {
        let (a, b) = (
            self.face_segment_start[slot] as usize,
            self.face_segment_start[slot + 1] as usize,
        );
        &self.face_segments[a..b]
    }

    /// The EF crossings of target edge `e` sorted from `lo` to `hi`, or `None` when the
    /// contour does not cross it.
    #[inline]
    pub fn crossings_of_edge(&self, e: u32) -> Option<&[Crossing]> {
        let slot = *self.edge_slot.get(&e)? as usize;
        let (a, b) = (
            self.edge_crossing_start[slot] as usize,
            self.edge_crossing_start[slot + 1] as usize,
        );
        Some(&self.edge_crossings[a..b])
    }
}

/// Counting sort of `(slot, value)` pairs into compressed rows: the values of each slot in the
/// order given, and the start of each row (`slots + 1` entries).
fn rows<T: Copy + Default>(slots: usize, items: &[(u32, T)]) -> (Vec<T>, Vec<u32>) {
    let mut start = vec![0u32; slots + 1];
    for &(s, _) in items {
        start[s as usize + 1] += 1;
    }
    for i in 0..slots {
        start[i + 1] += start[i];
    }
    let mut next = start.clone();
    let mut values = vec![T::default(); items.len()];
    for &(s, v) in items {
        let n = &mut next[s as usize];
        values[*n as usize] = v;
        *n += 1;
    }
    (values, start)
}

/// One end of a segment as the per-cutter-face pass finds it, before point ids exist: the
/// crossing edge (a target edge for EF, whose cutter face is the pass's; a cutter edge for FE,
/// whose target face is the segment's) and the side of the edge's `lo` vertex.
#[derive(Clone, Copy, Debug)]
enum End {
    Ef { edge: u32, lo_side: Sign },
    Fe { edge: u32, lo_side: Sign },
}

/// What the exact tests find for one cutter face: its segments `(target face, ends)` in the
/// order of its candidates, and how many candidates it had.
#[derive(Default)]
struct FaceHits {
    segments: Vec<(u32, [End; 2])>,
    candidates: usize,
}

/// Below this many cutter faces the exact tests run on the calling thread.
const PARALLEL_FACES: usize = 8;

/// Stage 2: exact intersection of the cutter with the target faces its boxes overlap.
///
/// 2a (parallel over cutter faces): every candidate pair `(t, f)` is tested exactly; a test is
/// a pure function of the pair, so the pass needs no shared state. 2b (sequential, in cutter
/// face order, then candidate order, then the order of the ends): point ids are given on first
/// sight of a key, so the ids, the segments and every list are the same whatever the thread
/// count. 2c (parallel): the exact points. 2d: crossings sorted along every edge.
pub(crate) fn intersect(
    target: &TargetIndex,
    cutter: &PreparedCutter,
) -> Result<Intersections, String> {
    intersect_timed(target, cutter, &mut Phases::new(false))
}

/// [`intersect`], with the time of its stages in `phases`.
pub(crate) fn intersect_timed(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    phases: &mut Phases,
) -> Result<Intersections, String> {
    use rayon::prelude::*;
    let nf = cutter.triangles.len();
    let mut out = Intersections {
        cutter_faces: vec![Vec::new(); nf],
        cutter_edges: vec![Vec::new(); cutter.edges.len()],
        ..Default::default()
    };
    let broad = target.broad_phase(&cutter.face_boxes, |f| cutter.face_points(f));
    phases.mark("broad");
    // 2a.
    let hits: Vec<Result<FaceHits, String>> = if nf >= PARALLEL_FACES {
        (0..nf as u32)
            .into_par_iter()
            .map(|f| face_hits(target, cutter, f, &broad[f as usize]))
            .collect()
    } else {
        (0..nf as u32)
            .map(|f| face_hits(target, cutter, f, &broad[f as usize]))
            .collect()
    };
    drop(broad);
    phases.mark("pairs");
    // 2b.
    let total: usize = hits
        .iter()
        .map(|h| h.as_ref().map_or(0, |h| h.segments.len()))
        .sum();
    let mut ef_ids: FxMap<(u32, u32), u32> = Default::default();
    let mut fe_ids: FxMap<(u32, u32), u32> = Default::default();
    ef_ids.reserve(total + 16);
    fe_ids.reserve(total + 16);
    out.segments.reserve(total);
    out.keys.reserve(total + 16);
    out.target_order.reserve(total);
    out.edge_slot.reserve(total);
    let mut face_slot: FxMap<u32, u32> = Default::default();
    face_slot.reserve(total);
    // (slot, segment id) and (slot, crossing), in the order found.
    let mut face_items: Vec<(u32, u32)> = Vec::with_capacity(total);
    let mut edge_items: Vec<(u32, Crossing)> = Vec::with_capacity(total + 16);
    for (f, h) in hits.into_iter().enumerate() {
        let f = f as u32;
        let h = h?;
        out.candidate_pairs += h.candidates;
        for (t, ends) in h.segments {
            let [a, b] = ends.map(|end| {
                let next = out.keys.len() as u32;
                match end {
                    End::Ef { edge, lo_side } => *ef_ids.entry((edge, f)).or_insert_with(|| {
                        out.keys.push(PointKey::Ef { edge, face: f });
                        let slots = out.edge_slot.len() as u32;
                        let slot = *out.edge_slot.entry(edge).or_insert(slots);
                        edge_items.push((
                            slot,
                            Crossing {
                                point: next,
                                lo_side,
                            },
                        ));
                        next
                    }),
                    End::Fe { edge, lo_side } => *fe_ids.entry((edge, t)).or_insert_with(|| {
                        out.keys.push(PointKey::Fe { edge, face: t });
                        out.cutter_edges[edge as usize].push(Crossing {
                            point: next,
                            lo_side,
                        });
                        next
                    }),
                }
            });
            let id = out.segments.len() as u32;
            out.segments.push(Segment { t, f, a, b });
            let slot = *face_slot.entry(t).or_insert_with(|| {
                out.target_order.push(t);
                out.target_order.len() as u32 - 1
            });
            face_items.push((slot, id));
            out.cutter_faces[f as usize].push(id);
        }
    }
    (out.face_segments, out.face_segment_start) = rows(out.target_order.len(), &face_items);
    (out.edge_crossings, out.edge_crossing_start) = rows(out.edge_slot.len(), &edge_items);
    phases.mark("ids");
    // 2c.
    let point = |key: &PointKey| match *key {
        PointKey::Ef { edge, face } => {
            let [lo, hi] = target.adjacency.edges[edge as usize];
            let [a, b, c] = cutter.face_points(face);
            HPoint::edge_face(
                &target.lpoints[lo as usize],
                &target.lpoints[hi as usize],
                a,
                b,
                c,
            )
        }
        PointKey::Fe { edge, face } => {
            let [lo, hi] = cutter.edges[edge as usize];
            let [u, v, w] = target.face_points(face);
            HPoint::face_edge(
                &cutter.lpoints[lo as usize],
                &cutter.lpoints[hi as usize],
                u,
                v,
                w,
            )
        }
    };
    out.points = if out.keys.len() >= 64 {
        out.keys.par_iter().map(point).collect()
    } else {
        out.keys.iter().map(point).collect()
    };
    phases.mark("points");
    // 2d: sort the crossings along every edge (lo → hi).
    let points = &out.points;
    for (&e, &slot) in out.edge_slot.iter() {
        let (a, b) = (
            out.edge_crossing_start[slot as usize] as usize,
            out.edge_crossing_start[slot as usize + 1] as usize,
        );
        let list = &mut out.edge_crossings[a..b];
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
    phases.mark("sort");
    Ok(out)
}

/// Stage 2a for cutter face `f` and its candidate target faces (ascending): the exact tests of
/// every pair, reusing the plane signs of the early-outs.
///
/// The EF test of target edge `pq` against `f` is [`exact::target_edge_crosses_cutter_face`]
/// and the FE test of cutter edge `ab` against target face `t` is
/// [`exact::cutter_edge_crosses_target_face`], spelled out: their first two signs (the edge's
/// ends against the other face's plane) are the plane signs already computed for the early-out,
/// and the edge–edge signs are shared between the EF and FE tests of the pair. Debug builds
/// check both against the functions of [`crate::exact`].
fn face_hits(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    f: u32,
    candidates: &[u32],
) -> Result<FaceHits, String> {
    let tris = &target.mesh.triangles;
    let ctri = cutter.triangles[f as usize];
    let [a, b, c] = cutter.face_points(f);
    let plane = exact::CutterPlane::new(a, b, c);
    let mut out = FaceHits {
        segments: Vec::new(),
        candidates: candidates.len(),
    };
    for &t in candidates {
        let tri = tris[t as usize];
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            continue; // repeated index: no area, no edges of its own (see the robustness contract)
        }
        let [u, v, w] = target.face_points(t);
        // Early-out: the target face strictly on one side of the cutter plane, or the cutter
        // face strictly on one side of the target plane.
        let s = [u, v, w].map(|p| plane.side(a, b, c, p));
        if s[0] != 0 && s[0] == s[1] && s[1] == s[2] {
            continue;
        }
        let tplane = TargetPlane::new(u, v, w);
        let r = [a, b, c].map(|p| tplane.side(u, v, w, p));
        if r[0] != 0 && r[0] == r[1] && r[1] == r[2] {
            continue;
        }
        // Edge–edge signs `orient3d(t_i, t_i+1, c_j', c_j+1')` for target edge i and cutter
        // edge j, both in their face's corner order; computed on first use.
        let tp = [u, v, w];
        let cp = [a, b, c];
        let mut m = [[2i8; 3]; 3];
        let mut edge_edge = |i: usize, j: usize| -> Sign {
            if m[i][j] == 2 {
                m[i][j] = exact::target_edge_vs_cutter_edge(
                    tp[i],
                    tp[(i + 1) % 3],
                    cp[j],
                    cp[(j + 1) % 3],
                );
            }
            m[i][j]
        };
        let mut ends = [End::Ef {
            edge: 0,
            lo_side: 0,
        }; 2];
        let mut n_ends = 0usize;
        let mut push = |end: End| -> Result<(), String> {
            if n_ends >= 2 {
                return Err(format!(
                    "target face {t} and cutter face {f} meet in more than two points"
                ));
            }
            ends[n_ends] = end;
            n_ends += 1;
            Ok(())
        };
        // EF: target edge i (corners i → i+1) against the cutter face.
        for i in 0..3 {
            let e = target.adjacency.triangle_edges[t as usize][i];
            if e == NO_EDGE {
                continue;
            }
            let (si, sj) = (s[i], s[(i + 1) % 3]);
            let hit = if si == 0 || sj == 0 || si == sj {
                None
            } else {
                // Orient the edge as the adjacency stores it (lo → hi): reversing it flips the
                // edge–edge signs and swaps the end sides.
                // The adjacency stores edges as `[lo, hi]` with `lo < hi`.
                let forward = tri[i] < tri[(i + 1) % 3];
                debug_assert_eq!(forward, target.adjacency.edges[e as usize][0] == tri[i]);
                let flip: Sign = if forward { 1 } else { -1 };
                let e1 = flip * edge_edge(i, 0);
                if e1 != 0 && flip * edge_edge(i, 1) == e1 && flip * edge_edge(i, 2) == e1 {
                    Some(if forward { si } else { sj })
                } else {
                    None
                }
            };
            #[cfg(debug_assertions)]
            {
                let [lo, hi] = target.adjacency.edges[e as usize];
                let (p, q) = (&target.lpoints[lo as usize], &target.lpoints[hi as usize]);
                debug_assert_eq!(hit, exact::target_edge_crosses_cutter_face(p, q, a, b, c));
            }
            if let Some(lo_side) = hit {
                push(End::Ef { edge: e, lo_side })?;
            }
        }
        // FE: cutter edge j (corners j → j+1) against the target face.
        for j in 0..3 {
            let g = cutter.tri_edges[f as usize][j];
            let (rj, rk) = (r[j], r[(j + 1) % 3]);
            let hit = if rj == 0 || rk == 0 || rj == rk {
                None
            } else {
                // orient3d(u, v, a', b') over the target edges, with the cutter edge oriented
                // lo → hi as stored.
                let forward = cutter.edges[g as usize][0] == ctri[j];
                let flip: Sign = if forward { 1 } else { -1 };
                let e1 = flip * edge_edge(0, j);
                if e1 != 0 && flip * edge_edge(1, j) == e1 && flip * edge_edge(2, j) == e1 {
                    Some(if forward { rj } else { rk })
                } else {
                    None
                }
            };
            #[cfg(debug_assertions)]
            {
                let [lo, hi] = cutter.edges[g as usize];
                let (pa, pb) = (&cutter.lpoints[lo as usize], &cutter.lpoints[hi as usize]);
                debug_assert_eq!(hit, exact::cutter_edge_crosses_target_face(pa, pb, u, v, w));
            }
            if let Some(lo_side) = hit {
                push(End::Fe { edge: g, lo_side })?;
            }
        }
        match n_ends {
            0 => {}
            2 => out.segments.push((t, ends)),
            _ => {
                return Err(format!(
                    "target face {t} and cutter face {f} meet in {n_ends} point(s)"
                ));
            }
        }
    }
    Ok(out)
}

/// The plane of a target face, for the early-out of a pair: `value(a) = n · (a − u)`, which is
/// exactly `orient3d(u, v, w, a)` (unperturbed).
struct TargetPlane {
    n: [i128; 3],
}

impl TargetPlane {
    fn new(u: &LPoint, v: &LPoint, w: &LPoint) -> TargetPlane {
        TargetPlane {
            n: exact::normal(u, v, w),
        }
    }

    /// Side of perturbed cutter point `a'`: the sign of
    /// [`exact::cutter_point_vs_target_plane`], cheaper when `a` is off the plane.
    #[inline]
    fn side(&self, u: &LPoint, v: &LPoint, w: &LPoint, a: &LPoint) -> Sign {
        let d = [0, 1, 2].map(|k| (a[k] - u[k]) as i128);
        let value = self.n[0] * d[0] + self.n[1] * d[1] + self.n[2] * d[2];
        if value != 0 {
            value.signum() as Sign
        } else {
            exact::cutter_point_vs_target_plane(u, v, w, a)
        }
    }
}

/// Builds the BVH of the cutter faces (for its self-intersection check).
pub(crate) fn cutter_bvh(cutter: &PreparedCutter) -> Bvh {
    Bvh::build(&cutter.face_boxes)
}
