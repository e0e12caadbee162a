//! Exact polygon operations in the projection of a face, for splitting faces: orientation,
//! point in polygon, and ear clipping of a polygon with holes. Every decision is an exact
//! predicate of [`crate::exact`] on the homogeneous points (a floating-point filter first where
//! it can decide).

use crate::exact::{self, HPoint, Sign};

pub(crate) fn fan(poly: &[usize]) -> Vec<[usize; 3]> {
    (1..poly.len().saturating_sub(1))
        .map(|i| [poly[0], poly[i], poly[i + 1]])
        .collect()
}

/// Orientation (+1 counter-clockwise in the projection) of a simple polygon, from its extreme
/// vertex (exact).
pub(crate) fn polygon_orientation(pts: &[HPoint], axis: usize) -> Sign {
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
pub(crate) fn point_in_polygon(p: &HPoint, poly: &[HPoint], axis: usize) -> bool {
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
pub(crate) fn triangulate(
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
