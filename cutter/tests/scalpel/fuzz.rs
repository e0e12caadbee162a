//! Random strokes: property tests (never a panic, a valid mesh after every step, a refused
//! step changes nothing) and the refusal rate on seeded random strokes.

use super::*;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]
    /// Random polylines (including self-crossing ones and near-degenerate samples) on a small
    /// sheet: never a panic; after every step (ok or error) the mesh is valid, and a failed
    /// step leaves it exactly as it was.
    /// Random grooves on a closed sphere (crossing each other and themselves): after every
    /// step (ok or error) the surface is valid, closed, manifold, of Euler characteristic 2,
    /// and a failed step leaves it exactly as it was.
    #[test]
    fn random_grooves_keep_a_sphere_closed(
        strokes in prop::collection::vec(
            prop::collection::vec((-0.6f64..0.6, -0.6f64..0.6), 2..16), 1..4),
        depth in prop::sample::select(vec![0.3, 0.8, 1.5]),
    ) {
        let sphere = csg::testkit::icosphere(3, 10.0);
        let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
        for stroke in strokes {
            let pts: Vec<DVec3> = stroke
                .iter()
                .map(|&(a, b)| DVec3::new(1.0, a, b).normalize() * 10.0)
                .collect();
            let before = s.mesh();
            if s.begin_stroke(pts[0]).is_err() {
                prop_assert_eq!(s.mesh(), before);
                continue;
            }
            for &q in &pts[1..] {
                let before = s.mesh();
                if s.step(q).is_err() {
                    prop_assert_eq!(s.mesh(), before);
                }
                let t = validate(s.dyn_mesh());
                prop_assert!(t.is_ok(), "{:?}", t);
                let t = t.unwrap();
                prop_assert!(t.closed && t.manifold && t.euler == 2, "{:?}", t);
            }
            let _ = s.end_stroke();
            let t = validate(s.dyn_mesh()).unwrap();
            prop_assert!(t.closed && t.manifold && t.euler == 2, "{:?}", t);
        }
    }

    /// Random strokes on a thin slab with a blade deeper than the slab (through-cuts) or
    /// shallower (grooves): after every step the surface is valid, closed and manifold,
    /// and a failed step leaves it exactly as it was.
    #[test]
    fn random_through_cuts_keep_a_slab_closed(
        strokes in prop::collection::vec(
            prop::collection::vec((2.0f64..10.0, 2.0f64..10.0), 2..12), 1..3),
        depth in prop::sample::select(vec![0.3, 1.0]),
    ) {
        let mesh = slab(12, 0.5);
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
        for stroke in strokes {
            let pts: Vec<DVec3> = stroke.iter().map(|&(x, y)| DVec3::new(x, y, 0.5)).collect();
            let before = s.mesh();
            if s.begin_stroke(pts[0]).is_err() {
                prop_assert_eq!(s.mesh(), before);
                continue;
            }
            for &q in &pts[1..] {
                let before = s.mesh();
                if s.step(q).is_err() {
                    prop_assert_eq!(s.mesh(), before);
                }
                let t = validate(s.dyn_mesh());
                prop_assert!(t.is_ok(), "{:?}", t);
                let t = t.unwrap();
                prop_assert!(t.closed && t.manifold, "{:?}", t);
            }
            let _ = s.end_stroke();
            let t = validate(s.dyn_mesh()).unwrap();
            prop_assert!(t.closed && t.manifold, "{:?}", t);
        }
    }

    #[test]
    fn random_strokes_never_break_the_mesh(
        strokes in prop::collection::vec(
            prop::collection::vec((0.0f64..8.0, 0.0f64..8.0, 0u8..4), 2..20), 1..4),
        depth in prop::sample::select(vec![0.0, 0.0, 0.5]),
    ) {
        let mesh = sheet(8);
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
        for stroke in strokes {
            let pts: Vec<DVec3> = stroke
                .iter()
                .map(|&(x, y, snap)| match snap {
                    // Snap some samples onto grid vertices / edges (degenerate cases).
                    0 => p(x.round(), y.round()),
                    1 => p(x.round() + 1e-9, y),
                    _ => p(x, y),
                })
                .collect();
            if s.begin_stroke(pts[0]).is_err() {
                continue;
            }
            for &q in &pts[1..] {
                let before = s.mesh();
                if s.step(q).is_err() {
                    prop_assert_eq!(s.mesh(), before);
                }
                let t = validate(s.dyn_mesh());
                prop_assert!(t.is_ok(), "{:?}", t);
            }
            let _ = s.end_stroke();
            let t = validate(s.dyn_mesh());
            prop_assert!(t.is_ok(), "{:?}", t);
        }
    }
}

/// Refused steps on random strokes (`scalpel::survey`): slits and grooves on a sphere, slits
/// and through-cuts on a thin slab. A refused step leaves the mesh unchanged (checked by the
/// step's transaction) and only delays the cut; this bounds how often it happens.
#[test]
fn refusal_rate_on_random_strokes() {
    use cutter::scalpel::survey::{random_strokes, survey};
    let sphere = csg::testkit::icosphere(3, 10.0);
    let plate = slab(12, 0.5);
    // Bounds: measured rates (seeded, so exact) with a margin; see the report printed.
    let cases: [(&str, &Mesh, f64, u64, f64); 4] = [
        ("sphere slit", &sphere, 0.0, 1, 0.01),
        ("sphere groove", &sphere, 0.5, 2, 0.005),
        ("slab slit", &plate, 0.0, 3, 0.01),
        ("slab through", &plate, 1.0, 4, 0.003),
    ];
    // Paths for the slot: on the slab's top face, 1 from its rim (a through-cut over the rim
    // has no far side under it): drawn on a sheet of that extent, lifted onto the top.
    let mut top = sheet(10);
    top.positions
        .iter_mut()
        .for_each(|q| *q += DVec3::new(1.0, 1.0, 0.5));
    for (name, mesh, depth, seed, bound) in cases {
        let strokes = random_strokes(if depth > 0.5 { &top } else { mesh }, 24, seed);
        let options = ScalpelOptions::default().with_depth(depth);
        let (r, s) = survey(mesh, options, &strokes).unwrap();
        eprintln!(
            "{name}: {} strokes, {} steps, {} refused ({:.2}%), {} off mesh; causes {:?}",
            r.strokes,
            r.steps,
            r.refused,
            100.0 * r.rate(),
            r.off_mesh,
            r.top_causes()
        );
        assert!(r.steps >= 80, "{name}: only {} steps", r.steps);
        validate(s.dyn_mesh()).unwrap_or_else(|e| panic!("{name}: {e}"));
        // A slot meeting another cut ends there and starts again past it (no refusal), on
        // either side: a far cut blocked by another slot's walls is such a meeting too.
        assert!(
            !r.causes
                .contains_key("through-cut blocked by a cut or boundary"),
            "{name}: {:?}",
            r.top_causes()
        );
        assert!(
            !r.causes.contains_key("far cut did not reach its sample"),
            "{name}: {:?}",
            r.top_causes()
        );
        // A slot whose two tips land on another slot's end vertices meets that slot (its end
        // edge is there already): it ends and restarts, not a step refused by the local check.
        if name == "slab through" {
            assert!(
                !r.causes.contains_key("local check"),
                "{name}: {:?}",
                r.top_causes()
            );
        }
        assert!(
            r.rate() <= bound,
            "{name}: {} of {} steps refused; causes {:?}",
            r.refused,
            r.steps,
            r.top_causes()
        );
        // Every sample is on the surface: an off-mesh error means the tip could not follow.
        assert!(
            r.off_mesh as f64 <= 0.08 * r.steps as f64,
            "{name}: {} of {} on-surface samples refused as off the mesh",
            r.off_mesh,
            r.steps
        );
    }
}
