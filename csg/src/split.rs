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

/// A short list stored inline up to `N` items (most face pieces have one or two triangles and
/// two or three corners: no allocation for them), on the heap beyond.
#[derive(Clone, Debug)]
pub(crate) enum Small<T: Copy, const N: usize> {
    /// The first `len` items of the array.
    Inline([Option<T>; N], u8),
    Heap(Vec<T>),
}

/// The iterator of [`Small`].
pub(crate) type SmallIter<'a, T> =
    std::iter::Chain<std::iter::Flatten<std::slice::Iter<'a, Option<T>>>, std::slice::Iter<'a, T>>;

impl<T: Copy, const N: usize> Default for Small<T, N> {
    fn default() -> Self {
        Small::Inline([None; N], 0)
    }
}

impl<T: Copy, const N: usize> Small<T, N> {
    pub fn push(&mut self, x: T) {
        match self {
            Small::Inline(items, len) if (*len as usize) < N => {
                items[*len as usize] = Some(x);
                *len += 1;
            }
            Small::Inline(items, _) => {
                let mut v: Vec<T> = items.iter().flatten().copied().collect();
                v.push(x);
                *self = Small::Heap(v);
            }
            Small::Heap(v) => v.push(x),
        }
    }

    pub fn len(&self) -> usize {
        match self {
            Small::Inline(_, len) => *len as usize,
            Small::Heap(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn iter(&self) -> SmallIter<'_, T> {
        let (inline, heap): (&[Option<T>], &[T]) = match self {
            Small::Inline(items, len) => (&items[..*len as usize], &[]),
            Small::Heap(v) => (&[], v),
        };
        inline.iter().flatten().chain(heap)
    }
}

impl<T: Copy, const N: usize> std::ops::Index<usize> for Small<T, N> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        match self {
            Small::Inline(items, len) => {
                assert!(i < *len as usize, "index {i} out of range");
                items[i].as_ref().expect("set below len")
            }
            Small::Heap(v) => &v[i],
        }
    }
}

impl<T: Copy + PartialEq, const N: usize> PartialEq for Small<T, N> {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl<T: Copy + Eq, const N: usize> Eq for Small<T, N> {}

impl<T: Copy, const N: usize> FromIterator<T> for Small<T, N> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        let mut s = Small::default();
        for x in iter {
            s.push(x);
        }
        s
    }
}

impl<'a, T: Copy, const N: usize> IntoIterator for &'a Small<T, N> {
    type Item = &'a T;
    type IntoIter = SmallIter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
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

fn fan(poly: &[usize]) -> Vec<[usize; 3]> {
    (1..poly.len().saturating_sub(1))
        .map(|i| [poly[0], poly[i], poly[i + 1]])
        .collect()
}

/// Orientation (+1 counter-clockwise in the projection) of a simple polygon, from its extreme
/// vertex (exact).
fn polygon_orientation(pts: &[HPoint], axis: usize) -> Sign {
    let (i, j) = exact::plane_axes(axis);
    let mut best = 0;
    for k in 1..pts.len() {
        let o = exact::cmp_coord(&pts[k], &pts[best], i)
            .then_with(|| exact::cmp_coord(&pts[k], &pts[best], j));
        if o == std::cmp::Ordering::Less {
            best = k;
        }
    }
    let n = pts.len();
    exact::orient2d(
        &pts[(best + n - 1) % n],
        &pts[best],
        &pts[(best + 1) % n],
        axis,
    )
}

/// Crossing-number point-in-polygon in the projection (exact; half-open rule on the second axis).
fn point_in_polygon(p: &HPoint, poly: &[HPoint], axis: usize) -> bool {
    let (_, j) = exact::plane_axes(axis);
    let mut inside = false;
    let n = poly.len();
    for k in 0..n {
        let a = &poly[k];
        let b = &poly[(k + 1) % n];
        let a_above = exact::cmp_coord(a, p, j) == std::cmp::Ordering::Greater;
        let b_above = exact::cmp_coord(b, p, j) == std::cmp::Ordering::Greater;
        if a_above != b_above {
            let o = exact::orient2d(a, b, p, axis);
            // Upward edge (b above): the crossing is right of p when p is left of a → b.
            if (b_above && o > 0) || (a_above && o < 0) {
                inside = !inside;
            }
        }
    }
    inside
}

/// Ear-clips a polygon with holes (outer counter-clockwise, holes clockwise, as seen from the
/// face normal). Returns the triangles (node ids) and whether the topology-only fallback ran.
fn triangulate(
    outer: &[usize],
    holes: &[Vec<usize>],
    pts: &[HPoint],
    axis: usize,
    sgn: Sign,
) -> (Vec<[usize; 3]>, bool) {
    if holes.is_empty() && outer.len() == 3 {
        return (vec![[outer[0], outer[1], outer[2]]], false);
    }
    let approx: Vec<[f64; 3]> = pts.iter().map(|p| p.approx(axis)).collect();
    // Orientation seen from the face normal: filter first, exact when it cannot decide.
    let mut orient = |a: usize, b: usize, c: usize| -> Sign {
        sgn * exact::orient2d_filter(&approx[a], &approx[b], &approx[c])
            .unwrap_or_else(|| exact::orient2d_exact(&pts[a], &pts[b], &pts[c], axis))
    };
    // Order along a line of the projection (lexicographic on the two in-plane axes), exact.
    let (ax_i, ax_j) = exact::plane_axes(axis);
    let along = |u: usize, v: usize| {
        exact::cmp_coord(&pts[u], &pts[v], ax_i)
            .then_with(|| exact::cmp_coord(&pts[u], &pts[v], ax_j))
    };
    let mut poly: Vec<usize> = outer.to_vec();
    let mut fallback = false;
    // Stage 3a: bridge holes, one at a time.
    let mut pending: Vec<Vec<usize>> = holes.to_vec();
    while let Some(hole) = pending.pop() {
        let mut done = false;
        'search: for hk in 0..hole.len() {
            for ok in 0..poly.len() {
                let (h, o) = (hole[hk], poly[ok]);
                if !locally_inside(&mut orient, &poly, ok, h)
                    || !locally_inside(&mut orient, &hole, hk, o)
                {
                    continue;
                }
                let blocked =
                    |ring: &[usize], orient: &mut dyn FnMut(usize, usize, usize) -> Sign| {
                        (0..ring.len()).any(|k| {
                            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                            if a == h || a == o || b == h || b == o {
                                return false;
                            }
                            segments_cross(orient, &along, h, o, a, b)
                        })
                    };
                if blocked(&poly, &mut orient)
                    || blocked(&hole, &mut orient)
                    || pending.iter().any(|r| blocked(r, &mut orient))
                {
                    continue;
                }
                // Splice: ... o, h, hole from h around, h, o, ...
                let mut merged = Vec::with_capacity(poly.len() + hole.len() + 2);
                merged.extend_from_slice(&poly[..=ok]);
                for k in 0..=hole.len() {
                    merged.push(hole[(hk + k) % hole.len()]);
                }
                merged.push(o);
                merged.extend_from_slice(&poly[ok + 1..]);
                poly = merged;
                done = true;
                break 'search;
            }
        }
        if !done {
            // Topology-only fallback: splice at the first vertices.
            fallback = true;
            let mut merged = poly.clone();
            merged.extend_from_slice(&hole);
            merged.push(hole[0]);
            merged.push(poly[poly.len() - 1]);
            poly = merged;
        }
    }
    // Stage 3b: ear clipping.
    let mut out = Vec::with_capacity(poly.len().saturating_sub(2));
    let mut n = poly.len();
    let mut reflex: Vec<bool> = Vec::with_capacity(n);
    for k in 0..n {
        let s = orient(poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]);
        reflex.push(s <= 0);
    }
    let mut k = 0;
    let mut since_last = 0;
    while n > 3 {
        let (ia, ic) = ((k + n - 1) % n, (k + 1) % n);
        let (a, b, c) = (poly[ia], poly[k], poly[ic]);
        let mut is_ear = !reflex[k];
        if is_ear {
            for m in 0..n {
                if !reflex[m] || m == ia || m == k || m == ic {
                    continue;
                }
                let p = poly[m];
                if p == a || p == b || p == c {
                    continue;
                }
                // The closed triangle: a reflex or flat vertex exactly on the diagonal `ca`
                // (contour points on one cutter plane are collinear in a target face's
                // projection, in every perturbed configuration) blocks the ear too, or the
                // clipped polygon would touch itself there and a later ear come out inverted.
                if orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0 {
                    is_ear = false;
                    break;
                }
            }
        }
        if !is_ear && since_last > n && orient(a, b, c) == 0 {
            // A flat vertex (collinear in every perturbed configuration: target faces folded
            // onto each other in one plane): clipping it adds a zero-area triangle, which is
            // geometrically harmless.
            is_ear = true;
        }
        if !is_ear && since_last > 2 * n {
            // No ear in a whole pass: topology-only fallback (clip anyway).
            fallback = true;
            is_ear = true;
        }
        if is_ear {
            out.push([a, b, c]);
            poly.remove(k);
            reflex.remove(k);
            n -= 1;
            let ia = (k + n - 1) % n;
            let ic = k % n;
            for &m in &[ia, ic] {
                let s = orient(poly[(m + n - 1) % n], poly[m], poly[(m + 1) % n]);
                reflex[m] = s <= 0;
            }
            k = ia;
            since_last = 0;
        } else {
            k = (k + 1) % n;
            since_last += 1;
        }
    }
    out.push([poly[0], poly[1], poly[2]]);
    (out, fallback)
}

/// Is the direction from `ring[k]` towards node `to` inside the ring's interior angle at `k`
/// (interior on the left of the ring's direction)?
fn locally_inside(
    orient: &mut dyn FnMut(usize, usize, usize) -> Sign,
    ring: &[usize],
    k: usize,
    to: usize,
) -> bool {
    let n = ring.len();
    let (prev, o, next) = (ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]);
    if to == prev || to == next || to == o {
        return false;
    }
    let left_of_next = orient(o, next, to) > 0;
    let right_of_prev = orient(o, prev, to) < 0;
    if orient(prev, o, next) > 0 {
        left_of_next && right_of_prev
    } else {
        left_of_next || right_of_prev
    }
}

/// Do segments `pq` and `ab` cross (or touch)? Exact; with the tie-break the only touching
/// configurations are shared endpoints, which the caller excludes. Collinear segments (flat
/// contour chains) touch only when they overlap along their common line.
fn segments_cross(
    orient: &mut dyn FnMut(usize, usize, usize) -> Sign,
    along: &dyn Fn(usize, usize) -> std::cmp::Ordering,
    p: usize,
    q: usize,
    a: usize,
    b: usize,
) -> bool {
    let o1 = orient(p, q, a);
    let o2 = orient(p, q, b);
    if o1 * o2 > 0 {
        return false;
    }
    if o1 == 0 && o2 == 0 {
        // All four on one line: overlap of the two intervals along it.
        let (p, q) = if along(p, q).is_le() { (p, q) } else { (q, p) };
        let (a, b) = if along(a, b).is_le() { (a, b) } else { (b, a) };
        return along(a, q).is_le() && along(p, b).is_le();
    }
    let o3 = orient(a, b, p);
    let o4 = orient(a, b, q);
    o3 * o4 <= 0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Twice the signed area of a triangle of integer points in the z = 0 plane.
    fn area2(p: &[[i64; 3]], t: [usize; 3]) -> i64 {
        let [a, b, c] = t.map(|i| p[i]);
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    }

    fn check_triangulation(coords: &[[i64; 3]], outer: &[usize], holes: &[Vec<usize>]) {
        let pts: Vec<HPoint> = coords.iter().map(HPoint::target_vertex).collect();
        let (tris, fallback) = triangulate(outer, holes, &pts, 2, 1);
        assert!(!fallback, "fallback used");
        let ring_area = |r: &[usize]| -> i64 {
            (1..r.len() - 1)
                .map(|k| area2(coords, [r[0], r[k], r[k + 1]]))
                .sum()
        };
        let want = ring_area(outer) + holes.iter().map(|h| ring_area(h)).sum::<i64>();
        let mut sum = 0;
        for &t in &tris {
            let a = area2(coords, t);
            assert!(a >= 0, "inverted triangle {t:?}");
            sum += a;
        }
        assert_eq!(sum, want, "triangles do not tile the polygon");
    }

    /// The root cause of the pole regression (`boolean_props.rs`): reflex vertex 4 lies exactly
    /// on the diagonal 0–2 of the convex vertex 1. Clipping the ear (0, 1, 2) would leave a
    /// polygon touching itself at 4 and an inverted triangle at the end.
    #[test]
    fn reflex_vertex_on_an_ear_diagonal_blocks_the_ear() {
        let coords = [
            [0, 0, 0],
            [4, 0, 0],
            [4, 4, 0],
            [3, 4, 0],
            [2, 2, 0],
            [0, 3, 0],
        ];
        check_triangulation(&coords, &[0, 1, 2, 3, 4, 5], &[]);
        // Every rotation of the ring (the clipper starts at a different vertex).
        for r in 1..6 {
            let ring: Vec<usize> = (0..6).map(|k| (k + r) % 6).collect();
            check_triangulation(&coords, &ring, &[]);
        }
    }

    /// Flat chains (several contour points on one line, flat vertices on the hole's lines):
    /// no fallback, exact tiling.
    #[test]
    fn flat_chains_and_collinear_bridges() {
        let coords = [
            [0, 0, 0],
            [2, 0, 0],
            [4, 0, 0],
            [6, 0, 0],
            [6, 6, 0],
            [0, 6, 0],
            // hole (clockwise), on the line y = 2 with the outer's flat vertices' x
            [2, 2, 0],
            [2, 4, 0],
            [4, 4, 0],
            [4, 2, 0],
        ];
        check_triangulation(&coords, &[0, 1, 2, 3, 4, 5], &[vec![6, 7, 8, 9]]);
    }

    /// Collinear segments cross only when they overlap (a bridge along a line that also holds
    /// a disjoint flat edge is not blocked by it).
    #[test]
    fn collinear_segments_cross_only_when_they_overlap() {
        let coords = [
            [0, 0, 0],
            [2, 0, 0],
            [3, 0, 0],
            [5, 0, 0],
            [1, 0, 0],
            [0, 1, 0],
        ];
        let pts: Vec<HPoint> = coords.iter().map(HPoint::target_vertex).collect();
        let mut orient =
            |a: usize, b: usize, c: usize| exact::orient2d(&pts[a], &pts[b], &pts[c], 2);
        let along = |u: usize, v: usize| exact::cmp_coord(&pts[u], &pts[v], 0);
        assert!(!segments_cross(&mut orient, &along, 0, 1, 2, 3));
        assert!(!segments_cross(&mut orient, &along, 1, 0, 3, 2));
        assert!(segments_cross(&mut orient, &along, 0, 2, 4, 3));
        assert!(segments_cross(&mut orient, &along, 4, 5, 0, 1));
        assert!(!segments_cross(&mut orient, &along, 2, 5, 0, 4));
    }
}
