//! Benchmarks of the local boolean (release build: `cargo bench -p csg --bench boolean`).
//!
//! - `warm`: sphere of 2M triangles (the peerbench `sphere_2m`: geodesic, radius 50) minus a
//!   164-triangle strip hugging it (20 boxes, 8 wide, from 2.5 above to 7.5 below the surface),
//!   with the target index cached: the drag-frame cost. Target ≤ 10 ms.
//! - `cold`: index build + the same cut. Target: faster than trueform in the same run.
//! - `ribbons`: 10 disjoint thin sub-cutters on a 500k-triangle sphere in one call. Target ≤ 30 ms.
//!
//! Set `CUTAWAY_BENCH_QUICK=1` for 100k/500k targets instead of 2M (faster to iterate).

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use csg::{DVec3, Mesh, TargetIndex};

/// A closed strip of `boxes` quad boxes swept along a great-circle arc of the sphere of radius
/// `r` (from angle `a0` to `a1` in the plane spanned by `u` and `v`), `width` wide, radially from
/// `below` under the surface to `above` over it.
fn sphere_strip(
    r: f64,
    u: DVec3,
    v: DVec3,
    a0: f64,
    a1: f64,
    boxes: usize,
    width: f64,
    above: f64,
    below: f64,
) -> Mesh {
    let n = u.cross(v).normalize();
    let mut positions = Vec::new();
    for i in 0..=boxes {
        let a = a0 + (a1 - a0) * i as f64 / boxes as f64;
        let dir = u * a.cos() + v * a.sin();
        let (inner, outer) = (dir * (r - below), dir * (r + above));
        let side = n * (width * 0.5);
        positions.extend([inner - side, inner + side, outer + side, outer - side]);
    }
    let mut triangles = Vec::new();
    let quad = |t: &mut Vec<[u32; 3]>, q: [u32; 4]| {
        t.push([q[0], q[1], q[2]]);
        t.push([q[0], q[2], q[3]]);
    };
    for i in 0..boxes as u32 {
        let (a, b) = (4 * i, 4 * (i + 1));
        for k in 0..4 {
            let k1 = (k + 1) % 4;
            quad(&mut triangles, [a + k, a + k1, b + k1, b + k]);
        }
    }
    let last = 4 * boxes as u32;
    quad(&mut triangles, [0, 3, 2, 1]);
    quad(&mut triangles, [last, last + 1, last + 2, last + 3]);
    let mut m = Mesh {
        positions,
        triangles,
    };
    if m.volume() < 0.0 {
        m = m.reversed();
    }
    m
}

/// CPU time of this thread in ms (`/proc/thread-self/schedstat`), or NaN where unavailable. On
/// a loaded machine wall time overstates the cost; CPU time does not.
fn thread_cpu_ms() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-6)
}

/// Mean wall and CPU ms of `f` over `n` runs.
fn timed<R>(n: usize, mut f: impl FnMut() -> R) -> (f64, f64) {
    let (w0, c0) = (Instant::now(), thread_cpu_ms());
    for _ in 0..n {
        black_box(f());
    }
    (
        w0.elapsed().as_secs_f64() * 1e3 / n as f64,
        (thread_cpu_ms() - c0) / n as f64,
    )
}

/// Minimal OBJ reader for the peerbench files (`v` and `f` records, polygons fanned); the bench
/// cannot use the app's readers (csg sees no file formats), and these files are plain.
fn read_obj(path: &str) -> Mesh {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut m = Mesh::default();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it.take(3).map(|x| x.parse().expect("coordinate")).collect();
                m.positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let idx: Vec<u32> = it
                    .map(|x| {
                        x.split('/')
                            .next()
                            .unwrap_or("")
                            .parse::<u32>()
                            .expect("index")
                            - 1
                    })
                    .collect();
                for k in 1..idx.len() - 1 {
                    m.triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    m
}

/// With `CUTAWAY_BENCH_TARGET` and `CUTAWAY_BENCH_CUTTER` (OBJ files, e.g. peerbench's
/// `meshes/sphere_2m.obj` and `meshes/cut_sphere_strip_quads.obj`), times the cut of those files:
/// the same inputs as `peers.py`, for the side-by-side ratio.
fn bench_files() {
    let (Ok(t), Ok(c)) = (
        std::env::var("CUTAWAY_BENCH_TARGET"),
        std::env::var("CUTAWAY_BENCH_CUTTER"),
    ) else {
        return;
    };
    let (target, cutter) = (read_obj(&t), read_obj(&c));
    let (wall_b, cpu_b) = timed(1, || TargetIndex::build(target.clone()).expect("index"));
    let index = TargetIndex::build(target.clone()).expect("index");
    let r = csg::subtract(&index, &cutter).expect("cut");
    let (wall, cpu) = timed(20, || csg::subtract(&index, &cutter).expect("cut"));
    let kept = r.materialize(&target);
    println!(
        "files {t} − {c}: {} − {} triangles; index build {wall_b:.1} ms wall ({cpu_b:.1} ms CPU on this thread); \
         warm cut {wall:.2} ms wall, {cpu:.2} ms CPU (mean of 20); kept {} walls {} removed {} contours {}; \
         vol(kept+walls) {:.6} vol(removed+walls) {:.6}",
        target.triangles.len(),
        cutter.triangles.len(),
        kept.triangles.len(),
        r.walls.mesh.triangles.len(),
        r.removed.mesh.triangles.len(),
        r.contours.len(),
        {
            let mut m = kept.clone();
            m.append(&r.walls.mesh);
            m.volume()
        },
        {
            let mut m = r.removed.mesh.clone();
            m.append(&r.walls.mesh.reversed());
            m.volume()
        },
    );
}

fn quick() -> bool {
    std::env::var("CUTAWAY_BENCH_QUICK").is_ok()
}

fn bench_boolean(c: &mut Criterion) {
    bench_files();
    let frequency = if quick() { 71 } else { 316 };
    let target = csg::testkit::geodesic_sphere(frequency, 50.0);
    let strip = sphere_strip(
        50.0,
        DVec3::X,
        DVec3::new(0.0, 0.6, 0.8),
        -0.5,
        0.5,
        20,
        8.0,
        2.5,
        7.5,
    );
    let t0 = Instant::now();
    let index = TargetIndex::build(target.clone()).expect("index");
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;
    let t0 = Instant::now();
    let r = csg::subtract(&index, &strip).expect("cut");
    let first_ms = t0.elapsed().as_secs_f64() * 1e3;
    println!(
        "target {} triangles, strip {} triangles: index build {build_ms:.1} ms, first cut {first_ms:.2} ms, \
         kept +{} −{}, walls {}, removed {}, contours {}, stats {:?}",
        target.triangles.len(),
        strip.triangles.len(),
        r.kept_new_faces.len(),
        r.removed_faces.len(),
        r.walls.mesh.triangles.len(),
        r.removed.mesh.triangles.len(),
        r.contours.len(),
        r.stats
    );

    let (wall, cpu) = timed(30, || csg::subtract(&index, &strip).expect("cut"));
    println!("warm cut: {wall:.2} ms wall, {cpu:.2} ms CPU (mean of 30)");

    let mut group = c.benchmark_group("boolean");
    group.sample_size(20);
    group.bench_function(
        format!("warm sphere {}k − strip", target.triangles.len() / 1000),
        |b| b.iter(|| csg::subtract(black_box(&index), black_box(&strip)).expect("cut")),
    );
    group.sample_size(10);
    group.bench_function(
        format!("cold sphere {}k − strip", target.triangles.len() / 1000),
        |b| {
            b.iter(|| {
                let index = TargetIndex::build(black_box(target.clone())).expect("index");
                csg::subtract(&index, black_box(&strip)).expect("cut")
            })
        },
    );

    // Ribbons: 10 thin disjoint sub-cutters across the strip's path on a 500k sphere.
    let frequency = if quick() { 71 } else { 158 };
    let target = csg::testkit::geodesic_sphere(frequency, 50.0);
    let index = TargetIndex::build(target.clone()).expect("index");
    let ribbons: Vec<Mesh> = (0..10)
        .map(|k| {
            let a = -0.5 + 0.1 * k as f64;
            sphere_strip(
                50.0,
                DVec3::X,
                DVec3::new(0.0, 0.6, 0.8),
                a,
                a + 0.02,
                1,
                8.0,
                2.5,
                7.5,
            )
        })
        .collect();
    let refs: Vec<&Mesh> = ribbons.iter().collect();
    let (wall, cpu) = timed(30, || csg::subtract_many(&index, &refs).expect("cut"));
    println!(
        "ribbons, 10 sub-cutters on {} triangles: {wall:.2} ms wall, {cpu:.2} ms CPU (mean of 30)",
        target.triangles.len()
    );
    group.sample_size(20);
    group.bench_function(
        format!(
            "ribbons 10 sub-cutters on sphere {}k",
            target.triangles.len() / 1000
        ),
        |b| b.iter(|| csg::subtract_many(black_box(&index), black_box(&refs)).expect("cut")),
    );
    group.finish();
}

criterion_group!(benches, bench_boolean);
criterion_main!(benches);
