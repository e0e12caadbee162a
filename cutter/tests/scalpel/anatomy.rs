//! Strokes on real anatomy (`CUTAWAY_ANATOMY`; skipped with a printed reason when absent).

use super::*;
use csg::testkit::{Resource, skip};

#[test]
fn strokes_on_real_anatomy() {
    let Some(dir) = anatomy_dir() else {
        return skip(Resource::Data, "no anatomy (set CUTAWAY_ANATOMY)");
    };
    let path = dir.join("knee_vhf_left_denver/VHF_Left_Muscle_Gracilis_smooth.stl");
    let Some(mesh) = read_binary_stl(&path) else {
        return skip(Resource::Data, format!("cannot read {}", path.display()));
    };
    // A stroke along the muscle's long axis on its surface, as a groove and as a slit.
    let bb = mesh.bbox();
    let axis = (0..3)
        .max_by(|&a, &b| bb.size()[a].total_cmp(&bb.size()[b]))
        .unwrap();
    let c = bb.center();
    for depth in [0.0, 1.5] {
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
        let before = topo(&s);
        let mut pts = Vec::new();
        for i in 0..=60 {
            let mut q = c;
            q[axis] = bb.min[axis] + bb.size()[axis] * (0.3 + 0.4 * i as f64 / 60.0);
            // Project onto the surface along the +x side: closest vertex in a slab.
            let v = mesh
                .positions
                .iter()
                .filter(|p| (p[axis] - q[axis]).abs() < 2.0)
                .max_by(|a, b| a[(axis + 1) % 3].total_cmp(&b[(axis + 1) % 3]))
                .copied()
                .unwrap();
            pts.push(v);
        }
        s.begin_stroke(pts[0]).unwrap();
        for &q in &pts[1..] {
            s.step(q).unwrap();
            assert!(topo(&s).manifold);
        }
        s.end_stroke().unwrap();
        let after = topo(&s);
        if depth > 0.0 {
            assert!(after.closed, "groove on a closed muscle keeps it closed");
            assert_eq!(delta(&before, &after), (0, 0, 0));
            // A second groove around the muscle, across the first one (an X on real anatomy):
            // the surface stays closed, manifold, same genus, after every step (refused steps
            // leave it as it was).
            let mid = bb.min[axis] + 0.5 * bb.size()[axis];
            let (e2, e3) = ((axis + 1) % 3, (axis + 2) % 3);
            let ring: Vec<DVec3> = mesh
                .positions
                .iter()
                .filter(|p| (p[axis] - mid).abs() < 0.5)
                .copied()
                .collect();
            if ring.len() < 8 {
                println!("skipped the crossing groove: {} ring vertices", ring.len());
                continue;
            }
            let centre = ring.iter().sum::<DVec3>() / ring.len() as f64;
            let angle = |p: &DVec3| (p[e3] - centre[e3]).atan2(p[e2] - centre[e2]);
            let mut arc: Vec<DVec3> = ring.into_iter().filter(|p| angle(p).abs() < 1.0).collect();
            arc.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
            let mut pts: Vec<DVec3> = Vec::new();
            for q in arc {
                if pts.last().is_none_or(|l| l.distance(q) > 0.8) {
                    pts.push(q);
                }
            }
            let mut refused = 0;
            s.begin_stroke(pts[0]).unwrap();
            for &q in &pts[1..] {
                let was = s.mesh();
                if s.step(q).is_err() {
                    refused += 1;
                    assert_eq!(s.mesh(), was);
                }
                let t = topo(&s);
                assert!(t.closed && t.manifold && t.euler == before.euler, "{t:?}");
            }
            s.end_stroke().unwrap();
            assert!(
                refused * 4 <= pts.len(),
                "{refused} of {} steps refused",
                pts.len()
            );
            // The second groove met the first: a junction point has 3 or 4 copies.
            assert!(max_copies(&s) >= 3, "the grooves did not meet");
        } else {
            assert_eq!(delta(&before, &after), (0, 1, -1));
        }
    }
}

/// Refused steps on random strokes on a real muscle (slits and grooves); skipped without the
/// anatomy.
#[test]
fn refusal_rate_on_real_anatomy() {
    use cutter::scalpel::survey::{mean_edge, random_strokes, survey};
    let Some(dir) = anatomy_dir() else {
        return skip(Resource::Data, "no anatomy (set CUTAWAY_ANATOMY)");
    };
    let path = dir.join("knee_vhf_left_denver/VHF_Left_Muscle_Gracilis_smooth.stl");
    let Some(mesh) = read_binary_stl(&path) else {
        return skip(Resource::Data, format!("cannot read {}", path.display()));
    };
    let strokes = random_strokes(&mesh, 10, 11);
    let h = mean_edge(&mesh);
    for depth in [0.0, 2.0 * h] {
        let options = ScalpelOptions::default().with_depth(depth);
        let (r, s) = survey(&mesh, options, &strokes).unwrap();
        eprintln!(
            "gracilis depth {depth:.3}: {} strokes, {} steps, {} refused ({:.2}%), {} off mesh; causes {:?}",
            r.strokes,
            r.steps,
            r.refused,
            100.0 * r.rate(),
            r.off_mesh,
            r.top_causes()
        );
        let t = validate(s.dyn_mesh()).unwrap();
        assert!(t.manifold);
        assert!(r.steps >= 50 && r.rate() <= 0.08, "{:?}", r.top_causes());
    }
}
