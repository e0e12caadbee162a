//! Where a finished cut ends (`Scalpel::end_stroke`, `relocate::tip_onto`): the lips end at the
//! drawn end of the path, not where the walk snapped its tip to avoid a sliver (up to a quarter
//! of the last segment for a slit, half of it for a groove).

use super::*;

/// Slits and grooves along wavy paths of many lengths over a sphere (so the last sample falls
/// anywhere in a triangle, near vertices and edges too): after the stroke the cut's end vertex
/// (the last segment's end, the vertex itself) is within 2% of an edge of the last sample's
/// nearest point on the sphere in at least nine strokes in ten (the move is refused where it
/// would make a sliver of a triangle around the tip; the walk's snap is up to half a segment) and
/// never farther than 0.6 edges; the
/// mesh stays valid, a groove closed.
#[test]
fn cut_ends_at_the_drawn_tip() {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(5, r);
    let [a, b, _] = sphere.triangles[0].map(|v| sphere.positions[v as usize]);
    let h = a.distance(b);
    let path: Vec<DVec3> = (0..=120)
        .map(|i| {
            let u = i as f64 / 120.0;
            let lon = -0.6 + 1.2 * u;
            let lat = 0.12 * (u * std::f64::consts::TAU).sin();
            DVec3::new(lat.cos() * lon.sin(), -lat.cos() * lon.cos(), lat.sin()) * r
        })
        .collect();
    for depth in [0.0, 0.75, 3.0] {
        let (mut close, mut strokes, mut worst) = (0, 0, 0.0f64);
        for samples in (30..=120).step_by(3) {
            let path = &path[..=samples];
            let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
            s.cut_stroke(path).unwrap();
            let t = topo(&s);
            assert!(t.manifold, "{t:?}");
            if depth > 0.0 {
                assert!(t.closed, "depth {depth}, {samples} samples: {t:?}");
            }
            let end = path[samples].normalize() * r;
            let seg = s.segments()[s.segments().len() - 1];
            let tip = s.dyn_mesh().pos(seg.b);
            assert_eq!(tip, seg.pb, "the segment ends where its vertex is");
            // The sphere's triangles are chords: the drawn end on the mesh is up to the
            // sagitta (h²/8r) inside the sphere.
            let off = (tip.distance(end) - h * h / (8.0 * r)).max(0.0) / h;
            worst = worst.max(off);
            strokes += 1;
            if off <= 0.02 {
                close += 1;
            }
        }
        println!(
            "depth {depth}: {close} of {strokes} cuts end within 2% of an edge of the drawn end, worst {worst:.3} edges"
        );
        assert!(
            10 * close >= 9 * strokes,
            "depth {depth}: {close} of {strokes} cuts end within 2% of an edge of the drawn end"
        );
        assert!(
            worst <= 0.6,
            "depth {depth}: a cut ends {worst} edges from the drawn end"
        );
    }
}
