//! csg's own spatial index against `obvhs` (the BVH DESIGN.md names) on a 1,997,120-triangle
//! geodesic sphere: build, cutter-overlap box query, ray pick.
//!
//! Run: `cargo bench -p csg --bench bvh` (release). Besides criterion's figures it prints one
//! line per operation with both wall times (median of several runs, same process, same mesh) and
//! the ratio obvhs / csg (above 1: csg is faster).
//!
//! Both trees are built the way they would serve Cutaway: conservative `f32` boxes rounded
//! outward from the `f64` triangles, one face per leaf for obvhs (its fastest PLOC preset; what
//! csg used before its own tree), its parallel build on. Both box queries return the faces whose
//! boxes overlap the query (the bench checks they find the same number). Both ray picks run the
//! same `f64` triangle test on the candidates: csg's [`SpatialIndex::ray_cast`] (watertight) and
//! obvhs's `ray_traverse` with a Möller–Trumbore test in `f64` (a little cheaper per triangle,
//! so the comparison favours obvhs); the bench checks that both pick the same face. Last, the
//! ray pick the window and the scalpel use, [`PickIndex`] (the obvhs tree with padded boxes and
//! the watertight test), against csg's tree: same face and `t` for every ray.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use csg::{Aabb, DVec3, Mesh, PickIndex, SpatialIndex, testkit};
use glam::Vec3A;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::ray::{Ray, RayHit};

/// Largest `f32` not above `x`.
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x { f.next_down() } else { f }
}

/// Smallest `f32` not below `x`.
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x { f.next_up() } else { f }
}

/// The obvhs tree over `mesh`'s faces (conservative `f32` boxes, one face per leaf).
fn build_obvhs(mesh: &Mesh) -> Bvh2 {
    let boxes: Vec<obvhs::aabb::Aabb> = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            let (min, max) = (a.min(b).min(c), a.max(b).max(c));
            obvhs::aabb::Aabb::new(
                Vec3A::new(round_down(min.x), round_down(min.y), round_down(min.z)),
                Vec3A::new(round_up(max.x), round_up(max.y), round_up(max.z)),
            )
        })
        .collect();
    obvhs::bvh2::builder::build_bvh2(
        &boxes,
        BvhBuildParams::fastest_build(),
        &mut Duration::default(),
    )
}

/// Faces whose leaf box overlaps `query` (obvhs; one face per leaf, so the leaf box is the face's).
fn obvhs_faces_in_box(bvh: &Bvh2, query: &Aabb, out: &mut Vec<u32>) {
    out.clear();
    let q = obvhs::aabb::Aabb::new(
        Vec3A::new(
            round_down(query.min.x),
            round_down(query.min.y),
            round_down(query.min.z),
        ),
        Vec3A::new(
            round_up(query.max.x),
            round_up(query.max.y),
            round_up(query.max.z),
        ),
    );
    bvh.aabb_traverse(q, |bvh, node| {
        let node = &bvh.nodes[node as usize];
        for i in node.first_index..node.first_index + node.prim_count {
            out.push(bvh.primitive_indices[i as usize]);
        }
        true
    });
}

/// Möller–Trumbore in `f64`: `t` of the hit of `o + t d` with triangle `abc`, either side.
fn ray_triangle(o: DVec3, d: DVec3, [a, b, c]: [DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t >= 0.0).then_some(t)
}

/// First face hit by `o + t d` (obvhs traversal, `f64` triangle test).
fn obvhs_ray_cast(bvh: &Bvh2, mesh: &Mesh, o: DVec3, d: DVec3) -> Option<(u32, f64)> {
    let ray = Ray::new_inf(o.as_vec3a(), d.as_vec3a());
    let mut hit = RayHit::none();
    let mut best: Option<(u32, f64)> = None;
    bvh.ray_traverse(ray, &mut hit, |_, i| {
        let face = bvh.primitive_indices[i];
        match ray_triangle(o, d, mesh.corners(face as usize)) {
            Some(t) => {
                if best.is_none_or(|(_, bt)| t < bt) {
                    best = Some((face, t));
                }
                t as f32
            }
            None => f32::INFINITY,
        }
    });
    best
}

/// Median wall time of `runs` calls of `f`.
fn median_time<T>(runs: usize, mut f: impl FnMut() -> T) -> Duration {
    let mut times: Vec<Duration> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed()
        })
        .collect();
    times.sort_unstable();
    times[runs / 2]
}

/// Cutter-sized query boxes (a tenth of the radius) centred on the sphere's surface.
fn query_boxes(count: usize) -> Vec<Aabb> {
    let mut rng = testkit::SplitMix(7);
    (0..count)
        .map(|_| {
            let c = rng.unit_vector();
            Aabb {
                min: c - DVec3::splat(0.05),
                max: c + DVec3::splat(0.05),
            }
        })
        .collect()
}

/// Rays from three radii out, towards random points of the unit sphere.
fn rays(count: usize) -> Vec<(DVec3, DVec3)> {
    let mut rng = testkit::SplitMix(11);
    (0..count)
        .map(|_| {
            let origin = rng.unit_vector() * 3.0;
            let target = rng.unit_vector();
            (origin, (target - origin).normalize())
        })
        .collect()
}

fn print_side_by_side(mesh: &Mesh) {
    let line = |what: &str, ours: Duration, theirs: Duration| {
        println!(
            "bvh {what:<36} csg {:>10.3} µs   obvhs {:>10.3} µs   obvhs/csg {:.2}",
            ours.as_secs_f64() * 1e6,
            theirs.as_secs_f64() * 1e6,
            theirs.as_secs_f64() / ours.as_secs_f64()
        );
    };
    let n = mesh.triangles.len();
    line(
        &format!("build ({n} triangles)"),
        median_time(5, || SpatialIndex::build(mesh)),
        median_time(5, || build_obvhs(mesh)),
    );
    let ours = SpatialIndex::build(mesh);
    let theirs = build_obvhs(mesh);
    let boxes = query_boxes(1000);
    let mut out = Vec::new();
    let (mut found_ours, mut found_theirs) = (0usize, 0usize);
    for b in &boxes {
        ours.faces_in_box(b, &mut out);
        found_ours += out.len();
        out.clear();
        obvhs_faces_in_box(&theirs, b, &mut out);
        found_theirs += out.len();
        out.clear();
    }
    // Both are conservative broad phases over boxes rounded outward to f32 by each tree in its own
    // way, so a face whose box only touches a query box's side may be found by one and not the
    // other; anything more than such a handful means the two do not answer the same query.
    println!("bvh box query candidates: csg {found_ours}, obvhs {found_theirs}");
    assert!(
        found_ours.abs_diff(found_theirs) * 100_000 <= found_ours.max(1),
        "box queries disagree: csg {found_ours}, obvhs {found_theirs}"
    );
    let per_query = |t: Duration| t / boxes.len() as u32;
    line(
        &format!("box query ({} faces each)", found_ours / boxes.len()),
        per_query(median_time(5, || {
            for b in &boxes {
                out.clear();
                ours.faces_in_box(b, &mut out);
            }
        })),
        per_query(median_time(5, || {
            for b in &boxes {
                obvhs_faces_in_box(&theirs, b, &mut out);
            }
        })),
    );
    let rays = rays(1000);
    for &(o, d) in &rays {
        let a = ours.ray_cast(mesh, o, d, f64::INFINITY).map(|h| h.face);
        let b = obvhs_ray_cast(&theirs, mesh, o, d).map(|(f, _)| f);
        assert_eq!(a, b, "ray picks disagree");
    }
    let per_ray = |t: Duration| t / rays.len() as u32;
    line(
        "ray pick",
        per_ray(median_time(5, || {
            for &(o, d) in &rays {
                black_box(ours.ray_cast(mesh, o, d, f64::INFINITY));
            }
        })),
        per_ray(median_time(5, || {
            for &(o, d) in &rays {
                black_box(obvhs_ray_cast(&theirs, mesh, o, d));
            }
        })),
    );
    // What the window and the scalpel use: csg::PickIndex (this obvhs tree with padded boxes and
    // csg's watertight test on the candidates) gives exactly csg's answer.
    line(
        "build PickIndex",
        median_time(5, || SpatialIndex::build(mesh)),
        median_time(5, || PickIndex::build(mesh)),
    );
    let picks = PickIndex::build(mesh);
    for &(o, d) in &rays {
        let a = ours
            .ray_cast(mesh, o, d, f64::INFINITY)
            .map(|h| (h.face, h.t));
        let b = picks
            .ray_cast(mesh, o, d, f64::INFINITY)
            .map(|h| (h.face, h.t));
        assert_eq!(a, b, "PickIndex and SpatialIndex disagree");
    }
    line(
        "ray pick, PickIndex (watertight)",
        per_ray(median_time(5, || {
            for &(o, d) in &rays {
                black_box(ours.ray_cast(mesh, o, d, f64::INFINITY));
            }
        })),
        per_ray(median_time(5, || {
            for &(o, d) in &rays {
                black_box(picks.ray_cast(mesh, o, d, f64::INFINITY));
            }
        })),
    );
}

fn bench(c: &mut Criterion) {
    let mesh = testkit::geodesic_sphere(316, 1.0);
    print_side_by_side(&mesh);
    let ours = SpatialIndex::build(&mesh);
    let theirs = build_obvhs(&mesh);
    let mut group = c.benchmark_group("bvh");
    group.sample_size(10);
    group.bench_function("build csg", |b| b.iter(|| SpatialIndex::build(&mesh)));
    group.bench_function("build obvhs", |b| b.iter(|| build_obvhs(&mesh)));
    let boxes = query_boxes(100);
    let mut out = Vec::new();
    group.bench_function("100 box queries csg", |b| {
        b.iter(|| {
            for q in &boxes {
                out.clear();
                ours.faces_in_box(q, &mut out);
            }
        })
    });
    group.bench_function("100 box queries obvhs", |b| {
        b.iter(|| {
            for q in &boxes {
                obvhs_faces_in_box(&theirs, q, &mut out);
            }
        })
    });
    let rays = rays(100);
    group.bench_function("100 ray picks csg", |b| {
        b.iter(|| {
            for &(o, d) in &rays {
                black_box(ours.ray_cast(&mesh, o, d, f64::INFINITY));
            }
        })
    });
    group.bench_function("100 ray picks obvhs", |b| {
        b.iter(|| {
            for &(o, d) in &rays {
                black_box(obvhs_ray_cast(&theirs, &mesh, o, d));
            }
        })
    });
    let picks = PickIndex::build(&mesh);
    group.bench_function("100 ray picks PickIndex", |b| {
        b.iter(|| {
            for &(o, d) in &rays {
                black_box(picks.ray_cast(&mesh, o, d, f64::INFINITY));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
