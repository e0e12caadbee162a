//! Scalpel scenario corpus (notes/scalpel.md §5): each scenario cuts a test mesh and compares
//! the change in components (C), boundary loops (b) and Euler characteristic (χ) with the table;
//! every step is followed by the full validator, an area check (splitting conserves area) and a
//! sliver check on the triangles the step created.

#[path = "support/binary_stl.rs"]
mod binary_stl;

use binary_stl::read_binary_stl;
use csg::{DVec3, Mesh};
use cutter::scalpel::invariants::{min_angle_deg, t_junction_near, validate};
use cutter::scalpel::{Scalpel, ScalpelOptions, Tool, TopologyReport, survey};

/// An `n × n` grid of unit squares on z = 0 from (0, 0), each split on the (0,0)-(1,1) diagonal
/// (right-isosceles triangles; longest edge h = √2).
fn sheet(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

fn topo(s: &Scalpel) -> TopologyReport {
    validate(s.dyn_mesh()).unwrap_or_else(|e| panic!("invalid mesh: {e}"))
}

fn delta(before: &TopologyReport, after: &TopologyReport) -> (i64, i64, i64) {
    (
        after.components as i64 - before.components as i64,
        after.boundary_loops as i64 - before.boundary_loops as i64,
        after.euler - before.euler,
    )
}

fn area(s: &Scalpel) -> f64 {
    s.mesh().area()
}

/// Checks after a step: valid structure, no sliver among the triangles created since
/// `triangles_before` (unless `min_angle` is 0), no geometric T-junction at new vertices, and
/// area conserved when `conserve_area`.
fn check_step(
    s: &Scalpel,
    triangles_before: usize,
    vertices_before: usize,
    area0: f64,
    conserve_area: bool,
    min_angle: f64,
) {
    let t = topo(s);
    assert!(t.manifold, "not manifold after a step: {t:?}");
    if conserve_area {
        let a = area(s);
        assert!(
            (a - area0).abs() <= 1e-9 * area0,
            "area changed: {area0} -> {a}"
        );
    }
    let m = s.dyn_mesh();
    for tri in triangles_before..m.triangle_count() {
        let ang = min_angle_deg(m, tri as u32);
        assert!(
            ang >= min_angle,
            "sliver: triangle {tri} has a {ang}° angle"
        );
    }
    // Geometric T-junctions in the rest pose (slits only: a groove's two lips coincide in the
    // rest pose while being separate sheets joined by the walls).
    if conserve_area {
        for v in vertices_before..m.vertex_count() {
            assert!(
                !t_junction_near(m, v as u32),
                "T-junction at new vertex {v}"
            );
        }
    }
}

/// Cuts `strokes` (each a polyline of samples), validating after every step.
fn cut_strokes(s: &mut Scalpel, strokes: &[Vec<DVec3>], conserve_area: bool, min_angle: f64) {
    let area0 = area(s);
    for stroke in strokes {
        let (t0, v0) = (s.dyn_mesh().triangle_count(), s.dyn_mesh().vertex_count());
        s.begin_stroke(stroke[0]).unwrap();
        check_step(s, t0, v0, area0, conserve_area, min_angle);
        for &q in &stroke[1..] {
            s.step(q).unwrap();
            check_step(s, t0, v0, area0, conserve_area, min_angle);
        }
        s.end_stroke().unwrap();
        check_step(s, t0, v0, area0, conserve_area, min_angle);
    }
}

/// Samples the segment `a → b` every `spacing`.
fn line(a: DVec3, b: DVec3, spacing: f64) -> Vec<DVec3> {
    let n = ((b - a).length() / spacing).ceil().max(1.0) as usize;
    (0..=n).map(|i| a.lerp(b, i as f64 / n as f64)).collect()
}

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

/// Cuts the strokes on a fresh 20×20 sheet and returns the topology change.
fn sheet_delta(strokes: &[Vec<DVec3>]) -> ((i64, i64, i64), Scalpel) {
    let mesh = sheet(20);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).unwrap();
    let before = topo(&s);
    assert_eq!(
        (before.components, before.boundary_loops, before.euler),
        (1, 1, 1)
    );
    cut_strokes(&mut s, strokes, true, 1.0);
    (delta(&before, &topo(&s)), s)
}

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
fn s21_grooves_keep_a_sphere_closed() {
    let sphere = csg::testkit::icosphere(4, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(0.8)).unwrap();
    let before = topo(&s);
    let arc = |from: f64, to: f64, tilt: f64| -> Vec<DVec3> {
        (0..=40)
            .map(|i| {
                let a = from + (to - from) * i as f64 / 40.0;
                let v = DVec3::new(a.cos(), a.sin(), tilt);
                v.normalize() * 10.0
            })
            .collect()
    };
    // One straight groove, then a crossing one (on the sphere: a tilted great-circle arc).
    cut_strokes(&mut s, &[arc(0.1, 1.3, 0.0)], false, 0.0);
    let after = topo(&s);
    assert!(after.closed && after.manifold, "{after:?}");
    assert_eq!(delta(&before, &after), (0, 0, 0));
    // Walls: the volume dropped (the groove is carved into the sphere).
    assert!(s.mesh().volume() < sphere.volume());
    let mut pts: Vec<DVec3> = (0..=40)
        .map(|i| {
            let z = -3.0 + 6.0 * i as f64 / 40.0;
            DVec3::new((0.7f64).cos() * 9.0, (0.7f64).sin() * 9.0, z).normalize() * 10.0
        })
        .collect();
    pts.dedup();
    // The crossing groove: every step succeeds with the surface still closed and manifold.
    s.begin_stroke(pts[0]).unwrap();
    for (i, &q) in pts[1..].iter().enumerate() {
        s.step(q).unwrap_or_else(|e| panic!("step {i}: {e}"));
        let t = topo(&s);
        assert!(t.closed && t.manifold && t.euler == 2, "{t:?}");
    }
    s.end_stroke().unwrap();
    let after2 = topo(&s);
    assert!(after2.closed && after2.manifold, "{after2:?}");
    assert_eq!(after2.euler, 2);
}

#[test]
fn multi_layer_blade_grooves_every_surface_it_reaches() {
    use cutter::scalpel::OpenOptions;
    use cutter::scalpel::layers::{Surface, cut_layer, reach, strokes_below};
    // "Skin" (radius 10) over "muscle" (radius 9): two surfaces.
    let skin = csg::testkit::icosphere(4, 10.0);
    let muscle = csg::testkit::icosphere(4, 9.0);
    let skin_index = csg::SpatialIndex::build(&skin);
    let muscle_index = csg::SpatialIndex::build(&muscle);
    let below = [Surface {
        id: 7,
        mesh: &muscle,
        index: &muscle_index,
    }];
    let pts: Vec<Option<DVec3>> = (0..=30)
        .map(|i| {
            let a = 0.1 + 1.0 * i as f64 / 30.0;
            Some(DVec3::new(a.cos(), a.sin(), 0.05).normalize() * 10.0)
        })
        .collect();
    let depth = 1.6;
    assert!(reach(&pts, depth).is_some_and(|b| b.overlaps(&muscle.bbox())));
    let layers = strokes_below(&skin, &skin_index, &pts, depth, &below);
    assert_eq!(layers.len(), 1, "{layers:?}");
    assert_eq!(layers[0].region, 7);
    assert!(
        (layers[0].depth - 0.6).abs() < 0.05,
        "depth left {}",
        layers[0].depth
    );
    // A shallow blade does not reach the muscle.
    assert!(strokes_below(&skin, &skin_index, &pts, 0.8, &below).is_empty());
    // A sample off the surface splits the stroke below it in two.
    let mut gap = pts.clone();
    gap[15] = None;
    let split = strokes_below(&skin, &skin_index, &gap, depth, &below);
    assert_eq!(split.len(), 2, "{split:?}");

    let closed = OpenOptions {
        width: 0.0,
        window: 0.0,
    };
    let options = ScalpelOptions::default().with_depth(depth);
    let (cut, report) = cut_layer(&muscle, &[&layers[0]], options, &closed)
        .unwrap()
        .expect("the muscle is cut");
    assert!(report.triangles_created > 0);
    let s = Scalpel::new(&cut, ScalpelOptions::default()).unwrap();
    let t = topo(&s);
    assert!(t.closed && t.manifold && t.components == 1, "{t:?}");
    // The stroke cut the muscle: its new vertices lie near radius 9, some below it (the groove).
    let new: Vec<DVec3> = cut.positions[muscle.positions.len()..].to_vec();
    assert!(new.len() > 10, "{} new vertices", new.len());
    assert!(new.iter().all(|p| p.length() > 8.0 && p.length() < 9.05));
    assert!(new.iter().any(|p| p.length() < 8.9));
    // A stroke the scalpel refuses (off the surface) leaves the layer alone: an error, no mesh.
    let off = cutter::scalpel::layers::LayerStroke {
        region: 7,
        samples: vec![DVec3::new(50.0, 0.0, 0.0), DVec3::new(51.0, 0.0, 0.0)],
        depth: 0.5,
    };
    assert!(cut_layer(&muscle, &[&off], options, &closed).is_err());
}

#[test]
fn s22_opening_reaches_its_width_and_leaves_the_rest_alone() {
    use cutter::scalpel::OpenOptions;
    use cutter::scalpel::dffd::open_positions;
    let (_, mut s) = sheet_delta(&[line(p(3.3, 10.5), p(16.7, 10.5), 0.5)]);
    s.advance_clock(1.0);
    let open = OpenOptions {
        width: 0.6,
        window: 0.5,
    };
    let shown = open_positions(&s, &open, s.clock());
    let m = s.dyn_mesh();
    // Lip copies at x = 10 (mid-slit) are 0.6 apart; far vertices did not move (bitwise).
    let mid: Vec<u32> = (0..m.vertex_count() as u32)
        .filter(|&v| (m.pos(v) - p(10.0, 10.5)).length() < 1e-9)
        .collect();
    assert_eq!(mid.len(), 2, "two lips at the middle");
    let gap = shown[mid[0] as usize].distance(shown[mid[1] as usize]);
    assert!((gap - 0.6).abs() <= 0.03, "gap {gap}");
    for v in 0..m.vertex_count() {
        let d = (m.pos(v as u32).y - 10.5).abs();
        if d > 3.0 * 0.6 + 1e-9 {
            assert_eq!(
                shown[v],
                m.pos(v as u32),
                "vertex {v} outside the support moved"
            );
        }
    }
    // Just after the cut the newest part is still closed (trailing window).
    let early = open_positions(&s, &open, s.clock() - 1.0);
    assert!(early[mid[0] as usize].distance(early[mid[1] as usize]) < gap);
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
    // Triangle by triangle: never more than 4 new in one crossed triangle.
    let b = survey::element_budget(&mesh, s.dyn_mesh());
    assert!(
        b.max <= 4.0,
        "{} new triangles in one crossed triangle: {:?}",
        b.max,
        b.worst
    );
    assert_eq!(b.total_new, r.triangles_created as f64);
    let per = r.triangles_created as f64 / r.triangles_cut as f64;
    assert!(
        per <= 2.0 + 6.0 / r.triangles_cut as f64,
        "{} new per {} crossed",
        r.triangles_created,
        r.triangles_cut
    );
}

fn anatomy_dir() -> Option<std::path::PathBuf> {
    if let Ok(d) = std::env::var("CUTAWAY_ANATOMY") {
        return Some(d.into());
    }
    let d = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy");
    d.exists().then_some(d)
}

#[test]
fn strokes_on_real_anatomy() {
    let Some(dir) = anatomy_dir() else {
        println!("skipped: no anatomy (set CUTAWAY_ANATOMY)");
        return;
    };
    let path = dir.join("knee_vhf_left_denver/VHF_Left_Muscle_Gracilis_smooth.stl");
    let Some(mesh) = read_binary_stl(&path) else {
        println!("skipped: cannot read {}", path.display());
        return;
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

mod fuzz {
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
}

// ---------------------------------------------------------------------------------------------
// Grooves (depth > 0) meeting grooves: notes §5 #21, cross cuts.

/// Points on the great circle of the sphere of radius `r` through `center` (a unit vector) with
/// tangent direction `dir` (made tangent), from arc parameter `from` to `to` (radians).
fn great_arc(center: DVec3, dir: DVec3, r: f64, from: f64, to: f64, n: usize) -> Vec<DVec3> {
    let c = center.normalize();
    let d = (dir - c * dir.dot(c)).normalize();
    (0..=n)
        .map(|i| {
            let s = from + (to - from) * i as f64 / n as f64;
            (c * s.cos() + d * s.sin()) * r
        })
        .collect()
}

/// Cuts grooves on a closed mesh, checking after every step that the surface stays closed,
/// manifold and of the same Euler characteristic and number of components; returns the smallest
/// angle of the triangles created and, per step, whether the blade was cutting after it.
fn groove_strokes(s: &mut Scalpel, strokes: &[Vec<DVec3>]) -> (f64, Vec<bool>) {
    let before = topo(s);
    assert!(before.closed);
    let mut min_angle = 180.0f64;
    let mut on_mesh = Vec::new();
    for stroke in strokes {
        let t0 = s.dyn_mesh().triangle_count();
        let check = |s: &Scalpel, what: &str| {
            let t = topo(s);
            assert!(
                t.closed
                    && t.manifold
                    && t.euler == before.euler
                    && t.components == before.components,
                "{what}: {t:?} (before {before:?})"
            );
        };
        s.begin_stroke(stroke[0]).unwrap();
        check(s, "begin");
        for (i, &q) in stroke[1..].iter().enumerate() {
            let r = s.step(q).unwrap_or_else(|e| panic!("step {i}: {e}"));
            on_mesh.push(r.on_mesh);
            check(s, &format!("step {i}"));
        }
        s.end_stroke().unwrap();
        check(s, "end");
        let m = s.dyn_mesh();
        for t in t0..m.triangle_count() {
            min_angle = min_angle.min(min_angle_deg(m, t as u32));
        }
    }
    (min_angle, on_mesh)
}

fn equator_groove(depth: f64) -> Scalpel {
    let sphere = csg::testkit::icosphere(4, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
    let first = great_arc(DVec3::X, DVec3::Y, 10.0, 0.1, 1.3, 40);
    groove_strokes(&mut s, &[first]);
    s
}

/// Floor vertices (below the surface) of the scalpel's mesh: their smallest radius.
fn deepest_floor_radius(s: &Scalpel) -> f64 {
    let m = s.dyn_mesh();
    (0..m.vertex_count() as u32)
        .filter(|&v| m.is_floor(v))
        .map(|v| m.pos(v).length())
        .fold(f64::INFINITY, f64::min)
}

/// The most coincident copies any surface point has (2 along a slit or groove, 4 where two cuts
/// cross, 3 where one ends on the other's lip and opens into it).
fn max_copies(s: &Scalpel) -> usize {
    let m = s.dyn_mesh();
    (0..m.vertex_count() as u32)
        .filter(|&v| !m.is_floor(v))
        .map(|v| m.copies(v).len() + 1)
        .max()
        .unwrap_or(1)
}

#[test]
fn groove_x_cut_at_90_degrees_crosses_the_trench() {
    let mut s = equator_groove(0.8);
    assert_eq!(max_copies(&s), 2);
    let crossing = DVec3::new(0.7f64.cos(), 0.7f64.sin(), 0.0);
    let second = great_arc(crossing, DVec3::Z, 10.0, -0.3, 0.3, 30);
    let vertices_before = s.dyn_mesh().vertex_count();
    let (min_angle, on_mesh) = groove_strokes(&mut s, &[second]);
    // One continuous cut: the blade never stopped cutting at the first groove.
    assert!(on_mesh.iter().all(|&c| c), "{on_mesh:?}");
    // It went on beyond the first groove: it cut vertices on both sides of it.
    let m = s.dyn_mesh();
    let new: Vec<DVec3> = (vertices_before..m.vertex_count())
        .map(|v| m.pos(v as u32))
        .filter(|p| (p.length() - 10.0).abs() < 1e-6)
        .collect();
    assert!(new.iter().any(|p| p.z > 1.0) && new.iter().any(|p| p.z < -1.0));
    // The crossing point has four copies (each lip of the first groove opened into by the second).
    assert_eq!(max_copies(&s), 4);
    assert!(min_angle >= 1.0, "min angle {min_angle}");
}

#[test]
fn groove_x_cut_at_10_degrees_merges() {
    let mut s = equator_groove(0.8);
    let crossing = DVec3::new(0.7f64.cos(), 0.7f64.sin(), 0.0);
    let a = 10f64.to_radians();
    let tangent = DVec3::new(-0.7f64.sin(), 0.7f64.cos(), 0.0);
    let dir = tangent * a.cos() + DVec3::Z * a.sin();
    let second = great_arc(crossing, dir, 10.0, -0.35, 0.35, 40);
    let (_, on_mesh) = groove_strokes(&mut s, &[second]);
    // The second cut merged into the first groove (it stopped cutting there, at least once) and
    // did not cross it.
    assert!(on_mesh.iter().any(|&c| !c), "{on_mesh:?}");
    assert!(max_copies(&s) < 4);
}

#[test]
fn groove_t_and_i_cuts() {
    // T: a groove from the side ending beyond the first one's lip (merges at the trench).
    let mut s = equator_groove(0.8);
    let crossing = DVec3::new(0.5f64.cos(), 0.5f64.sin(), 0.0);
    groove_strokes(
        &mut s,
        &[great_arc(crossing, DVec3::Z, 10.0, 0.35, 0.0, 20)],
    );
    // I: a second parallel groove, then one joining the two.
    let sphere = csg::testkit::icosphere(4, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(0.8)).unwrap();
    let tilt = |z: f64| DVec3::new(1.0, 0.0, z);
    let a = great_arc(tilt(0.25), DVec3::Y, 10.0, 0.1, 1.2, 40);
    let b = great_arc(tilt(-0.25), DVec3::Y, 10.0, 0.1, 1.2, 40);
    groove_strokes(&mut s, &[a, b]);
    let mid = DVec3::new(0.65f64.cos(), 0.65f64.sin(), 0.0);
    let (_, on_mesh) = groove_strokes(&mut s, &[great_arc(mid, DVec3::Z, 10.0, 0.245, -0.245, 30)]);
    assert!(on_mesh.iter().filter(|&&c| c).count() > 20, "{on_mesh:?}");
}

#[test]
fn groove_deeper_cut_determines_the_crossing() {
    // Shallow first groove, deep second one: the floor at the crossing is the deeper one.
    let mut s = equator_groove(0.4);
    let shallow = deepest_floor_radius(&s);
    assert!(
        (shallow - 9.6).abs() < 0.1,
        "shallow floor at radius {shallow}"
    );
    s.set_options(ScalpelOptions::default().with_depth(1.5));
    let crossing = DVec3::new(0.7f64.cos(), 0.7f64.sin(), 0.0);
    groove_strokes(
        &mut s,
        &[great_arc(crossing, DVec3::Z, 10.0, -0.3, 0.3, 30)],
    );
    let m = s.dyn_mesh();
    // Floor vertices of the first groove near the crossing were lowered to the deep blade.
    let lowered = (0..m.vertex_count() as u32)
        .filter(|&v| m.is_floor(v))
        .filter(|&v| m.pos(v).z.abs() < 0.2 && m.pos(v).length() < 9.0)
        .count();
    assert!(lowered >= 1, "no floor vertex at the crossing was lowered");
}

#[test]
fn groove_self_crossing_stroke() {
    let sphere = csg::testkit::icosphere(4, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(0.6)).unwrap();
    // An α on the sphere around +X: in along -y, loop, cross the own path, out.
    let mut flat = vec![];
    flat.extend(line(p(-4.0, 0.1), p(0.2, 0.1), 0.4));
    for i in 0..=60 {
        let a = -std::f64::consts::FRAC_PI_2 + i as f64 / 60.0 * 1.8 * std::f64::consts::PI;
        flat.push(p(2.2 + 2.0 * a.cos() - 2.0, 2.1 + 2.0 * a.sin()));
    }
    let last = *flat.last().unwrap();
    flat.extend(line(last, p(last.x, -3.5), 0.4));
    let pts: Vec<DVec3> = flat
        .iter()
        .map(|q| DVec3::new(10.0, q.x, q.y).normalize() * 10.0)
        .collect();
    let (_, on_mesh) = groove_strokes(&mut s, &[pts]);
    assert!(on_mesh.iter().all(|&c| c), "{on_mesh:?}");
    assert_eq!(max_copies(&s), 4, "the stroke crosses its own groove");
}

/// Cuts `strokes` (points `(a, b)` mapped to the sphere of radius 10 around +X) as grooves of
/// `depth` on a level-3 icosphere: after every step the mesh is valid, closed, manifold and of
/// Euler characteristic 2, and a failed step changes nothing.
fn grooves_on_small_sphere(strokes: &[Vec<(f64, f64)>], depth: f64) -> Scalpel {
    let sphere = csg::testkit::icosphere(3, 10.0);
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
    for (k, stroke) in strokes.iter().enumerate() {
        let pts: Vec<DVec3> = stroke
            .iter()
            .map(|&(a, b)| DVec3::new(1.0, a, b).normalize() * 10.0)
            .collect();
        s.begin_stroke(pts[0]).unwrap();
        for (i, &q) in pts[1..].iter().enumerate() {
            let before = s.mesh();
            let r = s.step(q);
            if r.is_err() {
                assert_eq!(s.mesh(), before);
            }
            let t = validate(s.dyn_mesh())
                .unwrap_or_else(|e| panic!("stroke {k} step {i} ({r:?}): {e}"));
            assert!(
                t.closed && t.manifold && t.euler == 2,
                "stroke {k} step {i}: {t:?}"
            );
        }
        s.end_stroke().unwrap();
        let t = topo(&s);
        assert!(
            t.closed && t.manifold && t.euler == 2,
            "stroke {k} end: {t:?}"
        );
    }
    s
}

/// Regressions found by `random_grooves_keep_a_sphere_closed`: strokes doubling back over their
/// own groove, then crossing it.
#[test]
fn groove_regressions_from_fuzzing() {
    grooves_on_small_sphere(
        &[
            vec![
                (-0.5769813282570557, 0.0),
                (-0.23578933750163797, 0.0),
                (0.0, 0.4322080635154642),
                (-0.5319501756221426, 0.0),
                (0.0, 0.0),
            ],
            vec![
                (0.0, 0.3931971621007554),
                (-0.49628304209339885, 0.5524357382783197),
            ],
        ],
        0.3,
    );
    grooves_on_small_sphere(
        &[vec![
            (0.0, -0.3359959359542282),
            (-0.452580861144083, 0.5787978272036272),
            (0.392696790286488, -0.35732122902080815),
        ]],
        0.3,
    );
}

// ---------------------------------------------------------------------------------------------
// Blade deeper than the structure: a through-cut (notes §5 #21 last case).

/// A closed slab `[0, n]² × [0, thickness]`: `n × n` unit squares on top and bottom, one row of
/// quads on each side (each quad split on a diagonal), outward.
fn slab(n: u32, thickness: f64) -> Mesh {
    let mut positions: Vec<DVec3> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut id = |p: DVec3| -> u32 {
        *index
            .entry([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .or_insert_with(|| {
                positions.push(p);
                positions.len() as u32 - 1
            })
    };
    let mut triangles = Vec::new();
    // A quad from corner `o` spanned by `u` and `v`, facing `u × v`.
    let mut quad = |o: DVec3, u: DVec3, v: DVec3, id: &mut dyn FnMut(DVec3) -> u32| {
        let (a, b, c, d) = (id(o), id(o + u), id(o + u + v), id(o + v));
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    };
    let n_f = n as f64;
    let z = DVec3::Z * thickness;
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64, j as f64);
            quad(DVec3::new(x, y, thickness), DVec3::X, DVec3::Y, &mut id);
            quad(DVec3::new(x, y, 0.0), DVec3::Y, DVec3::X, &mut id);
        }
    }
    for i in 0..n {
        let s = i as f64;
        quad(DVec3::new(s, 0.0, 0.0), DVec3::X, z, &mut id);
        quad(DVec3::new(s + 1.0, n_f, 0.0), -DVec3::X, z, &mut id);
        quad(DVec3::new(0.0, s + 1.0, 0.0), -DVec3::Y, z, &mut id);
        quad(DVec3::new(n_f, s, 0.0), DVec3::Y, z, &mut id);
    }
    Mesh::new(positions, triangles).unwrap()
}

/// Cuts one stroke and checks after every step that the surface stays closed and manifold;
/// returns the topology before and after.
fn through_stroke(
    mesh: &Mesh,
    depth: f64,
    pts: &[DVec3],
) -> (TopologyReport, TopologyReport, Scalpel) {
    let mut s = Scalpel::new(mesh, ScalpelOptions::default().with_depth(depth)).unwrap();
    let before = topo(&s);
    assert!(before.closed && before.manifold, "{before:?}");
    s.begin_stroke(pts[0]).unwrap();
    for (i, &q) in pts[1..].iter().enumerate() {
        s.step(q)
            .unwrap_or_else(|e| panic!("step {i}: {e} ({})", s.last_refusal()));
        let t = topo(&s);
        assert!(t.closed && t.manifold, "step {i}: {t:?}");
    }
    s.end_stroke().unwrap();
    let after = topo(&s);
    (before, after, s)
}

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

/// The element budget of grooves: new triangles (walls included) per triangle crossed, on a
/// spiral like the benchmark's (turns 3 h apart) on a geodesic sphere: at most 3 on average per
/// triangle the stroke crossed, never more than 4 in one. What "new in one crossed triangle"
/// counts is defined at `survey::element_budget`: its surface pieces minus one, plus the lip
/// walls of the segments cut through it, plus half of each floor triangle at either end of those
/// segments; every new triangle is counted exactly once (checked).
#[test]
fn groove_element_budget_on_a_spiral() {
    let sphere = csg::testkit::geodesic_sphere(40, 50.0);
    let [a, b, _] = sphere.triangles[0].map(|v| sphere.positions[v as usize]);
    let h = a.distance(b);
    for depth in [0.5, 2.0] {
        let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(depth)).unwrap();
        let spacing = 3.0 * h;
        let bb = spacing / std::f64::consts::TAU;
        let mut theta: f64 = 2.0 * std::f64::consts::TAU;
        let mut pts = Vec::new();
        while pts.len() < 200 {
            let r = bb * theta;
            pts.push(DVec3::new(r * theta.cos(), r * theta.sin(), 50.0).normalize() * 50.0);
            theta += h / r.max(h);
        }
        let before = topo(&s);
        let t0 = s.dyn_mesh().triangle_count();
        s.begin_stroke(pts[0]).unwrap();
        for &q in &pts[1..] {
            s.step(q).unwrap();
        }
        let r = s.end_stroke().unwrap();
        let t = topo(&s);
        assert!(t.closed && t.manifold && t.euler == before.euler, "{t:?}");
        let per = (s.dyn_mesh().triangle_count() - t0) as f64 / r.triangles_cut as f64;
        let m = s.dyn_mesh();
        let walls = (0..m.triangle_count() as u32)
            .filter(|&t| m.is_wall(t))
            .count();
        let floors = (0..m.vertex_count() as u32)
            .filter(|&v| m.is_floor(v))
            .count();
        eprintln!(
            "groove depth {depth} (h {h:.2}): {} crossed, {per:.2} new per crossed ({walls} walls, {floors} floor vertices)",
            r.triangles_cut
        );
        assert!(per <= 3.0, "{per} new triangles per crossed triangle");
        let b = survey::element_budget(&sphere, s.dyn_mesh());
        eprintln!(
            "groove depth {depth}: {} cut triangles, mean {:.2}, max {} new ({} over 4; worst: triangle, pieces, walls {:?}); (pieces, 2 walls) histogram {:?}",
            b.crossed, b.mean, b.max, b.over_four, b.worst, b.histogram
        );
        // Every new triangle is counted once.
        assert_eq!(b.total_new, (s.dyn_mesh().triangle_count() - t0) as f64);
        assert!(
            b.max <= 4.0,
            "{} new triangles in one crossed triangle: {:?}",
            b.max,
            b.worst
        );
    }
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

/// Grooves on random strokes (`scalpel::survey`) on three spheres: no step refused (24 strokes
/// crossing one another, per seed), fewer than 1% of the samples out of the tip's reach; and
/// the element budget of single strokes (turning up to 25° per sample): never more than 4 new
/// triangles in one crossed triangle at this depth. (At depth 0.2 a few triangles in a hundred
/// strokes get 5: a sharp turn where no vertex is near forces a floor change between two edge
/// splits; see `Groove::make_bottom`.)
#[test]
fn grooves_on_random_strokes_refuse_nothing_and_keep_the_budget() {
    use cutter::scalpel::survey::{element_budget, random_strokes, survey};
    let meshes = [
        ("icosphere 3", csg::testkit::icosphere(3, 10.0)),
        ("icosphere 4", csg::testkit::icosphere(4, 10.0)),
        ("geodesic 20", csg::testkit::geodesic_sphere(20, 10.0)),
    ];
    let options = ScalpelOptions::default().with_depth(0.5);
    for (name, mesh) in &meshes {
        let (mut steps, mut refused, mut off) = (0, 0, 0);
        for seed in [1, 5] {
            let strokes = random_strokes(mesh, 24, seed);
            let (r, s) = survey(mesh, options, &strokes).unwrap();
            let t = validate(s.dyn_mesh()).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(t.closed && t.manifold, "{name} seed {seed}: {t:?}");
            assert_eq!(r.refused, 0, "{name} seed {seed}: {:?}", r.top_causes());
            (steps, refused, off) = (steps + r.steps, refused + r.refused, off + r.off_mesh);
        }
        let (mut worst, mut mean, mut n) = (0.0f64, 0.0, 0);
        for stroke in random_strokes(mesh, 8, 99) {
            let (_, s) = survey(mesh, options, std::slice::from_ref(&stroke)).unwrap();
            let b = element_budget(mesh, s.dyn_mesh());
            assert_eq!(
                b.total_new,
                (s.dyn_mesh().triangle_count() - mesh.triangles.len()) as f64
            );
            assert!(b.max <= 4.0, "{name}: {} new in one: {:?}", b.max, b.worst);
            (worst, mean, n) = (worst.max(b.max), mean + b.mean, n + 1);
        }
        eprintln!(
            "{name}: {steps} groove steps, {refused} refused, {off} out of reach; single strokes: at most {worst} new per crossed triangle, mean {:.2}",
            mean / n as f64
        );
        assert!(off * 100 <= steps, "{name}: {off} of {steps} out of reach");
    }
}

/// Refused steps on random strokes on a real muscle (slits and grooves); skipped without the
/// anatomy.
#[test]
fn refusal_rate_on_real_anatomy() {
    use cutter::scalpel::survey::{mean_edge, random_strokes, survey};
    let Some(dir) = anatomy_dir() else {
        println!("skipped: no anatomy (set CUTAWAY_ANATOMY)");
        return;
    };
    let path = dir.join("knee_vhf_left_denver/VHF_Left_Muscle_Gracilis_smooth.stl");
    let Some(mesh) = read_binary_stl(&path) else {
        println!("skipped: cannot read {}", path.display());
        return;
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
