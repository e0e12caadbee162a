//! Slits (depth 0) on sheets and spheres: the scenario table of notes/scalpel.md §5 (topology
//! deltas per scenario), crossings, loops, trembling and step-size independence, the element
//! budget of a straight cut, and rejected input.

use super::*;

#[test]
fn s01_straight_interior_slit() {
    let (d, s) = sheet_delta(&[line(p(3.3, 5.4), p(15.6, 9.1), 0.4)]);
    assert_eq!(d, (0, 1, -1));
    // Element budget: crossing a triangle edge to edge leaves 3 in its place (+2), ends ≤ +3.
    let created = s.dyn_mesh().triangle_count() - 800;
    let t = topo(&s);
    assert!(t.boundary_edges > 4);
    assert!(
        created <= 2 * 40 + 6,
        "too many triangles created: {created}"
    );
}

#[test]
fn s02_boundary_to_interior() {
    let (d, _) = sheet_delta(&[line(p(0.0, 7.3), p(9.4, 8.2), 0.5)]);
    assert_eq!(d, (0, 0, 0));
}

#[test]
fn s03_boundary_to_boundary_splits_the_sheet() {
    let (d, s) = sheet_delta(&[line(p(0.0, 7.3), p(20.0, 11.6), 0.5)]);
    assert_eq!(d, (1, 1, 1));
    let t = topo(&s);
    assert_eq!(t.components, 2);
}

#[test]
fn s04_curved_arc_and_s_curve() {
    let arc: Vec<DVec3> = (0..=60)
        .map(|i| {
            let a = i as f64 / 60.0 * 2.5;
            p(10.0 + 5.0 * a.cos(), 10.0 + 5.0 * a.sin())
        })
        .collect();
    assert_eq!(sheet_delta(&[arc]).0, (0, 1, -1));
    let bez = |t: f64| {
        let (p0, p1, p2, p3) = (p(3.2, 3.1), p(18.0, 4.0), p(2.0, 16.0), p(16.7, 17.3));
        let u = 1.0 - t;
        p0 * (u * u * u) + p1 * (3.0 * u * u * t) + p2 * (3.0 * u * t * t) + p3 * (t * t * t)
    };
    let s_curve: Vec<DVec3> = (0..=80).map(|i| bez(i as f64 / 80.0)).collect();
    assert_eq!(sheet_delta(&[s_curve]).0, (0, 1, -1));
}

#[test]
fn s05_exactly_through_vertices_on_the_diagonal() {
    let (d, s) = sheet_delta(&[line(p(4.0, 4.0), p(14.0, 14.0), 0.37)]);
    assert_eq!(d, (0, 1, -1));
    // Along existing edges: no triangle is split, vertices only duplicated (9 interior ones).
    assert_eq!(s.dyn_mesh().triangle_count(), 800);
    assert_eq!(s.dyn_mesh().vertex_count(), 441 + 9);
}

#[test]
fn s06_along_edges_with_offsets() {
    for (off, splits) in [(0.0, false), (1e-9, false), (0.1, false), (0.3, true)] {
        let (d, s) = sheet_delta(&[line(p(4.0, 8.0 + off), p(14.0, 8.0 + off), 0.45)]);
        assert_eq!(d, (0, 1, -1), "offset {off}");
        let grew = s.dyn_mesh().triangle_count() > 800;
        assert_eq!(grew, splits, "offset {off}: splits expected {splits}");
    }
}

#[test]
fn s07_start_and_end_inside_faces() {
    // Barycentric (1/3,1/3,1/3) of triangle (5,5),(6,5),(6,6) and (0.9,0.05,0.05) and (0.5,0.48,0.02).
    let bary = |w: [f64; 3], i: f64, j: f64| {
        p(i, j) * w[0] + p(i + 1.0, j) * w[1] + p(i + 1.0, j + 1.0) * w[2]
    };
    for w in [[1.0 / 3.0; 3], [0.9, 0.05, 0.05], [0.5, 0.48, 0.02]] {
        let a = bary(w, 5.0, 5.0);
        let b = bary(w, 12.0, 9.0);
        let (d, _) = sheet_delta(&[line(a, b, 0.5)]);
        assert_eq!(d, (0, 1, -1), "bary {w:?}");
    }
    // Exactly on an edge and exactly on a vertex.
    let (d, _) = sheet_delta(&[line(p(5.5, 5.0), p(12.0, 9.0), 0.5)]);
    assert_eq!(d, (0, 1, -1));
    let (d, _) = sheet_delta(&[line(p(5.0, 5.0), p(12.0, 9.0), 0.5)]);
    assert_eq!(d, (0, 1, -1));
}

#[test]
fn s08_t_cut_onto_an_existing_slit() {
    let first = line(p(3.3, 10.2), p(16.7, 10.2), 0.5);
    let (_, mut s) = sheet_delta(std::slice::from_ref(&first));
    for end_x in [9.7, 12.0] {
        let mut s2 = s.clone();
        let before = topo(&s2);
        // 90° and 45° approaches ending on the lip.
        let start = if end_x == 9.7 {
            p(9.7, 4.1)
        } else {
            p(6.0, 4.2)
        };
        cut_strokes(&mut s2, &[line(start, p(end_x, 10.2), 0.5)], true, 0.0);
        assert_eq!(delta(&before, &topo(&s2)), (0, 0, 0), "T-cut to x={end_x}");
    }
    assert!(s.undo_stroke());
    assert_eq!(s.dyn_mesh().triangle_count(), 800);
}

#[test]
fn s09_i_cut_joins_two_slits() {
    let (_, mut s) = sheet_delta(&[
        line(p(5.2, 4.3), p(5.2, 15.7), 0.5),
        line(p(14.8, 4.3), p(14.8, 15.7), 0.5),
    ]);
    let before = topo(&s);
    cut_strokes(&mut s, &[line(p(5.2, 10.1), p(14.8, 10.1), 0.5)], true, 0.0);
    assert_eq!(delta(&before, &topo(&s)), (0, -1, 1));
}

fn x_cut(angle_deg: f64) -> ((i64, i64, i64), TopologyReport, Scalpel) {
    let (_, mut s) = sheet_delta(&[line(p(3.3, 10.2), p(16.7, 10.2), 0.5)]);
    let before = topo(&s);
    let a = angle_deg.to_radians();
    let dir = DVec3::new(a.cos(), a.sin(), 0.0);
    let c = p(10.1, 10.2);
    cut_strokes(
        &mut s,
        &[line(c - dir * 5.0, c + dir * 5.0, 0.5)],
        true,
        0.0,
    );
    let after = topo(&s);
    (delta(&before, &after), after, s)
}

#[test]
fn s10_x_cut_at_90_degrees_crosses() {
    let (d, after, s) = x_cut(90.0);
    assert_eq!(d, (0, 0, 0));
    assert_eq!((after.boundary_loops, after.euler), (2, 0));
    // The junction point has 4 copies.
    let m = s.dyn_mesh();
    let max_copies = (0..m.vertex_count() as u32)
        .map(|v| m.copies(v).len() + 1)
        .max()
        .unwrap_or(1);
    assert_eq!(max_copies, 4);
}

#[test]
fn s11_cross_at_20_degrees_merge_at_10() {
    let (d, _, _) = x_cut(20.0);
    assert_eq!(d, (0, 0, 0), "20° crosses");
    // 10°: merges into the existing slit instead of crossing: the second cut ends on the lip
    // (T-junction) and opens no new hole of its own on the far side within the lip's reach.
    let (_, after, s) = x_cut(10.0);
    let m = s.dyn_mesh();
    let max_copies = (0..m.vertex_count() as u32)
        .map(|v| m.copies(v).len() + 1)
        .max()
        .unwrap_or(1);
    assert!(
        max_copies < 4,
        "10° must not cross (found a {max_copies}-copy junction)"
    );
    assert!(after.manifold);
}

#[test]
fn s12_self_crossing_alpha_detaches_a_disk() {
    // Start inside, loop counter-clockwise, cross the own path, exit.
    let mut pts = vec![p(4.2, 10.1)];
    pts.extend(line(p(4.2, 10.1), p(9.95, 10.1), 0.5));
    for i in 0..=72 {
        let a = -std::f64::consts::FRAC_PI_2 + i as f64 / 72.0 * 1.8 * std::f64::consts::PI;
        pts.push(p(12.95 + 3.0 * a.cos() - 3.0, 13.1 + 3.0 * a.sin()));
    }
    let last = *pts.last().unwrap();
    pts.extend(line(last, p(last.x, 5.3), 0.5));
    let (d, _) = sheet_delta(&[pts]);
    assert_eq!(d, (1, 2, 0));
}

#[test]
fn s13_loop_tool_detaches_on_sheet_and_sphere() {
    let circle = |c: DVec3, r: f64, n: usize| -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                c + DVec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect()
    };
    let mesh = sheet(20);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_tool(Tool::Loop)).unwrap();
    let before = topo(&s);
    let pts = circle(p(10.3, 9.8), 4.1, 60);
    s.begin_stroke(pts[0]).unwrap();
    for &q in &pts[1..] {
        s.step(q).unwrap();
        topo(&s);
    }
    let report = s.end_stroke().unwrap();
    assert_eq!(delta(&before, &topo(&s)), (1, 2, 0));
    assert_eq!(report.detached.len(), 1);
    let piece = &report.detached[0];
    let expected = std::f64::consts::PI * 4.1 * 4.1;
    assert!(
        (piece.area() - expected).abs() < 0.1 * expected,
        "piece area {}",
        piece.area()
    );

    let sphere = csg::testkit::icosphere(4, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_tool(Tool::Loop)).unwrap();
    let before = topo(&s);
    assert_eq!((before.boundary_loops, before.euler), (0, 2));
    let pts: Vec<DVec3> = (0..48)
        .map(|i| {
            let a = i as f64 / 48.0 * std::f64::consts::TAU;
            DVec3::new(4.0 * a.cos(), 4.0 * a.sin(), 9.0).normalize() * 10.0
        })
        .collect();
    s.begin_stroke(pts[0]).unwrap();
    for &q in &pts[1..] {
        s.step(q).unwrap();
        assert!(topo(&s).manifold);
    }
    let report = s.end_stroke().unwrap();
    let after = topo(&s);
    assert_eq!(delta(&before, &after), (1, 2, 0));
    assert_eq!(report.detached.len(), 1);
}

#[test]
fn s14_cut_off_a_corner() {
    let (d, _) = sheet_delta(&[line(p(0.0, 3.7), p(3.6, 0.0), 0.3)]);
    assert_eq!(d, (1, 1, 1));
}

/// The 20×20 sheet with the unit squares of `[8, 12]²` removed (a square hole: b = 2, χ = 0).
fn sheet_with_hole() -> Mesh {
    let full = sheet(20);
    let triangles = full
        .triangles
        .iter()
        .copied()
        .filter(|t| {
            let c = t.iter().map(|&v| full.positions[v as usize]).sum::<DVec3>() / 3.0;
            !(8.0..12.0).contains(&c.x) || !(8.0..12.0).contains(&c.y)
        })
        .collect();
    Mesh::new(full.positions.clone(), triangles)
        .unwrap()
        .compacted()
}

#[test]
fn s15_cut_from_the_outer_boundary_into_the_hole() {
    let mut s = Scalpel::new(&sheet_with_hole(), ScalpelOptions::default()).unwrap();
    let before = topo(&s);
    assert_eq!(
        (before.components, before.boundary_loops, before.euler),
        (1, 2, 0)
    );
    cut_strokes(&mut s, &[line(p(0.0, 10.3), p(8.0, 10.3), 0.45)], true, 1.0);
    assert_eq!(delta(&before, &topo(&s)), (0, -1, 1));
}

#[test]
fn s19_near_degenerate_paths() {
    let h = 2f64.sqrt();
    // Passing 1e-9 h from a vertex, and parallel to an edge at 1e-9 h.
    for path in [
        line(p(3.0, 5.0 + 1e-9 * h), p(13.0, 5.0 + 1e-9 * h), 0.45),
        line(p(3.2, 3.2 + 1e-9 * h), p(12.7, 12.7 + 1e-9 * h), 0.45),
        line(p(3.3, 7.0 - 1e-9 * h), p(15.6, 7.0 - 1e-9 * h), 0.3),
    ] {
        let (d, _) = sheet_delta(&[path]);
        assert_eq!(d, (0, 1, -1));
    }
}

#[test]
fn s20_spiral_close_to_its_own_lips() {
    // ~80 segments, turns 2.5 h apart (h = √2), interior of a 40×40 sheet.
    let mesh = sheet(40);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    let before = topo(&s);
    let h = 2f64.sqrt();
    let b = 2.5 * h / std::f64::consts::TAU;
    let mut pts = Vec::new();
    let mut theta: f64 = 2.0 * std::f64::consts::TAU;
    while pts.len() < 81 {
        let r = b * theta;
        pts.push(p(20.13 + r * theta.cos(), 19.87 + r * theta.sin()));
        theta += 0.8 * h / r;
    }
    cut_strokes(&mut s, &[pts], true, 1.0);
    assert_eq!(delta(&before, &topo(&s)), (0, 1, -1));
}

/// Notes §4 Q0: the smallest angle of the triangles the corpus creates (slits
/// on the grid sheet, grooves and crossings on the sphere), printed as a histogram.
#[test]
fn min_angle_statistics_over_the_corpus() {
    let mut hist = [0usize; 6]; // <1°, 1–5°, 5–10°, 10–20°, 20–30°, ≥30°
    let mut worst_slit = 180.0f64;
    let mut worst_groove = 180.0f64;
    let mut count = |s: &Scalpel, from: usize, worst: &mut f64| {
        let m = s.dyn_mesh();
        for t in from..m.triangle_count() {
            let a = min_angle_deg(m, t as u32);
            *worst = worst.min(a);
            let k = [1.0, 5.0, 10.0, 20.0, 30.0]
                .iter()
                .take_while(|&&x| a >= x)
                .count();
            hist[k] += 1;
        }
    };
    let slits = [
        vec![line(p(3.3, 5.4), p(15.6, 9.1), 0.4)],
        vec![line(p(4.0, 4.0), p(14.0, 14.0), 0.37)],
        vec![line(p(4.0, 8.3), p(14.0, 8.3), 0.45)],
        vec![
            (0..=60)
                .map(|i| {
                    let a = i as f64 / 60.0 * 2.5;
                    p(10.0 + 5.0 * a.cos(), 10.0 + 5.0 * a.sin())
                })
                .collect(),
        ],
        vec![line(p(0.0, 7.3), p(20.0, 11.6), 0.5)],
    ];
    for strokes in &slits {
        let (_, s) = sheet_delta(strokes);
        count(&s, 800, &mut worst_slit);
    }
    let crossing = DVec3::new(0.7f64.cos(), 0.7f64.sin(), 0.0);
    for dir in [DVec3::Z, DVec3::new(-0.7f64.sin(), 0.7f64.cos(), 0.18)] {
        let mut s = equator_groove(0.8);
        let from = csg::testkit::icosphere(4, 10.0).triangles.len();
        groove_strokes(&mut s, &[great_arc(crossing, dir, 10.0, -0.3, 0.3, 30)]);
        count(&s, from, &mut worst_groove);
    }
    eprintln!(
        "min angle: slits {worst_slit:.2}°, grooves {worst_groove:.2}°; histogram <1° {}, 1–5° {}, 5–10° {}, 10–20° {}, 20–30° {}, ≥30° {}",
        hist[0], hist[1], hist[2], hist[3], hist[4], hist[5]
    );
    assert!(worst_slit >= 1.0, "slit sliver: {worst_slit}°");
    assert!(worst_groove > 0.0);
}

#[test]
fn s16_retracing_a_lip_changes_nothing() {
    let path = line(p(3.3, 10.2), p(16.7, 10.2), 0.5);
    let (_, mut s) = sheet_delta(std::slice::from_ref(&path));
    let before = topo(&s);
    let f = s.dyn_mesh().triangle_count();
    cut_strokes(&mut s, &[line(p(5.0, 10.2), p(15.0, 10.2), 0.5)], true, 0.0);
    assert_eq!(delta(&before, &topo(&s)), (0, 0, 0));
    assert_eq!(s.dyn_mesh().triangle_count(), f);
}

#[test]
fn s17_trembling_matches_the_monotone_path() {
    let (a, b) = (p(3.3, 5.4), p(15.6, 9.1));
    let dir = (b - a).normalize();
    let mut tremble = vec![a];
    let mut x = 0.0;
    while x < (b - a).length() - 0.7 {
        x += 0.6;
        tremble.push(a + dir * x);
        tremble.push(a + dir * (x - 0.3));
    }
    tremble.push(b);
    let (d1, s1) = sheet_delta(&[line(a, b, 0.4)]);
    let (d2, s2) = sheet_delta(&[tremble]);
    assert_eq!(d1, d2);
    let (f1, f2) = (
        s1.dyn_mesh().triangle_count() as i64,
        s2.dyn_mesh().triangle_count() as i64,
    );
    assert!((f1 - f2).abs() <= 2, "{f1} vs {f2} triangles");
}

#[test]
fn s18_step_size_sweep_gives_the_same_topology() {
    let (a, b) = (p(3.3, 5.4), p(15.6, 9.1));
    let h = 2f64.sqrt();
    let mut faces = Vec::new();
    for spacing in [0.05 * h, 0.5 * h, 2.0 * h, 50.0 * h] {
        let (d, s) = sheet_delta(&[line(a, b, spacing)]);
        assert_eq!(d, (0, 1, -1), "spacing {spacing}");
        faces.push(s.dyn_mesh().triangle_count() as i64);
    }
    let (lo, hi) = (faces.iter().min().unwrap(), faces.iter().max().unwrap());
    assert!(hi - lo <= 2, "face counts vary with step size: {faces:?}");
}

#[test]
fn s23_hourglass_is_rejected_and_the_mesh_unchanged() {
    // Two fans sharing only vertex 0 (a bow-tie).
    let mesh = csg::testkit::bow_tie();
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    let before = s.mesh();
    let r = s
        .begin_stroke(DVec3::new(-2.0, 0.1, 0.0))
        .and_then(|_| s.step(DVec3::new(0.0, 0.0, 0.0)))
        .and_then(|_| s.step(DVec3::new(2.0, 0.1, 0.0)));
    assert!(r.is_err(), "cutting through a bow-tie must fail");
    s.undo_stroke();
    assert_eq!(s.mesh(), before);
}

#[test]
fn off_mesh_sample_is_an_error_and_changes_nothing() {
    let mesh = sheet(10);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    assert!(s.begin_stroke(p(50.0, 50.0)).is_err());
    assert_eq!(s.mesh(), mesh);
    s.begin_stroke(p(2.3, 2.4)).unwrap();
    s.step(p(4.1, 3.3)).unwrap();
    let mid = s.mesh();
    let err = s.step(DVec3::new(5.0, 4.0, 30.0)).unwrap_err();
    assert!(err.to_string().contains("off the mesh"), "{err}");
    assert_eq!(s.mesh(), mid, "a failed step leaves the mesh as it was");
    s.step(p(6.2, 4.1)).unwrap();
    s.end_stroke().unwrap();
    assert!(s.undo_stroke());
    assert_eq!(s.mesh(), mesh);
}

#[test]
fn element_budget_straight_cut() {
    // Notes T1: a triangle crossed edge to edge becomes 3 (+2 net): net new triangles per crossed
    // triangle ≤ 2 on average (plus the two end faces).
    let mesh = sheet(40);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    let pts = line(p(2.3, 7.1), p(37.4, 30.2), 0.3);
    s.begin_stroke(pts[0]).unwrap();
    for &q in &pts[1..] {
        s.step(q).unwrap();
    }
    let r = s.end_stroke().unwrap();
    assert!(r.triangles_cut > 30);
    // Triangle by triangle (T1): never more than 4 pieces in one crossed triangle (an end
    // inside), 3 on average at most; a slit has no walls (T4).
    let b = survey::element_budget(&mesh, s.dyn_mesh());
    assert!(
        b.pieces_max <= 4,
        "{} pieces in triangle {}",
        b.pieces_max,
        b.worst
    );
    assert!(b.pieces_mean <= 3.0, "{} pieces on average", b.pieces_mean);
    assert_eq!(b.wall_triangles, 0);
    assert_eq!(b.total_new, r.triangles_created);
    let per = r.triangles_created as f64 / r.triangles_cut as f64;
    assert!(
        per <= 2.0 + 6.0 / r.triangles_cut as f64,
        "{} new per {} crossed",
        r.triangles_created,
        r.triangles_cut
    );
}

/// A cut that merged into a slit restarts, inside the same stroke, once the blade is past the
/// slit's end (the restart's nearest face is searched outward from where the cut merged, not
/// over the whole mesh): the stroke cuts on beyond the old slit.
#[test]
fn cut_restarts_past_the_slit_it_merged_into() {
    let mut s = Scalpel::new(&sheet(12), ScalpelOptions::default()).unwrap();
    cut_strokes(&mut s, &[line(p(6.1, 2.2), p(6.1, 7.3), 0.3)], true, 0.0);
    let before = s.segments().len();
    // 8° off the slit: merges into it, slides along its lips, then leaves them past its end.
    let mut pts = line(p(5.6, 1.8), p(6.1, 5.3), 0.3);
    pts.extend(line(p(6.1, 5.6), p(6.1, 10.7), 0.3));
    s.begin_stroke(pts[0]).unwrap();
    for &q in &pts[1..] {
        s.step(q).unwrap();
    }
    s.end_stroke().unwrap();
    let beyond = s.segments()[before..]
        .iter()
        .filter(|g| g.pa.y > 7.8 && g.pb.y > 7.8)
        .map(|g| g.pa.distance(g.pb))
        .sum::<f64>();
    assert!(beyond > 2.0, "cut only {beyond} beyond the old slit's end");
    assert!(validate(s.dyn_mesh()).unwrap().manifold);
}
