//! Cut points (on a vertex, on an edge, inside a face), their classification with relative
//! snapping, and the one exact predicate the scalpel decides topology with.
//!
//! A point is classified once, from barycentric weights, with thresholds relative to the triangle
//! (vertex before edge, as SOFA's `computeIncisionPath`), so a point exactly on a vertex never
//! becomes "on an edge at t = 1e-17" and no sliver triangle is created next to a vertex or edge.
//!
//! The exact predicate is `csg::exact::orient3d_f64` (Shewchuk's adaptive `orient3d`), the
//! mesh core's one home for exact predicates.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, is_real};
use csg::fast_hash::FastSet;

/// At most this many triangles examined when a cut restarts inside a stroke (see
/// `Scalpel::start_cut`), or when a stroke starts near a known vertex ([`super::locate`]).
pub const RESTART_SEARCH: usize = 4096;

/// Where a cut point lies on the current mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CutPoint {
    /// Exactly on an existing vertex.
    Vertex(u32),
    /// On the edge of half-edge `h` at position `point` (strictly inside the edge).
    Edge { h: u32, point: DVec3 },
    /// Strictly inside triangle `t` at `point`.
    Face { t: u32, point: DVec3 },
}

/// Side of `x` relative to the plane through `a`, `b`, `c`: `+1` on the side the normal of the
/// counter-clockwise triangle points to, `-1` on the other, `0` on the plane (exact, via
/// [`csg::exact::orient3d_f64`]).
#[inline]
pub fn side(a: DVec3, b: DVec3, c: DVec3, x: DVec3) -> i8 {
    csg::exact::orient3d_f64(a.to_array(), b.to_array(), c.to_array(), x.to_array())
}

/// Classifies the point with barycentric weights `bary` (corners 0, 1, 2 of triangle `t`) with
/// snapping radius `tau` (fraction of the triangle): a weight above `1 - tau` snaps to its
/// vertex; else a weight below `tau / 2` puts the point on the opposite edge.
pub fn classify(mesh: &DynMesh, t: u32, bary: DVec3, tau: f64) -> CutPoint {
    let tri = mesh.triangles[t as usize];
    let w = [bary.x, bary.y, bary.z];
    let (kmax, wmax) =
        (0..3).map(|k| (k, w[k])).fold(
            (0, f64::NEG_INFINITY),
            |acc, x| if x.1 > acc.1 { x } else { acc },
        );
    if wmax >= 1.0 - tau {
        return CutPoint::Vertex(tri[kmax]);
    }
    let (kmin, wmin) =
        (0..3).map(|k| (k, w[k])).fold(
            (0, f64::INFINITY),
            |acc, x| if x.1 < acc.1 { x } else { acc },
        );
    let p = mesh.pos(tri[0]) * w[0] + mesh.pos(tri[1]) * w[1] + mesh.pos(tri[2]) * w[2];
    if wmin < tau * 0.5 {
        // On the edge opposite corner kmin: half-edge from corner kmin+1 to kmin+2.
        let h = 3 * t + ((kmin + 1) % 3) as u32;
        let (a, b) = (mesh.pos(mesh.origin(h)), mesh.pos(mesh.dest(h)));
        let s = (w[(kmin + 2) % 3] / (1.0 - wmin).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        return CutPoint::Edge {
            h,
            point: a.lerp(b, s),
        };
    }
    CutPoint::Face { t, point: p }
}

/// [`classify`], but a point inside the face goes onto the nearest edge (the one opposite its
/// smallest weight) instead: for cuts that must not start inside a face.
pub fn classify_on_edges(mesh: &DynMesh, t: u32, bary: DVec3, tau: f64) -> CutPoint {
    match classify(mesh, t, bary, tau) {
        CutPoint::Face { .. } => {
            let w = [bary.x, bary.y, bary.z];
            let kmin = (0..3).min_by(|&a, &b| w[a].total_cmp(&w[b])).unwrap_or(0);
            let mut on = bary;
            on[kmin] = 0.0;
            let sum = on.x + on.y + on.z;
            if sum > 0.0 {
                on /= sum;
            }
            // Its smallest weight is 0 now: an edge (or a vertex), even with no snapping.
            classify(mesh, t, on, tau.max(1e-9))
        }
        cp => cp,
    }
}

/// Parameter in `[0, 1]` of the point of segment `a → b` closest to `p` (0 for a degenerate
/// segment).
pub fn segment_parameter(a: DVec3, b: DVec3, p: DVec3) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point of triangle `(a, b, c)` to `p`, as barycentric weights (Ericson, RTCD 5.1.5).
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return DVec3::new(1.0, 0.0, 0.0);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return DVec3::new(0.0, 1.0, 0.0);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return DVec3::new(1.0 - v, v, 0.0);
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return DVec3::new(0.0, 0.0, 1.0);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return DVec3::new(1.0 - w, 0.0, w);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return DVec3::new(0.0, 1.0 - w, w);
    }
    let denom = 1.0 / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    DVec3::new(1.0 - v - w, v, w)
}

/// The triangle of `mesh` closest to `p` with the closest point's barycentric weights and
/// distance, by a linear scan. Used only where a stroke starts (`begin_stroke`), never inside a
/// step (a cut restarting inside a stroke uses [`closest_face_near`]).
pub fn closest_face(mesh: &DynMesh, p: DVec3) -> Option<(u32, DVec3, f64)> {
    let mut best: Option<(u32, DVec3, f64)> = None;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if mesh.is_wall(t as u32) {
            // Groove walls are below the surface: a stroke never starts on them.
            continue;
        }
        let (a, b, c) = (mesh.pos(tri[0]), mesh.pos(tri[1]), mesh.pos(tri[2]));
        // Cheap reject on the box distance.
        if let Some((_, _, d)) = best {
            let lo = a.min(b).min(c);
            let hi = a.max(b).max(c);
            let q = p.clamp(lo, hi);
            if q.distance_squared(p) >= d * d {
                continue;
            }
        }
        let w = closest_on_triangle(p, a, b, c);
        let q = a * w.x + b * w.y + c * w.z;
        let d = q.distance(p);
        if best.is_none_or(|(_, _, bd)| d < bd) {
            best = Some((t as u32, w, d));
        }
    }
    best
}

/// The surface triangle nearest `p` among those connected to vertex `v`, searched best-first
/// outward from `v`'s triangles (by the distance from `p` to each triangle's bounding box, over
/// twins, walls included as passages) and stopped once one is found with `p` on it (to
/// rounding) and no unvisited triangle can be nearer, or `limit` triangles were examined. (Not
/// stopped at the nearest so far otherwise: the way from `v` to the triangles under `p` may
/// lead through farther ones, around or through another cut.) Cost independent of the mesh size: used where a cut restarts
/// inside a stroke (after merging into another cut), where the walk knows where it is.
pub fn closest_face_near(
    mesh: &DynMesh,
    v: u32,
    p: DVec3,
    limit: usize,
) -> Option<(u32, DVec3, f64)> {
    closest_face_near_examining(mesh, v, p, limit, &mut Vec::new())
}

/// [`closest_face_near`], also listing in `examined` the triangles it examined (the answer
/// depends on nothing else than them, their neighbours over twins and `v`'s triangles: the
/// samples' feet kept between steps, [`super::feet`], are dropped when one of those changes).
pub fn closest_face_near_examining(
    mesh: &DynMesh,
    v: u32,
    p: DVec3,
    limit: usize,
    examined: &mut Vec<u32>,
) -> Option<(u32, DVec3, f64)> {
    let mut best: Option<(u32, DVec3, f64)> = None;
    // On the surface (to rounding): no unvisited triangle can be nearer.
    let on_surface = 1e-9 * (1.0 + p.length());
    visit_near(mesh, v, p, limit, |t, box_distance| {
        if best.is_some_and(|(_, _, d)| d <= on_surface && box_distance >= d) {
            return false;
        }
        examined.push(t);
        if !mesh.is_wall(t) {
            let [a, b, c] = mesh.triangles[t as usize].map(|x| mesh.pos(x));
            let w = closest_on_triangle(p, a, b, c);
            let d = (a * w.x + b * w.y + c * w.z).distance(p);
            if best.is_none_or(|(_, _, bd)| d < bd) {
                best = Some((t, w, d));
            }
        }
        true
    });
    best
}

/// Visits the triangles connected to vertex `v` (and its copies) best-first by the distance of
/// each triangle's bounding box from `p`, over twins (walls included as passages), at most
/// `limit` of them: `visit(triangle, box distance)` returns false to stop. The local search
/// behind [`closest_face_near`] and [`super::through::ray_hit_near`]: its cost depends on how
/// far it goes, not on the mesh size.
pub fn visit_near(
    mesh: &DynMesh,
    v: u32,
    p: DVec3,
    limit: usize,
    mut visit: impl FnMut(u32, f64) -> bool,
) {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let box_distance = |t: u32| {
        let [a, b, c] = mesh.triangles[t as usize].map(|x| mesh.pos(x));
        p.clamp(a.min(b).min(c), a.max(b).max(c)).distance(p)
    };
    // The triangles queued: a few hundred per search (the opening searches a few per step), so
    // the fast hash, not the standard one.
    let mut seen: FastSet<u32> = FastSet::with_capacity_and_hasher(4 * limit, Default::default());
    let mut heap = BinaryHeap::new();
    let mut fan = Vec::new();
    let mut seeds = vec![v];
    seeds.extend(mesh.copies(v));
    for s in seeds {
        mesh.fan_into(s, &mut fan);
        for &h in &fan {
            if seen.insert(h / 3) {
                // Distances are >= 0, so their bit patterns order like the values.
                heap.push(Reverse((box_distance(h / 3).to_bits(), h / 3)));
            }
        }
    }
    let mut examined = 0;
    while let Some(Reverse((bits, t))) = heap.pop() {
        if examined >= limit || !visit(t, f64::from_bits(bits)) {
            break;
        }
        examined += 1;
        for k in 0..3 {
            let g = mesh.twin(3 * t + k);
            if is_real(g) && seen.insert(g / 3) {
                heap.push(Reverse((box_distance(g / 3).to_bits(), g / 3)));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri_mesh() -> DynMesh {
        DynMesh::from_mesh(&csg::Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2]],
        })
    }

    #[test]
    fn vertex_before_edge() {
        let m = tri_mesh();
        assert_eq!(
            classify(&m, 0, DVec3::new(0.9, 0.05, 0.05), 0.25),
            CutPoint::Vertex(0)
        );
        match classify(&m, 0, DVec3::new(0.5, 0.48, 0.02), 0.25) {
            CutPoint::Edge { h, point } => {
                assert_eq!(h, 0);
                assert!((point - DVec3::new(0.48 / 0.98, 0.0, 0.0)).length() < 1e-12);
            }
            other => panic!("expected an edge point, got {other:?}"),
        }
        assert!(matches!(
            classify(&m, 0, DVec3::splat(1.0 / 3.0), 0.25),
            CutPoint::Face { t: 0, .. }
        ));
    }

    #[test]
    fn exact_side_of_plane() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Z);
        assert_eq!(side(a, b, c, DVec3::new(0.3, 0.0, 0.7)), 0);
        assert_ne!(side(a, b, c, DVec3::new(0.3, 1e-300, 0.7)), 0);
        assert_eq!(
            side(a, b, c, DVec3::new(0.3, 1e-300, 0.7)),
            -side(a, b, c, DVec3::new(0.3, -1e-300, 0.7))
        );
        // Positive on the side the counter-clockwise triangle's normal points to.
        assert_eq!(side(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z), 1);
        assert_eq!(side(DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::Z), -1);
    }

    #[test]
    fn closest_point_regions() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        assert_eq!(
            closest_on_triangle(DVec3::new(-1., -1., 0.), a, b, c),
            DVec3::X
        );
        let w = closest_on_triangle(DVec3::new(0.25, 0.25, 5.0), a, b, c);
        assert!((w - DVec3::new(0.5, 0.25, 0.25)).length() < 1e-12);
    }

    #[test]
    fn local_search_finds_the_nearest_face_without_scanning() {
        let m = DynMesh::from_mesh(&csg::testkit::icosphere(3, 10.0));
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for k in 0..200u32 {
            let v = k * 3 % m.vertex_count() as u32;
            let jitter = DVec3::new(rnd(), rnd(), rnd()) * 3.0;
            let p = m.pos(v) + jitter;
            let (_, _, global) = closest_face(&m, p).unwrap();
            let (t, w, local) = closest_face_near(&m, v, p, 4096).unwrap();
            assert!(
                (global - local).abs() <= 1e-9 * (1.0 + global),
                "{global} {local}"
            );
            let [a, b, c] = m.triangles[t as usize].map(|x| m.pos(x));
            assert!(((a * w.x + b * w.y + c * w.z).distance(p) - local).abs() < 1e-9);
        }
        // The limit bounds the work: one triangle examined gives one of the vertex's own.
        let (t, _, _) = closest_face_near(&m, 0, -m.pos(0), 1).unwrap();
        assert!(m.triangles[t as usize].contains(&0));
    }
}
