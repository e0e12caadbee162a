//! One run of the `cutaway` binary's `surfaces` command, as a user starts it, with the figures the
//! label benches print: the command's own `surfaces_ms`, the process's wall time and, where
//! `/usr/bin/time` exists, its CPU time and peak resident memory.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// What one `cutaway surfaces INPUT --out OUT --format ply --json` run measured.
pub struct SurfacesRun {
    pub labels: usize,
    pub triangles: u64,
    /// Every surface reported closed.
    pub all_closed: bool,
    /// The command's clock: reading the file to the last file written.
    pub surfaces_ms: f64,
    /// The process, start to exit.
    pub wall_ms: f64,
    /// User + system seconds, if measured.
    pub cpu_s: Option<f64>,
    /// Peak resident memory in MB, if measured.
    pub peak_mb: Option<f64>,
}

/// Runs `cutaway surfaces` on `input` into `out` (emptied first and removed after).
pub fn run_surfaces(input: &Path, out: &Path) -> SurfacesRun {
    std::fs::remove_dir_all(out).ok();
    let bin = env!("CARGO_BIN_EXE_cutaway");
    let time = Path::new("/usr/bin/time");
    let timing = std::env::temp_dir().join(format!("surfaces_run_time_{}", std::process::id()));
    let mut command = if time.exists() {
        let mut c = Command::new(time);
        c.args(["-f", "%e %U %S %M", "-o"]).arg(&timing).arg(bin);
        c
    } else {
        Command::new(bin)
    };
    let start = Instant::now();
    let output = command
        .arg("surfaces")
        .arg(input)
        .arg("--out")
        .arg(out)
        .args(["--format", "ply", "--json"])
        .output()
        .unwrap();
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    assert!(
        output.status.success(),
        "cutaway surfaces {}: {}",
        input.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let surfaces = report["surfaces"].as_array().unwrap();
    let timed: Option<Vec<f64>> = std::fs::read_to_string(&timing).ok().map(|t| {
        t.split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect()
    });
    std::fs::remove_file(&timing).ok();
    let timed = timed.filter(|f| f.len() == 4);
    std::fs::remove_dir_all(out).ok();
    SurfacesRun {
        labels: surfaces.len(),
        triangles: surfaces
            .iter()
            .map(|s| s["triangles"].as_u64().unwrap())
            .sum(),
        all_closed: surfaces.iter().all(|s| s["closed"].as_bool() == Some(true)),
        surfaces_ms: report["surfaces_ms"].as_f64().unwrap(),
        wall_ms,
        cpu_s: timed.as_ref().map(|f| f[1] + f[2]),
        peak_mb: timed.as_ref().map(|f| f[3] / 1024.0),
    }
}

/// `12.3 s` / `456 MB`, or `?` where not measured.
pub fn or_unknown(value: Option<f64>, unit: &str) -> String {
    value.map_or_else(|| "?".into(), |v| format!("{v:.1} {unit}"))
}

/// The 1-minute load average, printed beside figures taken on a shared machine.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "?".into())
}
