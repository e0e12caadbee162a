//! Stage 4 of the boolean: the touched target faces are split along the contour, and the
//! touched cutter faces once per region solid they meet (each solid's walls are split by that
//! solid's contour only, so every region's kept + walls closes on its own); then every piece
//! gets its status (outside, or inside which sub-cutter).

use rayon::prelude::*;

use super::error::CutError;
use super::inputs::{CutInputs, PARALLEL_MIN};
use crate::adjacency::NO_EDGE;
use crate::classify;
use crate::exact::{self, HPoint};
use crate::intersect::{self, FxMap};
use crate::output::CutStats;
use crate::solids::{SolidSets, solid_of_face};
use crate::split::{self, FaceInput, OUT, Piece, PieceStatus, UNKNOWN, Vx};

/// Per touched face (in `isect.target_order`): its pieces, the statuses the crossings give
/// them (`UNKNOWN` otherwise), the triangulation fallbacks, the status of each corner's piece
/// when known, and which of its sides the contour crosses (bit k: side k).
pub(crate) struct TargetFace {
    pub slot: usize,
    pub t: u32,
    pub pieces: Vec<Piece>,
    pub statuses: Vec<u32>,
    pub fallbacks: usize,
    pub corner_status: [u32; 3],
    pub crossed: u8,
}

/// Buffers of one worker, reused from face to face.
#[derive(Default)]
struct Buffers {
    boundary: Vec<Vx>,
    arc_status: Vec<u32>,
    segments: Vec<(u32, u32, u32)>,
}

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

/// Per cutter face: its wall triangles with their cutter face and solid, whether the contour
/// splits it, and the fallbacks of the triangulation and of the statuses.
pub(crate) type CutterFaceWalls = (Vec<([Vx; 3], u32, u32)>, bool, usize, usize);

/// Splits the touched target faces and every cutter face, independently: in parallel when there
/// are enough of them (the target faces and the cutter faces at once, so that the threads share
/// the work). `cutter_in` and `sets` are stage 3's vertex solids.
pub(crate) fn split_faces(
    cut: &CutInputs,
    cutter_in: &[u32],
    sets: &SolidSets,
) -> Result<(Vec<TargetFace>, Vec<CutterFaceWalls>), CutError> {
    let isect = cut.isect;
    let split_walls = || -> Result<Vec<CutterFaceWalls>, CutError> {
        let cutter_faces = 0..cut.cutter.triangles.len() as u32;
        let one = |f| split_cutter_face(cut, cutter_in, sets, f);
        if isect.segments.len() >= PARALLEL_MIN {
            cutter_faces.into_par_iter().map(one).collect()
        } else {
            cutter_faces.map(one).collect()
        }
    };
    let split_targets = || -> Result<Vec<TargetFace>, CutError> {
        if isect.target_order.len() >= PARALLEL_MIN {
            (0..isect.target_order.len())
                .into_par_iter()
                .map_init(Buffers::default, |buf, slot| {
                    split_target_face(cut, buf, slot)
                })
                .collect()
        } else {
            let mut buf = Buffers::default();
            (0..isect.target_order.len())
                .map(|slot| split_target_face(cut, &mut buf, slot))
                .collect()
        }
    };
    let (faces, walls) = rayon::join(split_targets, split_walls);
    Ok((faces?, walls?))
}

/// The exact point of a face corner (a target or cutter vertex).
fn corner_point(cut: &CutInputs, v: Vx) -> HPoint {
    match v {
        Vx::T(i) => HPoint::target_vertex(&cut.target.lpoints[i as usize]),
        Vx::C(i) => HPoint::cutter_vertex(&cut.cutter.lpoints[i as usize]),
        Vx::X(_) => unreachable_point(),
    }
}

/// Splits the touched target face in `slot` of `isect.target_order`.
fn split_target_face(
    cut: &CutInputs,
    buf: &mut Buffers,
    slot: usize,
) -> Result<TargetFace, CutError> {
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let corner = |v: Vx| corner_point(cut, v);
    let mesh = &target.mesh;
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
            let f = cut.face_of_point(x.point);
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
        corner_point: &corner,
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
}

/// Splits cutter face `f` once per region solid it meets (its corners lie in, or its contour
/// belongs to).
fn split_cutter_face(
    cut: &CutInputs,
    cutter_in: &[u32],
    sets: &SolidSets,
    f: u32,
) -> Result<CutterFaceWalls, CutError> {
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let corner = |v: Vx| corner_point(cut, v);
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
                if cut.solid_of_point(x.point) != solid {
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
            corner_point: &corner,
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
}

/// Statuses of the target pieces the crossings leave open (rare: faces that only contour loops
/// cross). A piece without crossings on its boundary takes the status of one of its corners
/// known from another face (a vertex has one status), else one inside test; a loop's inside is
/// the flip of its container.
pub(crate) fn resolve_piece_statuses(
    cut: &CutInputs,
    faces: &mut [TargetFace],
    stats: &mut CutStats,
) -> Result<(), CutError> {
    let (target, cutter, isect) = (cut.target, cut.cutter, cut.isect);
    let mesh = &target.mesh;
    let open = |f: &TargetFace| {
        f.pieces
            .iter()
            .zip(&f.statuses)
            .any(|(p, &s)| s == UNKNOWN && matches!(p.status, PieceStatus::Default))
    };
    if faces.iter().any(open) {
        let mut vertex_status: FxMap<u32, u32> = Default::default();
        for f in faces.iter() {
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
    Ok(())
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
