//! Scalpel scenario corpus (notes/scalpel.md §5): each scenario cuts a test mesh and compares
//! the change in components (C), boundary loops (b) and Euler characteristic (χ) with the table;
//! every step is followed by the full validator, an area check (splitting conserves area) and a
//! sliver check on the triangles the step created.

#[allow(dead_code)] // not every reader is used by every includer
#[path = "../support/mesh_files.rs"]
mod mesh_files;

use csg::{DVec3, Mesh};
use cutter::scalpel::invariants::{min_angle_deg, t_junction_near, validate};
use cutter::scalpel::{Scalpel, ScalpelOptions, Tool, TopologyReport, survey};
use mesh_files::read_binary_stl;

mod anatomy;
mod ends;
mod fidelity;
mod fuzz;
mod grooves;
mod lips;
mod live_opening;
mod opened_lips;
mod opening;
mod slits;
mod strips;
mod through;
mod tips;
mod unfold;
mod walls;

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

fn anatomy_dir() -> Option<std::path::PathBuf> {
    if let Ok(d) = std::env::var("CUTAWAY_ANATOMY") {
        return Some(d.into());
    }
    let d = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy");
    d.exists().then_some(d)
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
/// A wavy arc of `samples + 1` points across the front (-y) of a sphere of radius `r` about the
/// origin: 1.2 rad of longitude with a latitude wave of 0.12 rad, one period.
fn wavy_arc(r: f64, samples: usize) -> Vec<DVec3> {
    (0..=samples)
        .map(|i| {
            let u = i as f64 / samples as f64;
            let lon = -0.6 + 1.2 * u;
            let lat = 0.12 * (u * std::f64::consts::TAU).sin();
            DVec3::new(lat.cos() * lon.sin(), -lat.cos() * lon.cos(), lat.sin()) * r
        })
        .collect()
}

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
