//! Scalpel step latency (notes/scalpel.md §4 P1–P3, T1; DESIGN.md's scalpel targets).
//!
//! A 1,000-step Archimedean spiral (turn spacing 3h, step 1h, h = mean edge length) around the
//! north pole of geodesic spheres of ~10k, ~130k and ~1M triangles; every step is timed alone,
//! the first one (`begin_stroke`) included.
//! Prints first / p50 / p99 / max per size, the 1M/10k median ratio, new triangles per crossed
//! triangle and the element budget as counted by `survey::element_budget` (T1: surface pieces
//! per crossed triangle, mean and largest; T4: wall triangles per path segment and per lip
//! edge); targets: p50 ≤ 0.5 ms, max ≤ 4 ms at 1M, ratio ≤ 1.5, ≤ 3 pieces per crossed triangle
//! on average and never more than 4 in one, at most 4 wall triangles per segment.
//! Then the refusal rate on random strokes (slits and grooves; a real muscle with
//! `CUTAWAY_ANATOMY` set).
//! Criterion then measures one step at 1M. Run: `cargo bench -p cutter --bench scalpel`.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;

use cutter::scalpel::{Scalpel, ScalpelOptions, survey};

#[allow(dead_code)] // the bench reads STL only
#[path = "../tests/support/mesh_files.rs"]
mod mesh_files;
use mesh_files::read_binary_stl;

const RADIUS: f64 = 50.0;

fn mean_edge(mesh: &csg::Mesh) -> f64 {
    let n = mesh.triangles.len().min(10_000);
    let mut sum = 0.0;
    for t in &mesh.triangles[..n] {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        sum += a.distance(b) + b.distance(c) + c.distance(a);
    }
    sum / (3 * n) as f64
}

/// Spiral samples in units of `h`, mapped onto the sphere around +Z.
fn spiral(h: f64, steps: usize) -> Vec<DVec3> {
    let spacing = 3.0 * h;
    let b = spacing / std::f64::consts::TAU;
    let mut theta: f64 = 2.0 * std::f64::consts::TAU;
    let mut out = Vec::with_capacity(steps + 1);
    while out.len() <= steps {
        let r = b * theta;
        let p = DVec3::new(r * theta.cos(), r * theta.sin(), RADIUS);
        out.push(p.normalize() * RADIUS);
        theta += h / r.max(h);
    }
    out
}

struct Figures {
    triangles: usize,
    times: Vec<Duration>,
    created: usize,
    crossed: usize,
    budget: survey::ElementBudget,
}

fn run_spiral(frequency: u32, depth: f64) -> Figures {
    let mesh = csg::testkit::geodesic_sphere(frequency, RADIUS);
    let h = mean_edge(&mesh);
    let mut s = Scalpel::new(&mesh, ScalpelOptions::default().with_depth(depth)).expect("scalpel");
    s.reserve(200_000);
    let pts = spiral(h, 1000);
    let before = s.dyn_mesh().triangle_count();
    let mut times = Vec::with_capacity(pts.len());
    // The first step (locating the start, closedness, the through-cut ray) is timed like the
    // others: it used to scan the whole mesh.
    let t0 = Instant::now();
    s.begin_stroke(pts[0]).expect("start on the sphere");
    times.push(t0.elapsed());
    for &q in &pts[1..] {
        let t0 = Instant::now();
        s.step(q).expect("step");
        times.push(t0.elapsed());
    }
    let report = s.end_stroke().expect("end");
    Figures {
        triangles: mesh.triangles.len(),
        times,
        created: s.dyn_mesh().triangle_count() - before,
        crossed: report.triangles_cut,
        budget: survey::element_budget(&mesh, s.dyn_mesh()),
    }
}

fn percentile(sorted: &[Duration], p: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i].as_secs_f64() * 1e3
}

fn bench_scalpel(c: &mut Criterion) {
    let mut medians = Vec::new();
    for depth in [0.0, 0.5] {
        for frequency in [23u32, 81, 224] {
            let f = run_spiral(frequency, depth);
            let mut sorted = f.times.clone();
            sorted.sort();
            let p50 = percentile(&sorted, 0.5);
            // Which steps were slowest (a size-independent spike is the machine, not the step).
            let mut slowest: Vec<(usize, f64)> = f
                .times
                .iter()
                .enumerate()
                .map(|(i, t)| (i, t.as_secs_f64() * 1e3))
                .collect();
            slowest.sort_by(|a, b| b.1.total_cmp(&a.1));
            slowest.truncate(3);
            eprintln!("  slowest steps (index, ms): {slowest:.3?}");
            eprintln!(
                "scalpel spiral depth {depth}: {:>9} triangles, {} steps: first {:.4} ms, p50 {:.4} ms, p99 {:.4} ms, max {:.4} ms; {} triangles crossed, {} created ({:.2} new per crossed; T1 surface pieces mean {:.2}, max {}; T4 wall triangles per segment {:.2}, around a floor vertex at most {})",
                f.triangles,
                f.times.len(),
                f.times[0].as_secs_f64() * 1e3,
                p50,
                percentile(&sorted, 0.99),
                percentile(&sorted, 1.0),
                f.crossed,
                f.created,
                f.created as f64 / f.crossed.max(1) as f64,
                f.budget.pieces_mean,
                f.budget.pieces_max,
                f.budget.walls_per_segment_mean,
                f.budget.walls_per_floor_vertex_max,
            );
            medians.push((depth, frequency, p50));
        }
    }
    for depth in [0.0, 0.5] {
        let m = |fr: u32| {
            medians
                .iter()
                .find(|x| x.0 == depth && x.1 == fr)
                .map(|x| x.2)
                .unwrap_or(f64::NAN)
        };
        eprintln!(
            "scalpel depth {depth}: median 1M / 10k = {:.2}",
            m(224) / m(23)
        );
    }

    refusal_figures();

    // Criterion: one step of the 1M slit spiral (the spiral restarts when used up).
    let mesh = csg::testkit::geodesic_sphere(224, RADIUS);
    let h = mean_edge(&mesh);
    let pts = spiral(h, 1000);
    let fresh = || {
        let mut s = Scalpel::new(&mesh, ScalpelOptions::default()).expect("scalpel");
        s.reserve(200_000);
        s.begin_stroke(pts[0]).expect("start");
        s
    };
    let mut s = fresh();
    let mut k = 1;
    c.bench_function("scalpel_step_1M", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                if k >= pts.len() {
                    s = fresh();
                    k = 1;
                }
                let t0 = Instant::now();
                s.step(pts[k]).expect("step");
                total += t0.elapsed();
                k += 1;
            }
            total
        })
    });
}

/// Refused steps on random strokes (`cutter::scalpel::survey`): slits and grooves on spheres of
/// ~10k and ~130k triangles and, with `CUTAWAY_ANATOMY` set, on a real muscle.
fn refusal_figures() {
    let mut meshes = vec![
        (
            "sphere 10k".to_string(),
            csg::testkit::geodesic_sphere(23, RADIUS),
        ),
        (
            "sphere 130k".to_string(),
            csg::testkit::geodesic_sphere(81, RADIUS),
        ),
    ];
    if let Ok(dir) = std::env::var("CUTAWAY_ANATOMY") {
        let path = std::path::Path::new(&dir)
            .join("knee_vhf_left_denver/VHF_Left_Muscle_Gracilis_smooth.stl");
        match read_binary_stl(&path) {
            Some(m) => meshes.push(("gracilis".to_string(), m)),
            None => eprintln!("refusals: cannot read {}", path.display()),
        }
    }
    for (name, mesh) in &meshes {
        let strokes = survey::random_strokes(mesh, 40, 7);
        let h = survey::mean_edge(mesh);
        for depth in [0.0, 2.0 * h] {
            let options = ScalpelOptions::default().with_depth(depth);
            let Ok((r, _)) = survey::survey(mesh, options, &strokes) else {
                continue;
            };
            eprintln!(
                "scalpel refusals {name} depth {depth:.3}: {} strokes, {} steps, {} refused ({:.2}%), {} on-surface samples off the mesh; causes {:?}",
                r.strokes,
                r.steps,
                r.refused,
                100.0 * r.rate(),
                r.off_mesh,
                r.top_causes()
            );
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(Duration::from_secs(3));
    targets = bench_scalpel
}
criterion_main!(benches);
