//! Benchmarks of the local boolean (release build: `cargo bench -p csg --bench boolean`).
//!
//! The boolean's speed figures (DESIGN.md's performance table), on peerbench's files (the same inputs `peers.py` cuts), printed with
//! the ratio to the peers measured in the same run:
//!
//! ```text
//! CUTAWAY_BENCH_TARGET=meshes/sphere_2m.obj \
//! CUTAWAY_BENCH_CUTTER=meshes/cut_sphere_strip.obj \
//! CUTAWAY_PEERS_CMD="python ../shared/peerbench/peers.py" \
//! CUTAWAY_BENCH_ONLY=files cargo bench -p csg --bench boolean
//! ```
//!
//! - `warm`: the cut with the target index cached (the drag-frame cost; the removed piece is a
//!   delta, built on first read: printed separately). Target ≤ 10 ms.
//! - `cold`: index build + the same cut. Target: faster than trueform's total in the same run.
//! - `CUTAWAY_PEERS_CMD` runs `peers.py` (trueform and manifold3d, `--repeat 3`) first, so the
//!   ratios compare figures of one run; `CUTAWAY_PEERS_JSON` reads an earlier `peers.py --json`
//!   file instead (its age is printed). `CUTAWAY_BENCH_PROFILE=N` runs N warm cuts only (for
//!   `perf record`). `CUTAWAY_CUT_PHASES=1` makes every profiled cut print its per-stage wall
//!   times (`CutResult::phases`) to stderr (broad phase, exact pair tests, ids, points, face splits, flood fill beside the
//!   output assembly, ...); e.g. with `CUTAWAY_BENCH_PROFILE=60`, take the minimum and median
//!   of each stage over the runs.
//!
//! Then, unless `CUTAWAY_BENCH_ONLY=files`, synthetic cases (criterion groups too):
//! - a strip on a 2M geodesic sphere (100k with `CUTAWAY_BENCH_QUICK=1`), warm and cold;
//! - `ribbons`: 10 disjoint thin sub-cutters on a 500k-triangle sphere in one call. Target ≤ 30 ms.
//!
//! Every figure comes with wall time (median and minimum), the process's CPU time (all threads)
//! and the load average: on the shared 2-core machine compare figures of one run only.

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use csg::{DVec3, Mesh, TargetIndex};

#[path = "../tests/support/mesh_files.rs"]
mod mesh_files;
use mesh_files::read_obj;

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

/// CPU time of the whole process (all threads: the cut runs parts on rayon's workers) in ms, from
/// `/proc/self/task/*/schedstat`, or NaN where unavailable.
fn process_cpu_ms() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let mut ns = 0.0;
    for task in tasks.flatten() {
        if let Some(t) = std::fs::read_to_string(task.path().join("schedstat"))
            .ok()
            .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        {
            ns += t;
        }
    }
    ns * 1e-6
}

/// Median and minimum of `n` runs of `f`: wall ms and the process's CPU ms (median).
struct Timing {
    wall_median: f64,
    wall_min: f64,
    cpu_median: f64,
    runs: usize,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn timing<R>(n: usize, mut f: impl FnMut() -> R) -> Timing {
    let (mut walls, mut cpus) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for _ in 0..n {
        let (w0, c0) = (Instant::now(), process_cpu_ms());
        black_box(f());
        walls.push(w0.elapsed().as_secs_f64() * 1e3);
        cpus.push(process_cpu_ms() - c0);
    }
    let wall_min = walls.iter().copied().fold(f64::INFINITY, f64::min);
    Timing {
        wall_median: median(&mut walls),
        wall_min,
        cpu_median: median(&mut cpus),
        runs: n,
    }
}

impl std::fmt::Display for Timing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:.2} ms wall median (min {:.2}), {:.2} ms CPU (all threads) median, {} runs, load {}",
            self.wall_median,
            self.wall_min,
            self.cpu_median,
            self.runs,
            load_average()
        )
    }
}

/// The 1-minute load average (`/proc/loadavg`), to judge how noisy a figure is.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "?".into())
}

/// Figures of one peer from a `peers.py --json` file: op A (target − cutter) and its total
/// (conversions included), median ms.
#[derive(Debug)]
struct PeerFigures {
    name: String,
    op_ms: f64,
    total_ms: f64,
}

/// Reads `peers.py --json` output: the peers' A figures, the files they cut, and the load
/// average at the start and end of their run.
fn read_peers(path: &str) -> Result<(Vec<PeerFigures>, String, String, String), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))?;
    let mut out = Vec::new();
    if let Some(peers) = v["peers"].as_object() {
        for (name, p) in peers {
            let a = &p["ops"]["A"];
            if let (Some(op), Some(total)) = (a["op_ms"].as_f64(), a["total_ms"].as_f64()) {
                out.push(PeerFigures {
                    name: name.clone(),
                    op_ms: op,
                    total_ms: total,
                });
            }
        }
    }
    let s = |x: &serde_json::Value| x.as_str().unwrap_or("?").to_owned();
    let load = format!(
        "{} → {}",
        v["calib_start"]["loadavg1"], v["calib_end"]["loadavg1"]
    );
    Ok((out, s(&v["target"]), s(&v["cutter"]), load))
}

/// The peers' figures for the ratio: `CUTAWAY_PEERS_CMD` (e.g. `"python
/// ../shared/peerbench/peers.py"`) is run now on the same files (`--peers trueform,manifold3d --repeat 3
/// --json …`, so the ratio compares figures of one run), or `CUTAWAY_PEERS_JSON` names the
/// `--json` output of an earlier `peers.py` run (its age is printed: compare only within one
/// window on this drifting machine).
fn peers_for(target: &str, cutter: &str) -> Option<Vec<PeerFigures>> {
    let path = if let Ok(cmd) = std::env::var("CUTAWAY_PEERS_CMD") {
        let json = std::env::temp_dir().join(format!("cutaway-peers-{}.json", std::process::id()));
        let peers = std::env::var("CUTAWAY_PEERS").unwrap_or_else(|_| "trueform,manifold3d".into());
        let mut words = cmd.split_whitespace();
        let program = words.next()?;
        println!("running the peers now: {cmd} {target} {cutter} --peers {peers} --repeat 3");
        let status = std::process::Command::new(program)
            .args(words)
            .args([target, cutter, "--peers", &peers, "--repeat", "3", "--json"])
            .arg(&json)
            .status();
        match status {
            Ok(s) if s.success() => {}
            other => {
                println!("peers: {cmd} failed: {other:?}");
                return None;
            }
        }
        json.to_string_lossy().into_owned()
    } else if let Ok(p) = std::env::var("CUTAWAY_PEERS_JSON") {
        p
    } else {
        println!(
            "peers: set CUTAWAY_PEERS_CMD=\"python ../shared/peerbench/peers.py\" to run \
             trueform and manifold3d on the same files in this run (or CUTAWAY_PEERS_JSON to a \
             peers.py --json file) for the ratio"
        );
        return None;
    };
    let age_min = std::fs::metadata(&path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.elapsed().ok())
        .map_or(f64::NAN, |d| d.as_secs_f64() / 60.0);
    match read_peers(&path) {
        Ok((peers, t, c, load)) => {
            let name = |p: &str| {
                std::path::Path::new(p)
                    .file_name()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            };
            if name(&t) != name(target) || name(&c) != name(cutter) {
                println!("peers: {path} cut {t} − {c}, not these files: no ratio");
                return None;
            }
            println!(
                "peers ({path}, written {age_min:.1} min ago, load {load}): {}",
                peers
                    .iter()
                    .map(|p| format!(
                        "{} A op {:.1} ms, total {:.1} ms",
                        p.name, p.op_ms, p.total_ms
                    ))
                    .collect::<Vec<_>>()
                    .join("; ")
            );
            if age_min > 30.0 {
                println!(
                    "peers: WARNING, the peer figures are {age_min:.0} min old: not the same window"
                );
            }
            Some(peers)
        }
        Err(e) => {
            println!("peers: {e}");
            None
        }
    }
}

/// With `CUTAWAY_BENCH_TARGET` and `CUTAWAY_BENCH_CUTTER` (OBJ files, e.g. `meshes/
/// sphere_2m.obj` and `cut_sphere_strip.obj`, the inputs of `peers.py`), times the cut of those
/// files: warm (index cached: the drag-frame cost), the lazy parts materialized (what a consumer
/// that reads the removed mesh or writes the kept mesh pays on top), and cold (index build +
/// cut), and prints the ratio to the peers (see [`peers_for`]).
fn bench_files() {
    let (Ok(t), Ok(c)) = (
        std::env::var("CUTAWAY_BENCH_TARGET"),
        std::env::var("CUTAWAY_BENCH_CUTTER"),
    ) else {
        println!(
            "files: set CUTAWAY_BENCH_TARGET=meshes/sphere_2m.obj \
             CUTAWAY_BENCH_CUTTER=meshes/cut_sphere_strip.obj for the peerbench cut"
        );
        return;
    };
    let (target, cutter) = (read_obj(&t), read_obj(&c));
    let profile: usize = std::env::var("CUTAWAY_BENCH_PROFILE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    if profile > 0 {
        // For `perf record`: only warm cuts.
        let index = TargetIndex::build(target.clone()).expect("index");
        let options = csg::CutOptions::default().with_phase_times(phases_wanted());
        let w = timing(profile, || {
            let r = csg::subtract_with(&index, &[&cutter], &options).expect("cut");
            print_phases(&r);
            r
        });
        println!("profile: {profile} warm cuts: {w}");
        std::process::exit(0);
    }
    let peers = peers_for(&t, &c);
    // Cold: index build + first cut, from the mesh already in memory (reading is not timed).
    let mut copies: Vec<Mesh> = (0..3).map(|_| target.clone()).collect();
    let mut first_cuts = Vec::new();
    let mut build_times = Vec::new();
    let cold = timing(3, || {
        let (index, times) = TargetIndex::build_timed(copies.pop().expect("copy")).expect("index");
        build_times.push(times);
        let t0 = Instant::now();
        let r = csg::subtract(&index, &cutter).expect("cut");
        first_cuts.push(t0.elapsed().as_secs_f64() * 1e3);
        r
    });
    let first_cut = median(&mut first_cuts);
    let index = TargetIndex::build(target.clone()).expect("index");
    let r = csg::subtract(&index, &cutter).expect("cut");
    let warm = timing(30, || csg::subtract(&index, &cutter).expect("cut"));
    let with_removed = timing(10, || {
        let r = csg::subtract(&index, &cutter).expect("cut");
        black_box(r.removed.mesh.triangles.len());
        r
    });
    let kept_ms = timing(3, || r.materialize(&target));
    let kept = r.materialize(&target);
    println!(
        "files {t} − {c}: {} − {} triangles; kept {} (+{} −{}), walls {}, removed {}, contours {}, stats {:?}",
        target.triangles.len(),
        cutter.triangles.len(),
        kept.triangles.len(),
        r.kept_new_faces.len(),
        r.removed_faces.len(),
        r.walls.mesh.triangles.len(),
        r.removed.mesh.triangles.len(),
        r.contours.len(),
        r.stats,
    );
    println!(
        "  vol(kept+walls) {:.6}, vol(removed+walls) {:.6}",
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
    println!("  warm cut (index cached):            {warm}");
    println!("  warm cut + removed mesh built:      {with_removed}");
    println!("  kept mesh materialized (2M copy):   {kept_ms}");
    println!("  cold (index build + cut):           {cold}");
    println!("    of which the first cut after the build: {first_cut:.2} ms wall median");
    // The index build's phases, from the cold run with the median build time.
    build_times.sort_by(|a, b| a.total_ms.total_cmp(&b.total_ms));
    if let Some(times) = build_times.get(build_times.len() / 2) {
        for line in times.to_string().lines() {
            println!("    {line}");
        }
    }
    if let Some(peers) = peers {
        for p in &peers {
            println!(
                "  ratio vs {}: warm {:.0}× its A op ({:.1} ms), {:.0}× its A total ({:.1} ms); cold {:.2}× faster than its total",
                p.name,
                p.op_ms / warm.wall_median,
                p.op_ms,
                p.total_ms / warm.wall_median,
                p.total_ms,
                p.total_ms / cold.wall_median,
            );
        }
    }
}

fn quick() -> bool {
    std::env::var("CUTAWAY_BENCH_QUICK").is_ok()
}

fn bench_boolean(c: &mut Criterion) {
    bench_files();
    if std::env::var("CUTAWAY_BENCH_ONLY").is_ok_and(|s| s == "files") {
        return;
    }
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

    let warm = timing(30, || csg::subtract(&index, &strip).expect("cut"));
    println!("warm cut: {warm}");

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
    let ribbons = timing(30, || csg::subtract_many(&index, &refs).expect("cut"));
    println!(
        "ribbons, 10 sub-cutters on {} triangles: {ribbons}",
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

/// `CUTAWAY_CUT_PHASES` set: the profiled cuts record and print their stage times.
fn phases_wanted() -> bool {
    std::env::var_os("CUTAWAY_CUT_PHASES").is_some()
}

/// Prints a cut's stage times (recorded when asked for) on one line of stderr.
fn print_phases(r: &csg::CutResult) {
    if !r.phases.is_empty() {
        let parts: Vec<String> = r
            .phases
            .iter()
            .map(|(n, ms)| format!("{n} {ms:.3}"))
            .collect();
        eprintln!("cut phases ms: {}", parts.join(" | "));
    }
}
