//! Through-cuts: a blade deeper than the structure cuts a slot through it, following its far
//! side.

use super::*;

#[test]
fn blade_deeper_than_a_slab_cuts_a_slot_through_it() {
    let mesh = slab(20, 0.5);
    let pts = line(DVec3::new(5.3, 10.2, 0.5), DVec3::new(14.6, 10.7, 0.5), 0.4);
    let (before, after, s) = through_stroke(&mesh, 1.0, &pts);
    assert_eq!(before.euler, 2);
    // A slot through the slab: closed, one piece, genus 1.
    assert!(after.closed && after.manifold);
    assert_eq!(
        (after.components, after.boundary_loops, after.euler),
        (1, 0, 0)
    );
    // Both faces of the slab were cut: new vertices on the top and on the bottom.
    let m = s.dyn_mesh();
    let new = mesh.positions.len()..m.vertex_count();
    let on = |z: f64| new.clone().filter(|&v| m.pos(v as u32).z == z).count();
    assert!(
        on(0.5) > 10 && on(0.0) > 10,
        "top {} bottom {}",
        on(0.5),
        on(0.0)
    );
    // The same blade, shallower than the slab: a groove, the genus unchanged.
    let (_, groove, _) = through_stroke(&mesh, 0.3, &pts);
    assert_eq!((groove.components, groove.euler), (1, 2));
}

/// A slot crossing another slot cannot open into it (its end there would not close): it ends
/// short of it and the stroke cuts a new slot past it, every step accepted, the slab closed and
/// manifold after each. Two slots crossing make three holes through the slab: χ 2 → −4.
#[test]
fn slot_reaching_another_slot_goes_on_past_it() {
    let mesh = slab(20, 0.5);
    let first = line(DVec3::new(5.3, 10.2, 0.5), DVec3::new(14.6, 10.7, 0.5), 0.4);
    let (_, after_first, mut s) = through_stroke(&mesh, 1.0, &first);
    assert_eq!(after_first.euler, 0);
    let second = line(DVec3::new(10.3, 4.1, 0.5), DVec3::new(10.6, 16.3, 0.5), 0.4);
    let vertices = s.dyn_mesh().vertex_count();
    s.begin_stroke(second[0]).unwrap();
    for (i, &q) in second[1..].iter().enumerate() {
        s.step(q)
            .unwrap_or_else(|e| panic!("step {i}: {e} ({})", s.last_refusal()));
        let t = topo(&s);
        assert!(t.closed && t.manifold, "step {i}: {t:?}");
    }
    s.end_stroke().unwrap();
    let t = topo(&s);
    assert_eq!((t.components, t.boundary_loops, t.euler), (1, 0, -4));
    // The second stroke cut on both sides of the first slot, on the top and on the bottom.
    let m = s.dyn_mesh();
    let new: Vec<DVec3> = (vertices..m.vertex_count())
        .map(|v| m.pos(v as u32))
        .collect();
    for z in [0.0, 0.5] {
        assert!(
            new.iter().any(|p| p.z == z && p.y < 9.0) && new.iter().any(|p| p.z == z && p.y > 12.0),
            "z {z}: not cut on both sides of the first slot"
        );
    }
}

#[test]
fn blade_deeper_than_a_sphere_cuts_through_it() {
    let sphere = csg::testkit::icosphere(4, 10.0);
    let pts = great_arc(DVec3::X, DVec3::Y, 10.0, -0.3, 0.3, 20);
    let (_, after, _) = through_stroke(&sphere, 25.0, &pts);
    assert_eq!(
        (after.components, after.boundary_loops, after.euler),
        (1, 0, 0)
    );
}

/// The far side of a through-cut follows the actual far surface under each sample (a ray along
/// the inward normal), not the near side moved by the thickness where the cut started: a slab
/// whose top is inclined (normal tilted 17° along the stroke) and rises along it, so the
/// structure is 2 thick along the normal where the stroke starts and 6.4 where it ends. Moved by
/// the starting thickness, the far slit would end about 1.3 short of where the ray from the
/// last sample leaves the slab.
#[test]
fn through_cut_far_side_follows_the_far_surface() {
    let mut mesh = slab(20, 1.0);
    let top = |x: f64| 4.0 + 0.3 * (x - 10.0);
    for p in mesh.positions.iter_mut() {
        if p.z == 1.0 {
            p.z = top(p.x);
        }
    }
    let y0 = 10.7;
    let pts: Vec<DVec3> = line(DVec3::new(3.0, y0, 0.0), DVec3::new(17.0, y0, 0.0), 0.4)
        .into_iter()
        .map(|p| DVec3::new(p.x, p.y, top(p.x)))
        .collect();
    let (_, after, s) = through_stroke(&mesh, 10.0, &pts);
    assert_eq!(
        (after.components, after.boundary_loops, after.euler),
        (1, 0, 0)
    );
    // Where the rays along the inward normal from the first and last samples meet the bottom.
    let n = DVec3::new(-0.3, 0.0, 1.0).normalize();
    let hit = |q: DVec3| q - n * (q.z / n.z);
    let (first, last) = (hit(pts[0]), hit(pts[pts.len() - 1]));
    let m = s.dyn_mesh();
    let far: Vec<DVec3> = (mesh.positions.len()..m.vertex_count())
        .map(|v| m.pos(v as u32))
        .filter(|p| p.z == 0.0)
        .collect();
    let lo = far.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
    let hi = far.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "far slit from x {lo:.2} to {hi:.2}; rays from the ends meet the bottom at {:.2}, {:.2}",
        first.x, last.x
    );
    assert!(far.len() > 10, "only {} far-side vertices", far.len());
    assert!(
        (lo - first.x).abs() <= 0.5 && (hi - last.x).abs() <= 0.5,
        "far slit from {lo} to {hi}, rays at {} and {}",
        first.x,
        last.x
    );
    let drift = far.iter().map(|p| (p.y - y0).abs()).fold(0.0, f64::max);
    assert!(
        drift <= 0.05,
        "the far slit drifts {drift} across the stroke"
    );
}

/// Regression (fuzz): a through-cut that turns sharply, then one crossing it.
#[test]
fn through_cut_regressions_from_fuzzing() {
    let strokes = [
        vec![
            (2.0, 6.100684636962648),
            (7.571928916677586, 9.210302800088467),
            (5.610659398543473, 2.0),
        ],
        vec![
            (2.0, 9.653254714923301),
            (9.224583010187406, 8.333726475664006),
        ],
    ];
    let mesh = slab(12, 0.5);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(1.0)).unwrap();
    for (k, stroke) in strokes.iter().enumerate() {
        let pts: Vec<DVec3> = stroke.iter().map(|&(x, y)| DVec3::new(x, y, 0.5)).collect();
        s.begin_stroke(pts[0]).unwrap();
        for (i, &q) in pts[1..].iter().enumerate() {
            let before = s.mesh();
            let r = s.step(q);
            if r.is_err() {
                assert_eq!(s.mesh(), before);
            }
            let t = validate(s.dyn_mesh())
                .unwrap_or_else(|e| panic!("stroke {k} step {i} ({r:?}): {e}"));
            assert!(t.closed && t.manifold, "stroke {k} step {i}: {t:?}");
        }
        s.end_stroke().unwrap();
        let t = topo(&s);
        assert!(t.closed && t.manifold, "stroke {k} end: {t:?}");
    }
}

/// The slab through-cut survey's strokes (seed 4: slots running onto the ends of earlier
/// slots, where both tips land on that slot's end vertices), replayed step by step: after every
/// step the mesh is valid, closed and manifold, and a refused step leaves it exactly as it was.
#[test]
fn through_cuts_meeting_slot_ends_keep_every_step_atomic() {
    use cutter::scalpel::survey::random_strokes;
    let plate = slab(12, 0.5);
    let mut top = sheet(10);
    top.positions
        .iter_mut()
        .for_each(|q| *q += DVec3::new(1.0, 1.0, 0.5));
    let strokes = random_strokes(&top, 24, 4);
    let mut s = Scalpel::new(&plate, ScalpelOptions::default().with_depth(1.0)).unwrap();
    let (mut steps, mut refused) = (0, 0);
    for stroke in &strokes {
        if s.begin_stroke(stroke[0]).is_err() {
            continue;
        }
        for &q in &stroke[1..] {
            let before = s.dyn_mesh().to_mesh();
            steps += 1;
            if s.step(q).is_err() {
                refused += 1;
                let after = s.dyn_mesh().to_mesh();
                assert_eq!(
                    before.positions, after.positions,
                    "refused step at {q} moved"
                );
                assert_eq!(
                    before.triangles, after.triangles,
                    "refused step at {q} changed"
                );
            }
            let t = validate(s.dyn_mesh()).unwrap_or_else(|e| panic!("step to {q}: {e}"));
            assert!(t.closed && t.manifold, "step to {q}: {t:?}");
        }
        s.end_stroke().unwrap();
    }
    assert!(steps >= 80, "only {steps} steps");
    assert!(refused * 300 <= steps, "{refused} of {steps} steps refused");
}
