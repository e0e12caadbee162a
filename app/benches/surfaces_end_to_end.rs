//! `cutaway surfaces` end to end against VTK doing the same work end to end, from one run:
//! reading the volume, one smoothed closed surface per label, one binary PLY per label written.
//!
//! ```text
//! CUTAWAY_ANATOMY=DIR CUTAWAY_PEERBENCH=DIR cargo bench -p cutaway --bench surfaces_end_to_end -- [VOLUME…] [--repeat 3]
//! ```
//! Without volumes it takes the SPL head atlas (`volumes/spl_head_atlas/hncma-atlas.nrrd`, 256³,
//! 312 labels). For each volume it prints the median over `--repeat` runs of our `surfaces_ms` and
//! process wall time (with CPU time and peak memory of the last run), then runs the peer script
//! `label_surfaces.py VOLUME --end-to-end DIR` (vtkSurfaceNets3D + vtkSurfaceNetsAtlas, and
//! Slicer's per-label flying edges + windowed sinc) and prints its medians and the ratios peer /
//! ours against our process time, which includes starting the process and everything the
//! command reports. Without python3 and vtk the peer is skipped with the reason printed.

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "support/surfaces_run.rs"]
mod surfaces_run;
use surfaces_run::{SurfacesRun, load_average, or_unknown, run_surfaces};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut repeat = 3usize;
    let mut volumes: Vec<PathBuf> = Vec::new();
    let mut k = 0;
    while k < args.len() {
        match args[k].as_str() {
            "--repeat" => {
                repeat = args
                    .get(k + 1)
                    .and_then(|r| r.parse().ok())
                    .expect("--repeat N");
                k += 1;
            }
            "--bench" => {}
            other => volumes.push(PathBuf::from(other)),
        }
        k += 1;
    }
    if volumes.is_empty() {
        let Some(root) = std::env::var_os("CUTAWAY_ANATOMY") else {
            println!(
                "surfaces_end_to_end bench skipped: no volume given and CUTAWAY_ANATOMY is not set"
            );
            return;
        };
        volumes.push(Path::new(&root).join("volumes/spl_head_atlas/hncma-atlas.nrrd"));
    }
    let work = std::env::temp_dir().join(format!("surfaces_end_to_end_{}", std::process::id()));
    for volume in &volumes {
        println!(
            "\n== {} (load average {})",
            volume.display(),
            load_average()
        );
        let runs: Vec<SurfacesRun> = (0..repeat.max(1))
            .map(|_| run_surfaces(volume, &work.join("ours")))
            .collect();
        let surfaces_ms = median(runs.iter().map(|r| r.surfaces_ms));
        let wall_ms = median(runs.iter().map(|r| r.wall_ms));
        let last = runs.last().expect("one run at least");
        println!(
            "cutaway  surfaces_ms {surfaces_ms:8.0} ms, process {wall_ms:8.0} ms ({:.2}× surfaces_ms); {} labels, all closed: {}, {:.2} M triangles; CPU {}, peak {}",
            wall_ms / surfaces_ms,
            last.labels,
            last.all_closed,
            last.triangles as f64 / 1e6,
            or_unknown(last.cpu_s, "s"),
            or_unknown(last.peak_mb, "MB"),
        );
        match peer(volume, &work.join("peer"), repeat) {
            Ok(peer) => {
                for (key, what) in [
                    ("surface_nets_e2e", "vtk surface nets + atlas"),
                    ("flying_edges_sinc_e2e", "vtk flying edges + sinc (Slicer)"),
                ] {
                    match peer[key]["median_s"].as_f64() {
                        Some(s) => println!(
                            "peer     {what:34} {:8.0} ms end to end, {:.2} M triangles; peer / cutaway process = {:.2}, / surfaces_ms = {:.2}",
                            s * 1e3,
                            peer[key]["triangles"].as_f64().unwrap_or(f64::NAN) / 1e6,
                            s * 1e3 / wall_ms,
                            s * 1e3 / surfaces_ms,
                        ),
                        None => println!("peer     {what:34} not run (see the script's output)"),
                    }
                }
            }
            Err(reason) => println!("peer     skipped: {reason}"),
        }
    }
    std::fs::remove_dir_all(&work).ok();
}

fn median(values: impl Iterator<Item = f64>) -> f64 {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs `label_surfaces.py VOLUME --end-to-end DIR` from `CUTAWAY_PEERBENCH`; its JSON, or why not.
fn peer(volume: &Path, dir: &Path, repeat: usize) -> Result<serde_json::Value, String> {
    let bench = std::env::var_os("CUTAWAY_PEERBENCH").ok_or("CUTAWAY_PEERBENCH is not set")?;
    let script = Path::new(&bench).join("label_surfaces.py");
    let json = dir.join("peer.json");
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let python = std::env::var_os("CUTAWAY_PYTHON").unwrap_or_else(|| "python3".into());
    let output = Command::new(&python)
        .arg(&script)
        .arg(volume)
        .args(["--repeat", &repeat.max(1).to_string()])
        .arg("--end-to-end")
        .arg(dir)
        .arg("--json")
        .arg(&json)
        .env("VTK_SMP_BACKEND_IN_USE", "STDThread")
        .output()
        .map_err(|e| format!("{}: {e}", python.to_string_lossy()))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        return Err(format!(
            "{} failed: {}",
            script.display(),
            stderr.lines().last().unwrap_or("")
        ));
    }
    print!("{}", String::from_utf8_lossy(&output.stdout));
    let text = std::fs::read_to_string(&json).map_err(|e| format!("{}: {e}", json.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", json.display()))
}
