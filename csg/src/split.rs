//! Stage 3 of the boolean: split one face along its contour segments and triangulate the pieces.
//!
//! # Notation
//! - Boundary: the face's corners and the crossing points on its edges, counter-clockwise seen
//!   from the face normal. A crossing node has exactly one inward segment (under the tie-break
//!   rule a crossing point lies inside exactly one face of the other mesh).
//! - Chain: contour segments inside the face. Interior nodes have degree 2 (a closed manifold
//!   cutter; for cutter faces, branches and dead ends from open or non-manifold targets are
//!   pruned first, see the robustness contract).
//! - Half-edge `h`: boundary half-edges `0..B` (node `i → i+1`), then two per segment.
//!
//! # Stages
//! 1. Trace the cycles: the face to the left of a boundary half-edge turns into the chain at a
//!    crossing node; the face to the left of a chain half-edge arriving at the boundary
//!    continues forward along it. No geometry is needed for this.
//! 2. Loops (cycles of chain only) are traversed twice; the counter-clockwise traversal is the
//!    loop's inside piece, the clockwise one a hole of the innermost piece containing it
//!    (exact point-in-polygon).
//! 3. Triangulate each piece: bridge holes, then ear-clip, with exact [`crate::exact::orient2d`]
//!    on the homogeneous points (zero-area faces: a fan, geometry is moot there).

use crate::exact::{self, HPoint, Sign};
use crate::polygon::{fan, point_in_polygon, polygon_orientation, triangulate};
pub(crate) use crate::small::Small;

/// A vertex of a face arrangement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Vx {
    /// Target vertex.
    T(u32),
    /// Cutter vertex.
    C(u32),
    /// Intersection point.
    X(u32),
}

/// Status code: outside the other mesh.
pub(crate) const OUT: u32 = 0;
/// Status code: not known yet.
pub(crate) const UNKNOWN: u32 = u32::MAX;

/// How a piece's status is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PieceStatus {
    /// Known from a boundary arc next to a crossing.
    Known(u32),
    /// The face's status without crossings (its corners' status, decided by the caller).
    Default,
    /// Inside a loop: the flip of the container piece (`inside` is the status on the far side of
    /// the loop when the container is outside).
    LoopOf { container: usize, inside: u32 },
}

/// A piece of a face.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Piece {
    pub status: PieceStatus,
    /// Triangles, counter-clockwise seen from the face normal.
    pub triangles: Small<[Vx; 3], 2>,
    /// The face corners on this piece's boundary.
    pub corners: Small<u32, 3>,
}

/// The input of [`split_face`].
pub(crate) struct FaceInput<'a> {
    /// Boundary nodes, counter-clockwise.
    pub boundary: &'a [Vx],
    /// Per boundary node: for a crossing node, the status of the boundary arc that ends at it;
    /// `UNKNOWN` for corners.
    pub arc_status: &'a [u32],
    /// Segments inside the face, as point-id pairs, and per segment the status beyond it when
    /// the other side is outside.
    pub segments: &'a [(u32, u32, u32)],
    /// Exact points by id.
    pub points: &'a [HPoint],
    /// Exact point of a corner vertex.
    pub corner_point: &'a dyn Fn(Vx) -> HPoint,
    /// Projection of the face: dominant normal axis and its sign; `None` for a zero normal.
    pub projection: Option<(usize, Sign)>,
}

/// Result of [`split_face`].
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct FaceSplit {
    pub pieces: Vec<Piece>,
    /// Polygons that needed the topology-only fallback of the ear clipper.
    pub fallbacks: usize,
}

/// Splits one face (see the module doc). `Err` only for an inconsistent arrangement (a bug).
pub(crate) fn split_face(input: &FaceInput) -> Result<FaceSplit, String> {
    if let Some(split) = split_once(input) {
        debug_assert_eq!(Ok(&split), split_general(input).as_ref());
        return Ok(split);
    }
    split_general(input)
}

/// The common case in a few steps: one segment across the face from one boundary crossing to
/// the other (97% of the target faces a strip cutter touches). The result is exactly what
/// [`split_general`] gives (debug builds check it): tracing from boundary half-edge 0, the
/// first piece is the boundary from corner 0 to the first crossing `i`, the segment, and the
/// boundary from the second crossing `j` back to corner 0; the second is the boundary from `i`
/// to `j` and the segment back. One piece is a triangle and the other a quadrilateral, strictly
/// convex in the perturbed configuration (its crossings lie inside two different edges), which
/// the ear clipper cuts at its first vertex. `None` for anything else, or if the quadrilateral
/// is not strictly convex after all: the general path decides then.
fn split_once(input: &FaceInput) -> Option<FaceSplit> {
    let (axis, sgn) = input.projection?;
    let [(a, b, _)] = input.segments[..] else {
        return None;
    };
    let nb = input.boundary.len();
    if nb != 5 || matches!(input.boundary[0], Vx::X(_)) {
        return None;
    }
    let mut crossings = (1..nb).filter(|&n| matches!(input.boundary[n], Vx::X(_)));
    let (i, j) = (crossings.next()?, crossings.next()?);
    if crossings.next().is_some() {
        return None;
    }
    let (Vx::X(pi), Vx::X(pj)) = (input.boundary[i], input.boundary[j]) else {
        return None;
    };
    if !((pi == a && pj == b) || (pi == b && pj == a)) || pi == pj {
        return None;
    }
    // The nodes of the two pieces (3 or 4 each), in tracing order.
    let mut first = [0usize; 4];
    let mut n_first = 0;
    for n in (0..=i).chain(j..nb) {
        *first.get_mut(n_first)? = n;
        n_first += 1;
    }
    let mut second = [0usize; 4];
    let mut n_second = 0;
    for n in i..=j {
        *second.get_mut(n_second)? = n;
        n_second += 1;
    }
    let point = |n: usize| match input.boundary[n] {
        Vx::X(p) => input.points[p as usize],
        v => (input.corner_point)(v),
    };
    let mut pieces = Vec::with_capacity(2);
    for (nodes, at) in [(&first[..n_first], i), (&second[..n_second], j)] {
        let status = match input.arc_status[at] {
            UNKNOWN => PieceStatus::Default,
            s => PieceStatus::Known(s),
        };
        let corners = nodes
            .iter()
            .filter_map(|&n| match input.boundary[n] {
                Vx::T(v) | Vx::C(v) => Some(v),
                Vx::X(_) => None,
            })
            .collect();
        let q = |k: usize| input.boundary[nodes[k]];
        let triangles = match nodes.len() {
            3 => [[q(0), q(1), q(2)]].into_iter().collect(),
            4 => {
                let approx = [0, 1, 2, 3].map(|k| match input.boundary[nodes[k]] {
                    Vx::X(p) => input.points[p as usize].approx(axis),
                    v => (input.corner_point)(v).approx(axis),
                });
                let convex = (0..4).all(|k| {
                    let (u, v, w) = ((k + 3) % 4, k, (k + 1) % 4);
                    sgn * exact::orient2d_filter(&approx[u], &approx[v], &approx[w]).unwrap_or_else(
                        || {
                            let [pu, pv, pw] = [u, v, w].map(|k| point(nodes[k]));
                            exact::orient2d_exact(&pu, &pv, &pw, axis)
                        },
                    ) > 0
                });
                if !convex {
                    return None;
                }
                [[q(3), q(0), q(1)], [q(1), q(2), q(3)]]
                    .into_iter()
                    .collect()
            }
            _ => return None,
        };
        pieces.push(Piece {
            status,
            triangles,
            corners,
        });
    }
    Some(FaceSplit {
        pieces,
        fallbacks: 0,
    })
}

/// [`split_face`] for any arrangement.
fn split_general(input: &FaceInput) -> Result<FaceSplit, String> {
    let nb = input.boundary.len();
    // Stage 1: nodes and half-edges.
    // Node ids: boundary 0..nb, then interior chain nodes.
    let mut node_of_point: crate::intersect::FxMap<u32, usize> = Default::default();
    let mut nodes: Vec<Vx> = input.boundary.to_vec();
    for (i, v) in input.boundary.iter().enumerate() {
        if let Vx::X(p) = v {
            node_of_point.insert(*p, i);
        }
    }
    let mut node = |p: u32, nodes: &mut Vec<Vx>| -> usize {
        *node_of_point.entry(p).or_insert_with(|| {
            nodes.push(Vx::X(p));
            nodes.len() - 1
        })
    };
    let ns = input.segments.len();
    let mut seg_nodes = Vec::with_capacity(ns);
    for &(a, b, _) in input.segments {
        let (na, nb_) = (node(a, &mut nodes), node(b, &mut nodes));
        seg_nodes.push((na, nb_));
    }
    let nn = nodes.len();
    // Incident segments per node (at most 2 used).
    let mut inc: Vec<[u32; 2]> = vec![[u32::MAX; 2]; nn];
    let mut deg = vec![0u8; nn];
    for (s, &(a, b)) in seg_nodes.iter().enumerate() {
        for n in [a, b] {
            if deg[n] >= 2 {
                return Err(format!("arrangement node of degree > 2 ({:?})", nodes[n]));
            }
            inc[n][deg[n] as usize] = s as u32;
            deg[n] += 1;
        }
    }
    for n in 0..nn {
        let want = if n < nb {
            if matches!(nodes[n], Vx::X(_)) { 1 } else { 0 }
        } else {
            2
        };
        if deg[n] != want && !(n < nb && deg[n] == 0) {
            return Err(format!(
                "arrangement node {:?} has degree {} (expected {want})",
                nodes[n], deg[n]
            ));
        }
    }
    // Half-edges: boundary i (i → i+1), chain 2s (a → b), 2s+1 (b → a); index nb + ...
    let nh = nb + 2 * ns;
    let head = |h: usize| -> usize {
        if h < nb {
            (h + 1) % nb
        } else {
            let s = (h - nb) / 2;
            if (h - nb).is_multiple_of(2) {
                seg_nodes[s].1
            } else {
                seg_nodes[s].0
            }
        }
    };
    let tail = |h: usize| -> usize {
        if h < nb {
            h
        } else {
            let s = (h - nb) / 2;
            if (h - nb).is_multiple_of(2) {
                seg_nodes[s].0
            } else {
                seg_nodes[s].1
            }
        }
    };
    // The half-edge leaving node n along segment s.
    let leave = |n: usize, s: u32| -> usize {
        let s = s as usize;
        if seg_nodes[s].0 == n {
            nb + 2 * s
        } else {
            nb + 2 * s + 1
        }
    };
    let next = |h: usize| -> usize {
        let n = head(h);
        if h < nb {
            if n < nb && deg[n] == 1 {
                leave(n, inc[n][0])
            } else {
                n
            }
        } else if n < nb {
            n
        } else {
            let s_in = ((h - nb) / 2) as u32;
            let other = if inc[n][0] == s_in {
                inc[n][1]
            } else {
                inc[n][0]
            };
            leave(n, other)
        }
    };
    // Stage 1b: trace.
    struct Cycle {
        nodes: Vec<usize>,
        on_boundary: bool,
        status: u32,
        inside: u32,
    }
    let mut used = vec![false; nh];
    let mut cycles: Vec<Cycle> = Vec::new();
    for start in 0..nh {
        if used[start] {
            continue;
        }
        let mut c = Cycle {
            nodes: Vec::new(),
            on_boundary: false,
            status: UNKNOWN,
            inside: UNKNOWN,
        };
        let mut h = start;
        loop {
            if used[h] {
                if h != start {
                    return Err("arrangement tracing did not close".into());
                }
                break;
            }
            used[h] = true;
            c.nodes.push(tail(h));
            if h < nb {
                c.on_boundary = true;
                let n = head(h);
                if n < nb && deg[n] == 1 && c.status == UNKNOWN {
                    c.status = input.arc_status[n];
                }
            } else if c.inside == UNKNOWN {
                c.inside = input.segments[(h - nb) / 2].2;
            }
            h = next(h);
            if c.nodes.len() > nh {
                return Err("arrangement tracing looped".into());
            }
        }
        cycles.push(c);
    }
    // Stage 2: orientation of loops, then containment.
    let proj = input.projection;
    let all_pts: Vec<HPoint> = nodes
        .iter()
        .map(|&v| match v {
            Vx::X(p) => input.points[p as usize],
            v => (input.corner_point)(v),
        })
        .collect();
    let hp = |n: usize| -> HPoint { all_pts[n] };
    let mut pieces_cycles: Vec<usize> = Vec::new(); // outer cycles
    let mut holes: Vec<usize> = Vec::new();
    for (i, c) in cycles.iter().enumerate() {
        if c.on_boundary {
            pieces_cycles.push(i);
        } else {
            let Some((axis, sgn)) = proj else {
                return Err("loop inside a zero-area face".into());
            };
            let pts: Vec<HPoint> = c.nodes.iter().map(|&n| hp(n)).collect();
            if polygon_orientation(&pts, axis) * sgn > 0 {
                pieces_cycles.push(i);
            } else {
                holes.push(i);
            }
        }
    }
    let mut piece_of_cycle = vec![usize::MAX; cycles.len()];
    let mut pieces: Vec<Piece> = Vec::new();
    for &ci in &pieces_cycles {
        piece_of_cycle[ci] = pieces.len();
        let c = &cycles[ci];
        let corners = c
            .nodes
            .iter()
            .filter_map(|&n| match nodes[n] {
                Vx::T(v) | Vx::C(v) => Some(v),
                Vx::X(_) => None,
            })
            .collect();
        let status = if c.on_boundary {
            if c.status != UNKNOWN {
                PieceStatus::Known(c.status)
            } else {
                PieceStatus::Default
            }
        } else {
            // Filled in below once the container is known.
            PieceStatus::Default
        };
        pieces.push(Piece {
            status,
            triangles: Small::default(),
            corners,
        });
    }
    // Container of every hole: the innermost outer cycle containing one of its points.
    let mut piece_holes: Vec<Vec<usize>> = vec![Vec::new(); pieces.len()];
    if !holes.is_empty() {
        let (axis, _) = proj.ok_or("loop inside a zero-area face")?;
        let polys: Vec<Vec<HPoint>> = pieces_cycles
            .iter()
            .map(|&ci| cycles[ci].nodes.iter().map(|&n| hp(n)).collect())
            .collect();
        for &hi in &holes {
            let probe = hp(cycles[hi].nodes[0]);
            // The loop's own inside piece has the same nodes in reverse; skip it.
            let mut own = usize::MAX;
            let mut best: Option<usize> = None;
            for (pi, &ci) in pieces_cycles.iter().enumerate() {
                let c = &cycles[ci];
                if !c.on_boundary && c.nodes.len() == cycles[hi].nodes.len() && {
                    let mut a = c.nodes.clone();
                    let mut b = cycles[hi].nodes.clone();
                    a.sort_unstable();
                    b.sort_unstable();
                    a == b
                } {
                    own = pi;
                    continue;
                }
                if !point_in_polygon(&probe, &polys[pi], axis) {
                    continue;
                }
                best = match best {
                    None => Some(pi),
                    Some(b) => {
                        // Keep the inner one: `pi` is inside `b` when a point of it is.
                        if point_in_polygon(&polys[pi][0], &polys[b], axis) {
                            Some(pi)
                        } else {
                            Some(b)
                        }
                    }
                };
            }
            let container = best.ok_or("a contour loop lies outside every piece")?;
            piece_holes[container].push(hi);
            if own != usize::MAX {
                pieces[own].status = PieceStatus::LoopOf {
                    container,
                    inside: cycles[hi].inside,
                };
            }
        }
    }
    // Stage 3: triangulate.
    let mut fallbacks = 0;
    for (pi, &ci) in pieces_cycles.iter().enumerate() {
        let outer: Vec<usize> = cycles[ci].nodes.clone();
        let hole_nodes: Vec<Vec<usize>> = piece_holes[pi]
            .iter()
            .map(|&h| cycles[h].nodes.clone())
            .collect();
        let tris = match proj {
            Some((axis, sgn)) => {
                let (t, fb) = triangulate(&outer, &hole_nodes, &all_pts, axis, sgn);
                fallbacks += fb as usize;
                t
            }
            None => fan(&outer),
        };
        pieces[pi].triangles = tris
            .into_iter()
            .map(|[a, b, c]| [nodes[a], nodes[b], nodes[c]])
            .collect();
    }
    Ok(FaceSplit { pieces, fallbacks })
}
