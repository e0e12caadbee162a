//! Mesh-core benchmarks: adjacency, regions, welding, the spatial index and its queries on
//! geodesic spheres of about 1M and 2M triangles (generated here, never committed).
//!
//! Run: `cargo bench -p csg --bench index`.
//! Target (DESIGN.md): adjacency + BVH for 1M triangles in at most 0.5 s on the 2-core machine.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use csg::adjacency::EdgeAdjacency;
use csg::regions::Regions;
use csg::weld::weld_soup;
use csg::{Aabb, DVec3, Mesh, SpatialIndex, testkit};

/// CPU time this thread has run, from `/proc/thread-self/schedstat` (Linux; None elsewhere).
///
/// The development machines are shared by several builds at once, so wall-clock figures swing
/// with the load; the CPU time of the measuring thread is what the code itself costs.
fn thread_cpu_time() -> Option<Duration> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanos = text.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(nanos))
}

/// Median CPU time of `runs` calls of `f`, or None where CPU time is not available.
fn median_cpu_time<T>(runs: usize, mut f: impl FnMut() -> T) -> Option<Duration> {
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let start = thread_cpu_time()?;
        black_box(f());
        times.push(thread_cpu_time()?.saturating_sub(start));
    }
    times.sort_unstable();
    times.get(runs / 2).copied()
}

/// Prints the CPU time (not wall time) of each build step, median of five runs.
fn print_cpu_times(label: &str, mesh: &Mesh, soup: &[DVec3]) {
    let adjacency = EdgeAdjacency::build(mesh);
    let steps: [(&str, Option<Duration>); 5] = [
        (
            "adjacency",
            median_cpu_time(5, || EdgeAdjacency::build(mesh)),
        ),
        (
            "regions",
            median_cpu_time(5, || Regions::build(mesh, &adjacency)),
        ),
        ("weld_soup", median_cpu_time(5, || weld_soup(soup))),
        ("bvh", median_cpu_time(5, || SpatialIndex::build(mesh))),
        (
            "adjacency+bvh",
            median_cpu_time(5, || {
                (EdgeAdjacency::build(mesh), SpatialIndex::build(mesh))
            }),
        ),
    ];
    for (step, time) in steps {
        match time {
            Some(t) => println!("cpu time {step}/{label}: {:.1} ms", t.as_secs_f64() * 1e3),
            None => println!("cpu time {step}/{label}: not available on this system"),
        }
    }
}

/// (label, geodesic frequency): 20·f² triangles.
const SIZES: [(&str, u32); 2] = [("1M", 224), ("2M", 316)];

fn sphere(frequency: u32) -> Mesh {
    let mesh = testkit::geodesic_sphere(frequency, 1.0);
    mesh.sanity_check().expect("generated sphere is valid");
    mesh
}

fn build_benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(8));
    for (label, frequency) in SIZES {
        let mesh = sphere(frequency);
        let soup = testkit::to_soup(&mesh);
        let adjacency = EdgeAdjacency::build(&mesh);
        println!(
            "{label}: {} triangles, {} vertices",
            mesh.triangle_count(),
            mesh.vertex_count()
        );
        print_cpu_times(label, &mesh, &soup);
        group.bench_with_input(BenchmarkId::new("adjacency", label), &mesh, |b, m| {
            b.iter(|| EdgeAdjacency::build(black_box(m)))
        });
        group.bench_with_input(BenchmarkId::new("regions", label), &mesh, |b, m| {
            b.iter(|| Regions::build(black_box(m), &adjacency))
        });
        group.bench_with_input(BenchmarkId::new("weld_soup", label), &soup, |b, s| {
            b.iter(|| weld_soup(black_box(s)))
        });
        group.bench_with_input(BenchmarkId::new("bvh", label), &mesh, |b, m| {
            b.iter(|| SpatialIndex::build(black_box(m)))
        });
        group.bench_with_input(BenchmarkId::new("adjacency+bvh", label), &mesh, |b, m| {
            b.iter(|| (EdgeAdjacency::build(black_box(m)), SpatialIndex::build(m)))
        });
        group.bench_with_input(BenchmarkId::new("report", label), &mesh, |b, m| {
            b.iter(|| black_box(m).report())
        });
    }
    group.finish();
}

fn query_benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("query");
    for (label, frequency) in SIZES {
        let mesh = sphere(frequency);
        let index = SpatialIndex::build(&mesh);
        let mut rng = testkit::SplitMix(7);
        // Rays from outside through a random point near the centre: each hits the sphere.
        let rays: Vec<(DVec3, DVec3)> = (0..4096)
            .map(|_| {
                let origin = rng.in_cube(1.0).normalize_or(DVec3::X) * 3.0;
                let target = rng.in_cube(0.5);
                (origin, target - origin)
            })
            .collect();
        // Query points at a random direction and radius: within ±10% of the radius; just outside
        // the surface (1.001 r, as picking and the scalpel ask); and deep inside (half the
        // radius), where many triangles are almost equally far and the box bounds prune little.
        let mut at_radius = |lo: f64, hi: f64| -> Vec<DVec3> {
            (0..4096)
                .map(|_| {
                    let r = lo + (hi - lo) * rng.next_f64();
                    rng.in_cube(1.0).normalize_or(DVec3::X) * r
                })
                .collect()
        };
        let points = at_radius(0.9, 1.1);
        let deep_points = at_radius(0.5, 0.5);
        let near_points = at_radius(1.001, 1.001);
        let per_query = |name: &str, total: Option<Duration>, n: usize| match total {
            Some(t) => println!(
                "cpu time {name}/{label}: {:.2} µs per query",
                t.as_secs_f64() * 1e6 / n as f64
            ),
            None => println!("cpu time {name}/{label}: not available on this system"),
        };
        let all_rays = || {
            rays.iter()
                .filter_map(|&(o, d)| index.ray_cast(&mesh, o, d, f64::INFINITY))
                .count()
        };
        per_query("ray_cast", median_cpu_time(5, all_rays), rays.len());
        for (name, set) in [
            ("closest_point", &points),
            ("closest_point_deep_inside", &deep_points),
            ("closest_point_near_surface", &near_points),
        ] {
            let all = || {
                set.iter()
                    .filter_map(|&p| index.closest_point(&mesh, p))
                    .count()
            };
            per_query(name, median_cpu_time(5, all), set.len());
        }
        let mut i = 0;
        group.bench_function(BenchmarkId::new("ray_cast", label), |b| {
            b.iter(|| {
                i = (i + 1) % rays.len();
                let (o, d) = rays[i];
                index.ray_cast(&mesh, o, d, f64::INFINITY)
            })
        });
        group.bench_function(BenchmarkId::new("closest_point", label), |b| {
            b.iter(|| {
                i = (i + 1) % points.len();
                index.closest_point(&mesh, points[i])
            })
        });
        group.bench_function(BenchmarkId::new("closest_point_deep_inside", label), |b| {
            b.iter(|| {
                i = (i + 1) % deep_points.len();
                index.closest_point(&mesh, deep_points[i])
            })
        });
        group.bench_function(BenchmarkId::new("closest_point_within_0.01", label), |b| {
            b.iter(|| {
                i = (i + 1) % points.len();
                index.closest_point_within(&mesh, points[i], 0.01)
            })
        });
        let mut out = Vec::new();
        group.bench_function(BenchmarkId::new("faces_in_box_0.02", label), |b| {
            b.iter(|| {
                i = (i + 1) % near_points.len();
                out.clear();
                let p = near_points[i];
                index.faces_in_box(
                    &Aabb {
                        min: p - DVec3::splat(0.01),
                        max: p + DVec3::splat(0.01),
                    },
                    &mut out,
                );
                out.len()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, build_benches, query_benches);
criterion_main!(benches);
