//! The scalpel's steps with the incision opening on (`"open"` in the path file), through
//! `cutaway scalpel --json` as a user runs it: step and opening times per step (median, max).
//!
//! Inputs, generated into a scratch folder (never committed):
//! - a geodesic sphere of 1,997,120 triangles (radius 100), a long groove (240 samples half a
//!   millimetre apart, 1 deep) and a second groove crossing it, opened 2 wide;
//! - the knee: the groove paths of `tests/data/scalpel_lips/` (patella, femur, skin) on
//!   `assets/knee/`, opened as the files say.
//!
//! Each case runs `RUNS` times; the figures printed are the medians over the runs of the
//! per-run `step_us_p50`, `step_us_max`, `open_us_p50`, `open_us_max`, and the largest of the
//! per-run maxima. A step's time on a shared machine varies from run to run by more than the
//! changes measured here, so each case is also replayed `RUNS` times in this process (the same
//! replay the command runs) and each step's least time over those runs is taken: the largest
//! of those and the steps over 4 ms are the step's own cost, without the machine's hiccups.
//! Targets: every step, opening included, at most 4 ms; the opening at most 1 ms for at most
//! 10k moved vertices (notes P4).
//! `CUTAWAY_BIN=/path/to/cutaway` measures another build of the binary with the same inputs.
//! Run: `cargo bench -p cutaway --bench scalpel_open`.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::DVec3;

const RUNS: usize = 3;

fn sphere_path(radius: f64, from: DVec3, to: DVec3, samples: usize) -> Vec<[f64; 3]> {
    (0..=samples)
        .map(|i| {
            let u = i as f64 / samples as f64;
            let wave = 0.02 * (u * std::f64::consts::TAU * 2.0).sin();
            let p = from.lerp(to, u) + DVec3::Z * wave;
            (p.normalize() * radius).to_array()
        })
        .collect()
}

fn inputs(dir: &Path) -> Vec<(String, PathBuf, PathBuf)> {
    std::fs::create_dir_all(dir).expect("scratch folder");
    let sphere = dir.join("sphere_2m.ply");
    if !sphere.exists() {
        let mesh = csg::testkit::geodesic_sphere(316, 100.0);
        cutaway::io::write_mesh(&sphere, &mesh).expect("write the sphere");
    }
    // 1.2 rad of arc at radius 100: 120 mm in 240 samples; the crossing one 80 mm in 160.
    let long = sphere_path(
        100.0,
        DVec3::new(-0.6, -1.0, 0.0),
        DVec3::new(0.6, -1.0, 0.05),
        240,
    );
    let crossing = sphere_path(
        100.0,
        DVec3::new(0.05, -1.0, -0.4),
        DVec3::new(-0.05, -1.0, 0.4),
        160,
    );
    let path = dir.join("sphere_2m_path.json");
    let json = serde_json::json!({"format": "cutaway-path/1", "depth": 1.0, "tool": "scalpel",
        "strokes": [long, crossing], "open": {"width": 2.0, "window": 0.5}});
    std::fs::write(&path, json.to_string()).expect("write the path");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut cases = vec![("sphere 2M, crossing grooves".to_string(), sphere, path)];
    for part in ["patella", "femur", "skin"] {
        cases.push((
            format!("knee {part}"),
            root.join(format!("assets/knee/{part}.ply")),
            root.join(format!("tests/data/scalpel_lips/{part}_path.json")),
        ));
    }
    cases
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[(v.len() - 1) / 2]
}

/// Per step, the least time (microseconds) over `RUNS` in-process replays of `path` on
/// `target`, as `cutaway scalpel` replays them.
fn least_step_times(target: &Path, path: &Path) -> Vec<f64> {
    use cutaway::cli::scalpel::{path_settings, region_scene};
    use cutaway::scalpel_session::{ScalpelSession, replay::replay};
    let path_file = cutaway::io::path_file::read_path_file(path).expect("path file");
    let mesh = cutaway::io::read_mesh(target).expect("target");
    let mut least: Vec<f64> = Vec::new();
    for _ in 0..RUNS {
        let mut scene = region_scene(&mesh, target);
        let mut session = ScalpelSession::headless(path_settings(&path_file));
        let done = replay(&mut session, &mut scene, &path_file.strokes).expect("replay");
        if least.is_empty() {
            least = done.step_us;
        } else {
            for (l, t) in least.iter_mut().zip(done.step_us) {
                *l = l.min(t);
            }
        }
    }
    least
}

fn main() {
    let bin = std::env::var("CUTAWAY_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_cutaway").into());
    let dir = std::env::temp_dir().join("cutaway-bench-scalpel-open");
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("binary {bin}; load average {}", load.trim());
    for (name, target, path) in inputs(&dir) {
        let mut runs: Vec<serde_json::Value> = Vec::new();
        for _ in 0..RUNS {
            let out = Command::new(&bin)
                .args(["scalpel"])
                .arg(&target)
                .arg("--path")
                .arg(&path)
                .arg("--out")
                .arg(dir.join("out.ply"))
                .arg("--json")
                .output()
                .expect("run cutaway");
            assert!(
                out.status.success(),
                "{name}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            runs.push(serde_json::from_slice(&out.stdout).expect("JSON"));
        }
        let field =
            |k: &str| -> Vec<f64> { runs.iter().map(|v| v[k].as_f64().unwrap_or(0.0)).collect() };
        let worst = |k: &str| field(k).into_iter().fold(0.0, f64::max);
        println!(
            "{name}: {} steps; step p50 {:.0} us, max {:.0} us (worst run {:.0}); \
             opening p50 {:.0} us, max {:.0} us (worst run {:.0}); target every step <= 4000 us",
            runs[0]["steps"],
            median(field("step_us_p50")),
            median(field("step_us_max")),
            worst("step_us_max"),
            median(field("open_us_p50")),
            median(field("open_us_max")),
            worst("open_us_max"),
        );
        let least = least_step_times(&target, &path);
        let over = least.iter().filter(|&&t| t > 4000.0).count();
        println!(
            "{name}: each step's least time over {RUNS} replays in this process: max {:.0} us, \
             {over} of {} steps over 4000 us",
            least.iter().copied().fold(0.0, f64::max),
            least.len(),
        );
    }
}
