//! Small floating-point geometry helpers of the editor: triangle/triangle and ray tests.
//!
//! These drive interactive decisions (does the front face touch the surface, does a plane cross
//! its neighbour), not topology, so plain `f64` with a relative tolerance is the right tool here:
//! the exact predicates of `csg` are for the boolean. Touching within the tolerance counts as "not
//! intersecting", so faces that only share an edge or a corner never report a collision.

use glam::DVec3;

use csg::Aabb;

/// Relative tolerance of the intersection tests (scaled by the triangles' size).
const REL_EPS: f64 = 1e-9;

/// True when the triangles `a` and `b` properly cross: each has points strictly on both sides of
/// the other's plane and the crossing segments overlap by more than the tolerance. Touching (a
/// shared edge, a corner on a face, coplanar overlap) is not crossing.
pub fn tri_tri_intersect(a: &[DVec3; 3], b: &[DVec3; 3]) -> bool {
    let scale = tri_scale(a).max(tri_scale(b));
    if scale == 0.0 {
        return false;
    }
    let eps = REL_EPS * scale;
    let na = (a[1] - a[0]).cross(a[2] - a[0]);
    let nb = (b[1] - b[0]).cross(b[2] - b[0]);
    let (Some(na), Some(nb)) = (na.try_normalize(), nb.try_normalize()) else {
        return false;
    };
    let da = b.map(|p| snap((p - a[0]).dot(na), eps));
    if same_side(&da) {
        return false;
    }
    let db = a.map(|p| snap((p - b[0]).dot(nb), eps));
    if same_side(&db) {
        return false;
    }
    let dir = na.cross(nb);
    if dir.length_squared() < 1e-24 {
        return false; // (nearly) coplanar: touching only
    }
    let (Some(ia), Some(ib)) = (interval(a, &db, dir), interval(b, &da, dir)) else {
        return false;
    };
    let overlap = ia.1.min(ib.1) - ia.0.max(ib.0);
    overlap > eps
}

fn tri_scale(t: &[DVec3; 3]) -> f64 {
    (t[1] - t[0])
        .length()
        .max((t[2] - t[0]).length())
        .max((t[2] - t[1]).length())
}

fn snap(d: f64, eps: f64) -> f64 {
    if d.abs() <= eps { 0.0 } else { d }
}

/// All three signed distances on one side, zero allowed: the triangle at most touches the plane
/// (a shared edge or corner, or coplanar), it does not cross it.
fn same_side(d: &[f64; 3]) -> bool {
    (d[0] >= 0.0 && d[1] >= 0.0 && d[2] >= 0.0) || (d[0] <= 0.0 && d[1] <= 0.0 && d[2] <= 0.0)
}

/// The interval, along `dir`, of the part of triangle `t` lying on the other triangle's plane
/// (`d` holds the signed distances of `t`'s corners to that plane).
fn interval(t: &[DVec3; 3], d: &[f64; 3], dir: DVec3) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut push = |p: DVec3| {
        let s = p.dot(dir);
        lo = lo.min(s);
        hi = hi.max(s);
    };
    for i in 0..3 {
        let j = (i + 1) % 3;
        if d[i] == 0.0 {
            push(t[i]);
        }
        if (d[i] > 0.0 && d[j] < 0.0) || (d[i] < 0.0 && d[j] > 0.0) {
            let s = d[i] / (d[i] - d[j]);
            push(t[i] + (t[j] - t[i]) * s);
        }
    }
    (lo <= hi).then_some((lo / dir.length(), hi / dir.length()))
}

/// True when the (planar or not) quads `a` and `b`, each split along its first diagonal, cross.
pub fn quad_quad_intersect(a: &[DVec3; 4], b: &[DVec3; 4]) -> bool {
    let ta = quad_triangles(a);
    let tb = quad_triangles(b);
    let ba = Aabb::from_points(a.iter());
    let bb = Aabb::from_points(b.iter());
    if !ba.overlaps(&bb) {
        return false;
    }
    ta.iter()
        .any(|x| tb.iter().any(|y| tri_tri_intersect(x, y)))
}

/// The two triangles of a quad split along its first diagonal (0-2).
pub fn quad_triangles(q: &[DVec3; 4]) -> [[DVec3; 3]; 2] {
    [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
}

/// Parameter `t >= 0` where the ray `origin + t·dir` meets triangle `tri` (both sides), if it does.
pub fn ray_triangle(origin: DVec3, dir: DVec3, tri: &[DVec3; 3]) -> Option<f64> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - tri[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t >= 0.0).then_some(t)
}

/// Parameter `t` where the line `origin + t·dir` meets the plane through `point` with `normal`
/// (None when parallel).
pub fn line_plane(origin: DVec3, dir: DVec3, point: DVec3, normal: DVec3) -> Option<f64> {
    let denom = dir.dot(normal);
    if denom.abs() < 1e-12 * dir.length() * normal.length() {
        return None;
    }
    Some((point - origin).dot(normal) / denom)
}

/// Signed volume of a closed polygon soup, polygons fan-triangulated (positive when outward).
pub fn signed_volume(positions: &[DVec3], faces: &[Vec<u32>]) -> f64 {
    let origin = positions.first().copied().unwrap_or(DVec3::ZERO);
    let mut sum = 0.0;
    for f in faces {
        for k in 1..f.len().saturating_sub(1) {
            let a = positions[f[0] as usize] - origin;
            let b = positions[f[k] as usize] - origin;
            let c = positions[f[k + 1] as usize] - origin;
            sum += a.dot(b.cross(c));
        }
    }
    sum / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [DVec3; 3] {
        [DVec3::from(a), DVec3::from(b), DVec3::from(c)]
    }

    #[test]
    fn crossing_triangles_intersect() {
        let a = t([0., 0., 0.], [2., 0., 0.], [0., 2., 0.]);
        let b = t([0.5, 0.5, -1.], [0.5, 0.5, 1.], [1.5, -1., 0.]);
        assert!(tri_tri_intersect(&a, &b));
        assert!(tri_tri_intersect(&b, &a));
    }

    #[test]
    fn separated_and_touching_triangles_do_not() {
        let a = t([0., 0., 0.], [2., 0., 0.], [0., 2., 0.]);
        let above = t([0., 0., 1.], [2., 0., 1.], [0., 2., 2.]);
        assert!(!tri_tri_intersect(&a, &above));
        // Shares an edge, folded up: touching only.
        let hinge = t([0., 0., 0.], [2., 0., 0.], [0., 0., 2.]);
        assert!(!tri_tri_intersect(&a, &hinge));
        // Beside, in another plane, crossing the first plane outside the triangle.
        let beside = t([3., 3., -1.], [3., 3., 1.], [4., 3., 0.]);
        assert!(!tri_tri_intersect(&a, &beside));
    }

    #[test]
    fn ray_hits_triangle() {
        let a = t([0., 0., 0.], [2., 0., 0.], [0., 2., 0.]);
        let hit = ray_triangle(DVec3::new(0.5, 0.5, 3.0), DVec3::NEG_Z, &a);
        assert_eq!(hit, Some(3.0));
        assert_eq!(
            ray_triangle(DVec3::new(3.0, 3.0, 3.0), DVec3::NEG_Z, &a),
            None
        );
    }
}
