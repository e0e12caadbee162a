//! The marching-cubes case table for a binary mask, derived (not typed in) from two rules.
//!
//! Notation: a cube's corner `c = dx + 2·dy + 4·dz` sits at `(dx, dy, dz)`. Its 12 edges are
//! numbered x-edges `0..4` (`dy + 2·dz`), y-edges `4..8` (`4 + dx + 2·dz`) and z-edges `8..12`
//! (`8 + dx + 2·dy`). A configuration is the 8-bit set of inside corners.
//!
//! 1. On each cube face, the crossing edges (ends on different sides) are joined by segments:
//!    two crossings make one segment; four (inside corners on a diagonal) make two segments, each
//!    cutting off one inside corner, so the inside corners of an ambiguous face are always
//!    separated. The rule reads only the face's four corners, so the two cubes sharing a face
//!    make the same segments.
//! 2. Each segment is oriented so that, seen from outside the cube through that face, the inside
//!    corner lies on its right: then the polygon it belongs to runs counter-clockwise seen from
//!    outside the mask, and the two cubes sharing a face traverse the segment in opposite
//!    directions.
//!
//! Segments that share a crossing edge form the cube's polygons (closed loops). A cube whose only
//! polygon is a triangle or a quadrilateral keeps it as such, without a centre vertex (the
//! quadrilateral is split into two triangles after smoothing, along its shorter diagonal, so the
//! split does not depend on how the grid's axes are ordered or flipped); every other polygon is
//! closed with a fan from its own centre vertex.
//!
//! Why the direct fill stays free of self-intersection: its vertices stay on their cube edges, so
//! its triangles lie in the closed cube and meet a neighbouring cube only along the face segments
//! they share; neither diagonal of a quadrilateral lies in a cube face (checked by the tests), and
//! the two triangles of a quadrilateral project onto a convex quadrilateral (the cube's only
//! 4-sided polygons cut off an edge or a face of corners, whose crossing edges lie on two parallel
//! planes or are parallel), so they share the diagonal and nothing else, whichever is chosen.

use std::sync::OnceLock;

use glam::DVec3;

/// The two corners of each edge.
pub const EDGE_CORNERS: [[usize; 2]; 12] = [
    [0, 1],
    [2, 3],
    [4, 5],
    [6, 7],
    [0, 2],
    [1, 3],
    [4, 6],
    [5, 7],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

/// The six faces: corners in cyclic order, and the outward normal.
const FACES: [([usize; 4], [f64; 3]); 6] = [
    ([0, 2, 6, 4], [-1.0, 0.0, 0.0]),
    ([1, 3, 7, 5], [1.0, 0.0, 0.0]),
    ([0, 1, 5, 4], [0.0, -1.0, 0.0]),
    ([2, 3, 7, 6], [0.0, 1.0, 0.0]),
    ([0, 1, 3, 2], [0.0, 0.0, -1.0]),
    ([4, 5, 7, 6], [0.0, 0.0, 1.0]),
];

/// Position of corner `c` in the unit cube.
pub fn corner(c: usize) -> DVec3 {
    DVec3::new((c & 1) as f64, ((c >> 1) & 1) as f64, ((c >> 2) & 1) as f64)
}

/// Midpoint of edge `e` in the unit cube.
pub fn edge_midpoint(e: usize) -> DVec3 {
    let [a, b] = EDGE_CORNERS[e];
    (corner(a) + corner(b)) * 0.5
}

/// The edge joining corners `a` and `b` (which differ in one bit).
fn edge_between(a: usize, b: usize) -> usize {
    EDGE_CORNERS
        .iter()
        .position(|&[p, q]| (p, q) == (a, b) || (p, q) == (b, a))
        .expect("corners of one cube face edge")
}

/// One polygon of a configuration.
#[derive(Clone, Debug, Default)]
pub struct Polygon {
    /// Oriented segments `(from_edge, to_edge)`; the fan triangle is `[centre, from, to]`.
    pub segments: Vec<[u8; 2]>,
    /// Lowest corner of the box the centre vertex must stay in (unit cube): the whole cube for
    /// a cube's only polygon, else the box of the polygon's edge midpoints widened by 1/4.
    pub lo: DVec3,
    /// Highest corner of that box.
    pub hi: DVec3,
    /// Mean of the polygon's edge midpoints (the centre vertex's raw position).
    pub centre: DVec3,
    /// The loop's cube edges in order (counter-clockwise seen from outside) when the polygon is
    /// kept without a centre vertex (the cube's only polygon, with 3 or 4 sides); empty for a fan.
    pub direct: Vec<u8>,
}

/// The polygons of all 256 configurations (built once).
pub fn table() -> &'static [Vec<Polygon>; 256] {
    static TABLE: OnceLock<[Vec<Polygon>; 256]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|config| polygons(config as u8)))
}

/// The polygons of one configuration.
fn polygons(config: u8) -> Vec<Polygon> {
    let inside = |c: usize| config >> c & 1 == 1;
    let mut segments: Vec<[usize; 2]> = Vec::new();
    for (corners, normal) in FACES {
        let normal = DVec3::from_array(normal);
        let crossing = |k: usize| inside(corners[k]) != inside(corners[(k + 1) % 4]);
        let count = (0..4).filter(|&k| crossing(k)).count();
        // Each inside corner whose two face edges both cross is cut off on its own; with two
        // crossings the segment joins them whichever corners are inside.
        let mut cut = |p: usize, q: usize, inner: usize| {
            let (a, b) = (edge_of(corners, p), edge_of(corners, q));
            let (pa, pb) = (edge_midpoint(a), edge_midpoint(b));
            let right = normal.cross(pb - pa).dot(corner(inner) - pa);
            segments.push(if right < 0.0 { [a, b] } else { [b, a] });
        };
        match count {
            0 => {}
            2 => {
                let ks: Vec<usize> = (0..4).filter(|&k| crossing(k)).collect();
                let inner = (0..4).map(|k| corners[k]).find(|&c| inside(c)).unwrap_or(0);
                cut(ks[0], ks[1], inner);
            }
            _ => {
                for k in 0..4 {
                    if inside(corners[k]) {
                        cut((k + 3) % 4, k, corners[k]);
                    }
                }
            }
        }
    }
    // Group segments into loops by shared edges (union-find over the 12 edges).
    let mut parent: [usize; 12] = std::array::from_fn(|e| e);
    fn find(parent: &mut [usize; 12], mut e: usize) -> usize {
        while parent[e] != e {
            e = parent[e];
        }
        e
    }
    for &[a, b] in &segments {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    let mut out: Vec<(usize, Polygon)> = Vec::new();
    for &[a, b] in &segments {
        let root = find(&mut parent, a);
        let i = match out.iter().position(|(r, _)| *r == root) {
            Some(i) => i,
            None => {
                out.push((root, Polygon::default()));
                out.len() - 1
            }
        };
        out[i].1.segments.push([a as u8, b as u8]);
    }
    let alone = out.len() == 1;
    out.into_iter()
        .map(|(_, mut p)| {
            let mids: Vec<DVec3> = p
                .segments
                .iter()
                .map(|s| edge_midpoint(s[0] as usize))
                .collect();
            // A cube's only polygon may use the whole cube; several polygons keep to their own
            // corner of it (their midpoints' box widened by a quarter voxel).
            let (lo, hi) = if alone {
                (DVec3::ZERO, DVec3::ONE)
            } else {
                let lo = mids.iter().fold(DVec3::INFINITY, |m, &q| m.min(q));
                let hi = mids.iter().fold(DVec3::NEG_INFINITY, |m, &q| m.max(q));
                ((lo - 0.25).max(DVec3::ZERO), (hi + 0.25).min(DVec3::ONE))
            };
            p.lo = lo;
            p.hi = hi;
            p.centre = mids.iter().sum::<DVec3>() / mids.len() as f64;
            if alone && (3..=4).contains(&p.segments.len()) {
                p.direct = loop_order(&p.segments);
            }
            p
        })
        .collect()
}

/// The loop's edges in order, following the segments from the first one.
fn loop_order(segments: &[[u8; 2]]) -> Vec<u8> {
    let mut order = vec![segments[0][0]];
    while order.len() < segments.len() {
        let last = *order.last().unwrap_or(&segments[0][0]);
        match segments.iter().find(|s| s[0] == last) {
            Some(s) => order.push(s[1]),
            None => break,
        }
    }
    order
}

/// The cube edge along face side `k` (from `corners[k]` to `corners[k + 1]`).
fn edge_of(corners: [usize; 4], k: usize) -> usize {
    edge_between(corners[k], corners[(k + 1) % 4])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every polygon is one closed loop: each of its edges starts exactly one segment and ends
    /// exactly one; every crossing edge of the cube is in exactly one polygon.
    #[test]
    fn polygons_are_closed_loops_over_the_crossing_edges() {
        for config in 0..=255u8 {
            let inside = |c: usize| config >> c & 1 == 1;
            let mut used = [0; 12];
            for p in &table()[config as usize] {
                let mut starts = [0; 12];
                let mut ends = [0; 12];
                for s in &p.segments {
                    starts[s[0] as usize] += 1;
                    ends[s[1] as usize] += 1;
                }
                assert_eq!(starts, ends, "config {config:#010b}");
                for e in 0..12 {
                    assert!(starts[e] <= 1, "config {config:#010b} edge {e}");
                    used[e] += starts[e];
                }
            }
            for (e, [a, b]) in EDGE_CORNERS.iter().enumerate() {
                let crossing = inside(*a) != inside(*b);
                assert_eq!(used[e], crossing as i32, "config {config:#010b} edge {e}");
            }
        }
    }

    /// True when cube edges `a` and `b` lie on a common cube face.
    fn share_face(a: usize, b: usize) -> bool {
        FACES.iter().any(|(corners, _)| {
            let on = |e: usize| EDGE_CORNERS[e].iter().all(|c| corners.contains(c));
            on(a) && on(b)
        })
    }

    /// A direct loop runs along its polygon's segments; neither diagonal of a quadrilateral lies
    /// in a cube face; the quadrilaterals are the corner-pair and face-of-four cuts.
    #[test]
    fn direct_loops_follow_their_segments() {
        let mut quads = 0;
        for config in 0..=255u8 {
            let polygons = &table()[config as usize];
            for p in polygons {
                if p.direct.is_empty() {
                    assert!(
                        polygons.len() > 1 || p.segments.len() > 4,
                        "config {config:#010b}"
                    );
                    continue;
                }
                assert_eq!(polygons.len(), 1);
                let n = p.direct.len();
                assert_eq!(n, p.segments.len());
                for k in 0..n {
                    let side = [p.direct[k], p.direct[(k + 1) % n]];
                    assert!(p.segments.contains(&side), "config {config:#010b}");
                }
                if n == 4 {
                    for k in 0..2 {
                        let (a, b) = (p.direct[k] as usize, p.direct[k + 2] as usize);
                        assert!(!share_face(a, b), "config {config:#010b}");
                    }
                    let inside = config.count_ones();
                    assert!(
                        inside == 2 || inside == 4 || inside == 6,
                        "config {config:#010b}"
                    );
                    quads += 1;
                }
            }
        }
        // 12 corner pairs and 3 faces of four, each with its complement.
        assert_eq!(quads, 30);
    }

    #[test]
    fn single_corner_is_one_outward_triangle() {
        let polys = &table()[1];
        assert_eq!(polys.len(), 1);
        let p = &polys[0];
        assert_eq!(p.segments.len(), 3);
        for s in &p.segments {
            let (a, b) = (edge_midpoint(s[0] as usize), edge_midpoint(s[1] as usize));
            // Normal of [centre, a, b] points away from corner 0.
            let n = (a - p.centre).cross(b - p.centre);
            assert!(n.dot(p.centre) > 0.0);
        }
        // Two opposite corners: two separate triangles.
        assert_eq!(table()[0b1000_0001].len(), 2);
        // A face diagonal (corners 0 and 3 on face z = 0): separated.
        assert_eq!(table()[0b0000_1001].len(), 2);
    }
}
