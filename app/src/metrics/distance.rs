//! The smallest distance between two triangle meshes (the cut walls and a critical structure),
//! with the pair of closest points.
//!
//! The distance between two triangles that do not intersect is reached at a vertex of one and
//! the other triangle, or at an edge of each. So the minimum over the meshes is:
//! 1. every vertex of either mesh against the other mesh (exact point–triangle distance through
//!    the other mesh's BVH, pruned by the best distance found so far); then
//! 2. for every wall triangle, the structure's triangles in its box widened by that best distance:
//!    an exact test whether they intersect (Shewchuk's adaptive `orient3d`: an edge of one that
//!    passes through the other makes the distance 0), else the distances between their nine
//!    edge pairs.
//!
//! Distances themselves are computed in `f64` (not exact arithmetic); only the intersection
//! decision, where a rounding could turn "touches" into "misses", uses exact signs.

use csg::{Aabb, Mesh, SpatialIndex};
use glam::DVec3;
use robust::{Coord3D, orient3d};

/// The closest pair of points of two meshes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPair {
    /// mm (0 when the meshes touch or cross).
    pub distance: f64,
    /// The point on the first mesh (the walls).
    pub on_first: DVec3,
    /// The point on the second mesh (the structure).
    pub on_second: DVec3,
}

/// The smallest distance between `first` and `second` (`None` when either has no triangles).
pub fn min_distance(first: &Mesh, second: &Mesh) -> Option<ClosestPair> {
    if first.triangles.is_empty() || second.triangles.is_empty() {
        return None;
    }
    let first_index = SpatialIndex::build(first);
    let second_index = SpatialIndex::build(second);
    let mut best: Option<ClosestPair> = None;
    let bound = |best: &Option<ClosestPair>| best.map_or(f64::INFINITY, |b| b.distance);
    // 1. Vertices against the other mesh.
    for p in used_vertices(first) {
        if let Some(c) = second_index.closest_point_within(second, p, bound(&best)) {
            keep(&mut best, c.distance, p, c.point);
        }
    }
    for q in used_vertices(second) {
        if let Some(c) = first_index.closest_point_within(first, q, bound(&best)) {
            keep(&mut best, c.distance, c.point, q);
        }
    }
    // 2. Crossings and edge pairs of nearby triangles.
    let mut candidates = Vec::new();
    for t in 0..first.triangle_count() {
        let a = first.corners(t);
        let reach = bound(&best);
        if reach == 0.0 {
            break;
        }
        let mut box_ = Aabb::from_points(&a);
        box_ = box_.expanded(reach);
        candidates.clear();
        second_index.faces_in_box(&box_, &mut candidates);
        for &f in &candidates {
            let b = second.corners(f as usize);
            if let Some(point) = crossing(&a, &b) {
                keep(&mut best, 0.0, point, point);
                break;
            }
            for i in 0..3 {
                for j in 0..3 {
                    let (p, q) = closest_on_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
                    keep(&mut best, p.distance(q), p, q);
                }
            }
        }
    }
    best
}

fn keep(best: &mut Option<ClosestPair>, distance: f64, on_first: DVec3, on_second: DVec3) {
    if best.is_none_or(|b| distance < b.distance) {
        *best = Some(ClosestPair {
            distance,
            on_first,
            on_second,
        });
    }
}

/// The vertices that triangles use.
fn used_vertices(mesh: &Mesh) -> impl Iterator<Item = DVec3> + '_ {
    let mut used = vec![false; mesh.positions.len()];
    for tri in &mesh.triangles {
        for &v in tri {
            used[v as usize] = true;
        }
    }
    mesh.positions
        .iter()
        .zip(used)
        .filter(|(_, u)| *u)
        .map(|(p, _)| *p)
}

fn coord(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Sign of the exact orientation of `d` against the plane of `a, b, c`.
fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let value = orient3d(coord(a), coord(b), coord(c), coord(d));
    if value > 0.0 {
        1.0
    } else if value < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// A point where triangles `a` and `b` meet when an edge of one passes through (or touches) the
/// other; decided with exact signs. Coplanar contact is left to the edge and vertex distances
/// (which are then 0 up to rounding).
fn crossing(a: &[DVec3; 3], b: &[DVec3; 3]) -> Option<DVec3> {
    edge_through(a, b).or_else(|| edge_through(b, a))
}

/// A point where an edge of `edges` passes through triangle `tri`.
fn edge_through(edges: &[DVec3; 3], tri: &[DVec3; 3]) -> Option<DVec3> {
    let [a, b, c] = *tri;
    for k in 0..3 {
        let (p, q) = (edges[k], edges[(k + 1) % 3]);
        let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
        if sp == 0.0 && sq == 0.0 || sp * sq > 0.0 {
            continue;
        }
        let s = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
        if s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0) {
            // Where the segment meets the triangle's plane.
            let n = (b - a).cross(c - a);
            let (dp, dq) = (n.dot(p - a), n.dot(q - a));
            let t = if dp == dq { 0.0 } else { dp / (dp - dq) };
            return Some(p + (q - p) * t.clamp(0.0, 1.0));
        }
    }
    None
}

/// The closest points of segments `p0 p1` and `q0 q1` (degenerate segments are points).
pub fn closest_on_segments(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> (DVec3, DVec3) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let r = p0 - q0;
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let (s, t);
    if a == 0.0 && e == 0.0 {
        return (p0, q0);
    }
    if a == 0.0 {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = d1.dot(r);
        if e == 0.0 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s0 = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t0 > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            } else {
                t = t0;
                s = s0;
            }
        }
    }
    (p0 + d1 * s, q0 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri_mesh(points: [DVec3; 3]) -> Mesh {
        Mesh {
            positions: points.to_vec(),
            triangles: vec![[0, 1, 2]],
        }
    }

    #[test]
    fn parallel_edges_are_found_where_no_vertex_is_closest() {
        // Two triangles whose nearest features are crossing edges (an X seen from above), 2 apart.
        let a = tri_mesh([
            DVec3::new(-5.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -5.0),
        ]);
        let b = tri_mesh([
            DVec3::new(0.0, -5.0, 2.0),
            DVec3::new(0.0, 5.0, 2.0),
            DVec3::new(0.0, 0.0, 7.0),
        ]);
        let pair = min_distance(&a, &b).unwrap();
        assert!((pair.distance - 2.0).abs() < 1e-12, "{pair:?}");
        assert!(pair.on_first.distance(DVec3::ZERO) < 1e-12);
        assert!(pair.on_second.distance(DVec3::new(0.0, 0.0, 2.0)) < 1e-12);
    }

    #[test]
    fn a_piercing_triangle_is_at_distance_zero() {
        // Edges of each pass through the other; no vertex of either lies on the other.
        let a = tri_mesh([
            DVec3::new(-10.0, -10.0, 0.0),
            DVec3::new(10.0, -10.0, 0.0),
            DVec3::new(0.0, 10.0, 0.0),
        ]);
        let b = tri_mesh([
            DVec3::new(0.0, 0.0, -5.0),
            DVec3::new(0.0, 0.0, 5.0),
            DVec3::new(30.0, 0.0, 0.0),
        ]);
        let pair = min_distance(&a, &b).unwrap();
        assert_eq!(pair.distance, 0.0);
        // The triangles cross along y = z = 0, 0 <= x <= 5.
        let p = pair.on_first;
        assert!(p.y.abs() < 1e-12 && p.z.abs() < 1e-12, "{pair:?}");
        assert!((-1e-12..=5.0 + 1e-12).contains(&p.x), "{pair:?}");
    }

    #[test]
    fn matches_brute_force_on_sampled_points() {
        // Brute force over dense samples of both triangles can only be larger (or equal).
        let a = tri_mesh([
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 0.5),
            DVec3::new(1.0, 4.0, -0.5),
        ]);
        let b = tri_mesh([
            DVec3::new(4.0, 4.0, 3.0),
            DVec3::new(6.0, 2.0, 2.0),
            DVec3::new(2.0, 6.0, 4.0),
        ]);
        let pair = min_distance(&a, &b).unwrap();
        let sample = |m: &Mesh, u: f64, v: f64| {
            let [p, q, r] = m.corners(0);
            p + (q - p) * u + (r - p) * v
        };
        let n = 60;
        let mut brute = f64::INFINITY;
        for i in 0..=n {
            for j in 0..=n - i {
                let pa = sample(&a, i as f64 / n as f64, j as f64 / n as f64);
                let (c, _) = csg::spatial::closest_on_triangle(
                    pa,
                    b.positions[0],
                    b.positions[1],
                    b.positions[2],
                );
                brute = brute.min(pa.distance(c));
            }
        }
        assert!(
            pair.distance <= brute + 1e-12,
            "{} > {brute}",
            pair.distance
        );
        assert!(pair.distance > brute - 0.1, "{} << {brute}", pair.distance);
        assert!((pair.on_first.distance(pair.on_second) - pair.distance).abs() < 1e-12);
    }
}
