//! Tests of the spatial index against brute-force scans.

use super::*;
use crate::testkit;

#[test]
fn empty_and_single() {
    let empty = Mesh::default();
    let index = SpatialIndex::build(&empty);
    index.sanity_check(&empty).unwrap();
    assert_eq!(index.closest_point(&empty, DVec3::ZERO), None);
    assert_eq!(index.ray_cast(&empty, DVec3::ZERO, DVec3::X, 1.0), None);
    let mut out = vec![];
    index.faces_in_box(
        &Aabb {
            min: DVec3::splat(-1.0),
            max: DVec3::ONE,
        },
        &mut out,
    );
    assert!(out.is_empty());

    let tri = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    let index = SpatialIndex::build(&tri);
    index.sanity_check(&tri).unwrap();
    let hit = index
        .ray_cast(&tri, DVec3::new(0.25, 0.25, 1.0), DVec3::NEG_Z, 10.0)
        .unwrap();
    assert_eq!((hit.face, hit.t), (0, 1.0));
    assert_eq!(hit.bary, DVec3::new(0.5, 0.25, 0.25));
    assert_eq!(hit.point, DVec3::new(0.25, 0.25, 0.0));
    // From below too (both sides), and not beyond t_max.
    assert!(
        index
            .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 10.0)
            .is_some()
    );
    assert!(
        index
            .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::Z, 0.5)
            .is_none()
    );
    assert!(
        index
            .ray_cast(&tri, DVec3::new(0.25, 0.25, -1.0), DVec3::NEG_Z, 10.0)
            .is_none()
    );
    assert!(
        index
            .ray_cast(&tri, DVec3::ZERO, DVec3::ZERO, 10.0)
            .is_none()
    );
    let cp = index
        .closest_point(&tri, DVec3::new(2.0, 2.0, 3.0))
        .unwrap();
    assert_eq!(cp.point, DVec3::new(0.5, 0.5, 0.0));
    assert_eq!(cp.bary, DVec3::new(0.0, 0.5, 0.5));
    assert!(
        index
            .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.6)
            .is_none()
    );
    assert!(
        index
            .closest_point_within(&tri, DVec3::new(2.0, 2.0, 3.0), 3.7)
            .is_some()
    );
}

/// Queries on a tree big enough for the parallel build (several workers' subtrees), with a
/// pile of identical faces (one Morton code: split in the middle), answer exactly what a
/// scan of every face answers.
#[test]
fn queries_match_brute_force_on_a_large_tree() {
    let mut m = testkit::geodesic_sphere(60, 5.0);
    assert!(m.triangles.len() >= 2 * PARALLEL_RANGE);
    let v = m.positions.len() as u32;
    m.positions.extend([
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(0.1, 0.3, 0.3),
        DVec3::new(0.1, 0.2, 0.4),
    ]);
    m.triangles
        .extend(std::iter::repeat_n([v, v + 1, v + 2], 3 * LEAF_SIZE + 1));
    let index = SpatialIndex::build(&m);
    index.sanity_check(&m).unwrap();
    let boxes: Vec<(DVec3, DVec3)> = (0..m.triangles.len())
        .map(|t| {
            let [a, b, c] = m.corners(t);
            FBox::outward(a.min(b).min(c), a.max(b).max(c)).to_f64()
        })
        .collect();
    let mut state = 7u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..40 {
        let c = DVec3::new(next(), next(), next()) * 6.0;
        let h = DVec3::new(next(), next(), next()).abs() * 0.5;
        let query = Aabb {
            min: c - h,
            max: c + h,
        };
        let mut got = Vec::new();
        index.faces_in_box(&query, &mut got);
        got.sort_unstable();
        let want: Vec<u32> = (0..m.triangles.len() as u32)
            .filter(|&t| {
                let (min, max) = boxes[t as usize];
                min.cmple(query.max).all() && query.min.cmple(max).all()
            })
            .collect();
        assert_eq!(got, want);
        let origin = DVec3::new(next(), next(), next()) * 8.0;
        let direction = DVec3::new(next(), next(), next());
        let ray = WatertightRay::new(origin, direction).unwrap();
        let mut want_hit: Option<RayHit> = None;
        for t in 0..m.triangles.len() as u32 {
            if let Some(hit) = ray.intersect(&m, t, f64::INFINITY)
                && want_hit.is_none_or(|b| hit.t < b.t)
            {
                want_hit = Some(hit);
            }
        }
        let got_hit = index.ray_cast(&m, origin, direction, f64::INFINITY);
        assert_eq!(got_hit, want_hit);
        let p = DVec3::new(next(), next(), next()) * 7.0;
        let mut want_cp: Option<(f64, u32)> = None;
        for t in 0..m.triangles.len() {
            let [a, b, c] = m.corners(t);
            let d2 = (p - closest_on_triangle(p, a, b, c).0).length_squared();
            if want_cp.is_none_or(|(best, _)| d2 < best) {
                want_cp = Some((d2, t as u32));
            }
        }
        let got_cp = index.closest_point(&m, p).unwrap();
        assert_eq!(Some(got_cp.face), want_cp.map(|(_, face)| face));
    }
}

#[test]
fn rays_through_shared_edges_and_vertices_hit() {
    // Axis rays through every vertex and edge midpoint of an axis-aligned cube must hit.
    let m = testkit::cube(DVec3::splat(-1.0), DVec3::ONE);
    let index = SpatialIndex::build(&m);
    index.sanity_check(&m).unwrap();
    for x in [-1.0, -0.5, 0.0, 0.5, 1.0] {
        for y in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            let hit = index.ray_cast(&m, DVec3::new(x, y, 5.0), DVec3::NEG_Z, 100.0);
            let hit = hit.unwrap_or_else(|| panic!("ray at ({x}, {y}) missed"));
            assert_eq!(hit.t, 4.0);
        }
    }
}

#[test]
fn degenerate_triangles_closest_point() {
    let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
    let (q, bary) = closest_on_triangle(DVec3::new(1.5, 1.0, 0.0), a, b, c);
    assert_eq!(q, DVec3::new(1.5, 0.0, 0.0));
    assert!((bary.x + bary.y + bary.z - 1.0).abs() < 1e-15);
    assert_eq!(a * bary.x + b * bary.y + c * bary.z, q);
    let (q, _) = closest_on_triangle(DVec3::ONE, a, a, a);
    assert_eq!(q, a);
}

#[test]
fn icosphere_queries() {
    let m = testkit::icosphere(3, 2.0);
    let index = SpatialIndex::build(&m);
    index.sanity_check(&m).unwrap();
    let hit = index
        .ray_cast(&m, DVec3::new(0.0, 0.0, -10.0), DVec3::Z, f64::INFINITY)
        .unwrap();
    assert!((hit.t - 8.0).abs() < 0.05 && hit.point.z < 0.0);
    let cp = index.closest_point(&m, DVec3::new(0.0, 0.0, 0.1)).unwrap();
    assert!((cp.distance - 1.9).abs() < 0.05);
    let mut out = vec![];
    index.faces_in_box(&m.bbox(), &mut out);
    out.sort_unstable();
    assert_eq!(out, (0..m.triangle_count() as u32).collect::<Vec<_>>());
}
