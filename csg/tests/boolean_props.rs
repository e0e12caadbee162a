//! Property tests of the boolean: random strip cutters on spheres and tori, with coordinates
//! snapped to coarse grids so that many vertices lie exactly on cutter planes (coincidences are
//! the point). Every cut must satisfy the robustness contract (see `boolean_common::check_cut`)
//! and put sample points where they belong: inside target and cutter in the removed solid, inside
//! the target only in the kept one, by ray parity against the inputs
//! (`boolean_common::check_membership`), which a cut that removes nothing fails.

mod boolean_common;

use boolean_common::*;
use csg::testkit::{icosphere, torus};
use csg::{CutError, DVec3, Mesh, TargetIndex};
use proptest::prelude::*;

fn target_sphere() -> Mesh {
    // Radius 10, snapped to a 1/64 grid (fine enough that no two vertices merge).
    snapped(&icosphere(3, 10.0), 1.0 / 64.0)
}

fn cut_prop(target: &Mesh, index: &TargetIndex, cutter: &Mesh) -> Result<(), TestCaseError> {
    match csg::subtract(index, cutter) {
        Ok(_) => cut_checked(index, target, cutter)
            .map(|_| ())
            .map_err(TestCaseError::fail),
        // Snapping can make a random strip self-intersect: not this test's subject.
        Err(CutError::SelfIntersecting { .. } | CutError::NotPositive { .. }) => {
            Err(TestCaseError::reject("invalid cutter"))
        }
        Err(e) => Err(TestCaseError::fail(format!("{e}"))),
    }
}

fn strip_from(points: &[(i32, i32, i32)], grid: f64, width: f64, height: f64) -> Mesh {
    let path: Vec<DVec3> = points
        .iter()
        .enumerate()
        .map(|(i, &(x, y, z))| DVec3::new(x as f64 + 3.0 * i as f64, y as f64, z as f64) * grid)
        .collect();
    snapped(&strip(&path, DVec3::Z, width, height), grid)
}

/// The property-test configuration: 48 cases from a fixed seed, unless `PROPTEST_CASES` /
/// `PROPTEST_RNG_SEED` say otherwise (CI pins the seed; exploring other seeds is how the named
/// regressions below were found: `PROPTEST_CASES=2000 PROPTEST_RNG_SEED=7 cargo test ...`).
fn config() -> ProptestConfig {
    // `ProptestConfig::default()` already carries the environment's overrides.
    let mut c = ProptestConfig {
        max_global_rejects: 4000,
        ..ProptestConfig::default()
    };
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 48;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = proptest::test_runner::RngSeed::Fixed(0x00c0_ffee);
    }
    c
}

proptest! {
    // A fixed seed: CI must not turn red on a newly drawn case; failures found by exploring other
    // seeds become named regression tests below.
    #![proptest_config(config())]

    /// Strips snapped to a 0.25 grid (axis-aligned caps and walls on grid planes).
    #[test]
    fn random_strips_on_a_snapped_sphere(
        start in (-20i32..0, -40i32..40, -48i32..48),
        steps in prop::collection::vec((0i32..2, -2i32..3, -2i32..3), 2..6),
        width in 4u32..16,
        height in 4u32..40,
    ) {
        let target = target_sphere();
        let index = TargetIndex::build(target.clone()).unwrap();
        let mut pts = vec![start];
        for s in steps {
            let last = *pts.last().unwrap();
            pts.push((last.0 + s.0, last.1 + s.1, last.2 + s.2));
        }
        let cutter = strip_from(&pts, 0.25, width as f64 * 0.25, height as f64 * 0.25);
        cut_prop(&target, &index, &cutter)?;
    }

    /// Boxes with corners on a coarse grid through a torus whose vertices are on a finer grid.
    #[test]
    fn random_boxes_on_a_snapped_torus(
        lo in (-12i32..12, -12i32..12, -6i32..6),
        size in (1i32..12, 1i32..12, 1i32..8),
    ) {
        let target = snapped(&torus(6.0, 2.0, 24, 12), 1.0 / 32.0);
        let index = TargetIndex::build(target.clone()).unwrap();
        let g = 0.5;
        let min = DVec3::new(lo.0 as f64, lo.1 as f64, lo.2 as f64) * g;
        let max = min + DVec3::new(size.0 as f64, size.1 as f64, size.2 as f64) * g;
        let cutter = csg::testkit::cube(min, max);
        cut_prop(&target, &index, &cutter)?;
    }
}

proptest! {
    #![proptest_config(config())]

    /// Boxes whose corners are two target vertices (vertex on vertex, edges along target edges
    /// or through target vertices, faces through many snapped vertices).
    #[test]
    fn boxes_spanned_by_target_vertices(
        i in 0usize..642,
        j in 0usize..642,
        pad in (0i32..3, 0i32..3, 0i32..3),
    ) {
        let target = target_sphere();
        let index = TargetIndex::build(target.clone()).unwrap();
        let (p, q) = (target.positions[i], target.positions[j]);
        let pad = DVec3::new(pad.0 as f64, pad.1 as f64, pad.2 as f64) / 64.0;
        let (min, max) = (p.min(q), p.max(q) + pad);
        prop_assume!((max - min).min_element() > 0.0);
        let cutter = csg::testkit::cube(min, max);
        cut_prop(&target, &index, &cutter)?;
    }

    /// Strips on a snapped torus (hole and saddle regions; walls with several loops).
    #[test]
    fn random_strips_on_a_snapped_torus(
        start in (-40i32..0, -40i32..40, -12i32..12),
        steps in prop::collection::vec((0i32..2, -3i32..4, -1i32..2), 2..7),
        width in 2u32..12,
        height in 2u32..24,
    ) {
        let target = snapped(&torus(6.0, 2.0, 24, 12), 1.0 / 32.0);
        let index = TargetIndex::build(target.clone()).unwrap();
        let mut pts = vec![start];
        for s in steps {
            let last = *pts.last().unwrap();
            pts.push((last.0 + s.0, last.1 + s.1, last.2 + s.2));
        }
        let cutter = strip_from(&pts, 0.25, width as f64 * 0.25, height as f64 * 0.25);
        cut_prop(&target, &index, &cutter)?;
    }

    /// Randomly rotated boxes snapped to a coarse grid (non-planar quads, near-coplanar faces).
    #[test]
    fn snapped_rotated_boxes_on_a_snapped_sphere(
        axis in (-8i32..9, -8i32..9, -8i32..9),
        angle in 0u32..64,
        centre in (-48i32..48, -48i32..48, -48i32..48),
        size in (2i32..40, 2i32..40, 2i32..40),
    ) {
        let target = target_sphere();
        let index = TargetIndex::build(target.clone()).unwrap();
        let axis = DVec3::new(axis.0 as f64, axis.1 as f64, axis.2 as f64).normalize_or(DVec3::Z);
        let rot = glam::DQuat::from_axis_angle(axis, angle as f64 * std::f64::consts::TAU / 64.0);
        let half = DVec3::new(size.0 as f64, size.1 as f64, size.2 as f64) * 0.125;
        let centre = DVec3::new(centre.0 as f64, centre.1 as f64, centre.2 as f64) * 0.25;
        let mut cutter = csg::testkit::cube(-half, half);
        for p in &mut cutter.positions {
            *p = rot * *p + centre;
        }
        cut_prop(&target, &index, &snapped(&cutter, 0.125))?;
    }
}

proptest! {
    #![proptest_config(config())]

    /// Open targets (a snapped sphere with a random band of faces removed): kept and removed
    /// still partition the target's faces exactly, untouched vertices keep their bits, and every
    /// open contour ends on the target's boundary.
    #[test]
    fn random_strips_on_an_open_sphere(
        start in (-20i32..0, -40i32..40, -48i32..48),
        steps in prop::collection::vec((0i32..2, -2i32..3, -2i32..3), 2..6),
        width in 4u32..16,
        height in 4u32..40,
        band in (-40i32..40, 1i32..20),
    ) {
        let sphere = target_sphere();
        let (lo, hi) = (band.0 as f64 * 0.25, (band.0 + band.1) as f64 * 0.25);
        let triangles = sphere
            .triangles
            .iter()
            .filter(|t| {
                let z = t.iter().map(|&i| sphere.positions[i as usize].z).sum::<f64>() / 3.0;
                z < lo || z > hi
            })
            .copied()
            .collect();
        let target = Mesh { positions: sphere.positions.clone(), triangles };
        let index = TargetIndex::build(target.clone()).unwrap();
        let mut pts = vec![start];
        for s in steps {
            let last = *pts.last().unwrap();
            pts.push((last.0 + s.0, last.1 + s.1, last.2 + s.2));
        }
        let cutter = strip_from(&pts, 0.25, width as f64 * 0.25, height as f64 * 0.25);
        let r = match csg::subtract(&index, &cutter) {
            Ok(r) => r,
            Err(CutError::SelfIntersecting { .. } | CutError::NotPositive { .. }) => {
                return Err(TestCaseError::reject("invalid cutter"));
            }
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        let kept = r.materialize(&target);
        let (at, ak, ar) = (area(&target), area(&kept), area(&r.removed.mesh));
        prop_assert!((ak + ar - at).abs() <= 1e-9 * at, "area {ak} + {ar} != {at}");
        for (i, p) in target.positions.iter().enumerate() {
            prop_assert_eq!(kept.positions[i].to_array().map(f64::to_bits), p.to_array().map(f64::to_bits));
        }
        // Open polylines end on boundary edges of the target (edges with one face).
        let mut count = std::collections::HashMap::new();
        for t in &target.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        let boundary: Vec<(DVec3, DVec3)> = count
            .iter()
            .filter(|&(_, &n)| n == 1)
            .map(|(&(a, b), _)| (target.positions[a as usize], target.positions[b as usize]))
            .collect();
        let on_boundary = |p: DVec3| {
            boundary.iter().any(|&(a, b)| {
                let ab = b - a;
                let u = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                (a + ab * u - p).length() < 1e-9
            })
        };
        for c in r.contours.iter().filter(|c| !c.closed) {
            let ends = [c.points[0], *c.points.last().unwrap()];
            prop_assert!(
                ends.iter().all(|&p| on_boundary(p)),
                "open contour ends at {:?}",
                ends
            );
        }
    }
}

/// Random rigid placements of a box cutter against a fixed target (the "fuzz target for random
/// cutter transforms", run as a seeded property test).
#[test]
fn random_cutter_transforms() {
    let target = icosphere(3, 10.0);
    let index = TargetIndex::build(target.clone()).unwrap();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut classified = Membership::default();
    for _ in 0..40 {
        let axis = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize_or(DVec3::Z);
        let rot = glam::DQuat::from_axis_angle(axis, rnd() * 6.3);
        let shift = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 20.0;
        let mut cutter =
            csg::testkit::cube(DVec3::new(-2.0, -3.0, -12.0), DVec3::new(2.0, 3.0, 1.0));
        for p in &mut cutter.positions {
            *p = rot * *p + shift;
        }
        let r = cut_checked(&index, &target, &cutter).unwrap();
        // Generic placements: the merged files are closed by position too.
        check_cut_welded(&target, &r).unwrap();
        let m = check_membership(&target, &cutter, &r, MEMBERSHIP_SAMPLES).unwrap();
        classified.removed += m.removed;
        classified.kept += m.kept;
        classified.outside += m.outside;
    }
    // The membership check is not vacuous: many sample points fell in each class.
    println!("membership samples over 40 cuts: {classified:?}");
    assert!(
        classified.removed >= 200 && classified.kept >= 1000 && classified.outside >= 1000,
        "{classified:?}"
    );
}

/// Shrunk proptest case: a box whose bottom face is tangent to the torus bottom along a target
/// edge (a cutter edge crosses both faces of that edge at the same limit point).
#[test]
fn regression_box_tangent_to_torus_bottom() {
    let target = snapped(&torus(6.0, 2.0, 24, 12), 1.0 / 32.0);
    let index = TargetIndex::build(target.clone()).unwrap();
    let cutter = csg::testkit::cube(DVec3::new(0.0, 1.5, -2.0), DVec3::new(5.5, 2.5, -1.5));
    cut_checked(&index, &target, &cutter).unwrap();
}

/// Shrunk proptest case: a strip whose top face crosses target faces lying in one plane, so a
/// cutter-face piece is flat in every perturbed configuration (flat ears).
#[test]
fn regression_strip_over_coplanar_target_faces() {
    let target = target_sphere();
    let index = TargetIndex::build(target.clone()).unwrap();
    let mut pts = vec![(-3, 25, 10)];
    for s in [(0, 0, -2), (0, 2, 0), (1, 2, 0), (0, -1, 0)] {
        let l = *pts.last().unwrap();
        pts.push((l.0 + s.0, l.1 + s.1, l.2 + s.2));
    }
    let cutter = strip_from(&pts, 0.25, 8.0 * 0.25, 27.0 * 0.25);
    cut_checked(&index, &target, &cutter).unwrap();
}

/// Shrunk proptest case (found by CI at the end of session 1): a short snapped strip near the
/// sphere's top where kept + removed exceeded the target's area by 0.012. Root cause: the ear
/// clipper ignored a (flat) chain vertex lying exactly on the diagonal of a candidate ear (contour
/// points on one vertical cutter plane are collinear in the face's projection), so the clipped
/// polygon touched itself and the last triangle came out inverted. Ears are now tested against
/// the closed triangle.
#[test]
fn regression_short_strip_near_the_pole_loses_area() {
    let target = target_sphere();
    let index = TargetIndex::build(target.clone()).unwrap();
    let mut pts = vec![(-18, -21, 31)];
    for s in [(0, -2, 2), (0, 0, 2), (0, 2, 0)] {
        let l = *pts.last().unwrap();
        pts.push((l.0 + s.0, l.1 + s.1, l.2 + s.2));
    }
    let cutter = strip_from(&pts, 0.25, 7.0 * 0.25, 4.0 * 0.25);
    cut_checked(&index, &target, &cutter).unwrap();
}
