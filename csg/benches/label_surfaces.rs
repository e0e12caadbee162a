//! Label volume → smoothed surfaces on the SPL head atlas, against VTK in the same run.
//!
//! ```text
//! CUTAWAY_ANATOMY=DIR [CUTAWAY_PEERBENCH=DIR] cargo bench -p csg --bench label_surfaces -- [--json OUT]
//! ```
//! Times "read to last smoothed surface" (gzip NRRD decode + [`label_surfaces`] at the default
//! smoothing), median of 3 runs, then runs the peer script `label_surfaces.py` from
//! `CUTAWAY_PEERBENCH` (VTK's vtkSurfaceNets3D and the classic flying edges + windowed sinc) on
//! the same volume and prints both and the ratios. Without python/vtk the peer is skipped with the
//! reason printed. Also prints the peak resident memory against the goal (volume bytes + twice the
//! output meshes) and the distribution of per-label volume and centroid errors against the voxels.

#[path = "../tests/support/nrrd.rs"]
mod nrrd;

use std::path::{Path, PathBuf};
use std::time::Instant;

use csg::DVec3;
use csg::labels::{LabelGrid, LabelSurface, PhaseTimes, SurfaceOptions, label_surfaces_timed};
use serde_json::{Value, json};

const ATLAS: &str = "volumes/spl_head_atlas/hncma-atlas.nrrd";
const RUNS: usize = 3;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let json_out = args
        .iter()
        .position(|a| a == "--json")
        .and_then(|i| args.get(i + 1))
        .map(PathBuf::from);
    let Some(root) = std::env::var_os("CUTAWAY_ANATOMY") else {
        println!("label_surfaces bench skipped: CUTAWAY_ANATOMY is not set");
        return;
    };
    let path = Path::new(&root).join(ATLAS);

    let mut runs = Vec::new();
    let mut last = None;
    for _ in 0..RUNS {
        // The previous run's volume and surfaces go first, so the peak below is one run's.
        drop(last.take());
        let start = Instant::now();
        let cpu_start = process_cpu_seconds();
        let volume = nrrd::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let read_s = start.elapsed().as_secs_f64();
        let grid = LabelGrid::new(volume.dims, &volume.data, volume.world_from_voxel).unwrap();
        let (surfaces, phases) =
            label_surfaces_timed(&grid, &SurfaceOptions::default(), &|_| true).unwrap();
        let total_s = start.elapsed().as_secs_f64();
        let cpu_s = process_cpu_seconds()
            .zip(cpu_start)
            .map(|(end, start)| end - start);
        runs.push((total_s, read_s, phases, cpu_s));
        last = Some((volume, surfaces));
    }
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (total_s, read_s, phases, cpu_s) = runs[RUNS / 2];
    let (volume, surfaces) = last.expect("at least one run");
    let peak = peak_resident_bytes();
    let triangles: usize = surfaces.iter().map(|s| s.mesh.triangle_count()).sum();
    let volume_bytes = std::mem::size_of_val(volume.data.as_slice());
    let mesh_bytes: usize = surfaces
        .iter()
        .map(|s| {
            std::mem::size_of_val(s.mesh.positions.as_slice())
                + std::mem::size_of_val(s.mesh.triangles.as_slice())
        })
        .sum();
    println!(
        "cutaway  read+surfaces {:8.1} ms (read {:.1} ms), {} labels, {} triangles",
        total_s * 1e3,
        read_s * 1e3,
        surfaces.len(),
        triangles
    );
    if let Some(cpu) = cpu_s {
        println!(
            "cpu      {:.1} ms of CPU time in that run (all threads; less sensitive to the machine's load than wall time)",
            cpu * 1e3
        );
    }
    print_phases(&phases);
    let budget = volume_bytes + 2 * mesh_bytes;
    match peak {
        Some(peak) => println!(
            "memory   peak resident {:.1} MB; volume {:.1} MB + 2 x meshes {:.1} MB = {:.1} MB (peak / that = {:.2})",
            peak as f64 / 1e6,
            volume_bytes as f64 / 1e6,
            mesh_bytes as f64 / 1e6,
            budget as f64 / 1e6,
            peak as f64 / budget as f64
        ),
        None => println!("memory   peak resident size unknown (no /proc/self/status)"),
    }
    let errors = error_summary(&volume, &surfaces);
    println!("errors   {errors}");

    let peer = run_peer(&path);
    let mut report = json!({
        "volume": ATLAS,
        "labels": surfaces.len(),
        "triangles": triangles,
        "threads": rayon::current_num_threads(),
        "read_s": read_s,
        "total_s": total_s,
        "cpu_s": cpu_s,
        "peak_resident_bytes": peak,
        "volume_bytes": volume_bytes,
        "mesh_bytes": mesh_bytes,
        "errors": errors,
        "phases": {
            "scan_s": phases.scan_s,
            "extract_cpu_s": phases.extract_s,
            "smooth_cpu_s": phases.smooth_s,
            "decimate_cpu_s": phases.decimate_s,
            "world_cpu_s": phases.world_s,
        },
    });
    match peer {
        Ok(peer) => {
            let nets = peer["surface_nets"]["s"].as_f64().unwrap_or(f64::NAN);
            let classic = peer["flying_edges_sinc"]["s"].as_f64().unwrap_or(f64::NAN);
            let peer_read = peer["read_s"].as_f64().unwrap_or(f64::NAN);
            println!(
                "vtk      surface_nets {:8.1} ms, flying_edges_sinc {:8.1} ms (read {:.1} ms excluded)",
                nets * 1e3,
                classic * 1e3,
                peer_read * 1e3
            );
            println!(
                "ratio    vtk surface_nets / cutaway = {:.2}, vtk classic / cutaway = {:.2}",
                nets / total_s,
                classic / total_s
            );
            report["peer"] = peer;
            report["ratio_surface_nets"] = json!(nets / total_s);
            report["ratio_classic"] = json!(classic / total_s);
        }
        Err(reason) => {
            println!("vtk      skipped: {reason}");
            report["peer_skipped"] = json!(reason);
        }
    }
    if let Some(out) = json_out {
        std::fs::write(&out, serde_json::to_string_pretty(&report).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", out.display()));
    }
}

/// Prints where the time went: the scan is wall time, the per-label phases CPU time summed over
/// the labels (they run in parallel on every thread).
fn print_phases(p: &PhaseTimes) {
    println!(
        "phases   scan {:.1} ms wall; per label, CPU summed over {} threads: extract {:.1} ms, smooth {:.1} ms, decimate {:.1} ms, world {:.1} ms",
        p.scan_s * 1e3,
        rayon::current_num_threads(),
        p.extract_s * 1e3,
        p.smooth_s * 1e3,
        p.decimate_s * 1e3,
        p.world_s * 1e3
    );
}

/// CPU time used by this process so far (user + system, all threads), where the system reports
/// it (`/proc/self/stat`, in clock ticks of 10 ms).
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which is in parentheses and may hold spaces).
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i)?.parse::<f64>().ok();
    // utime and stime are fields 14 and 15 of the line, 12 and 13 after the name.
    Some((ticks(11)? + ticks(12)?) / 100.0)
}

/// The process's peak resident set size (`VmHWM`), where the system reports it. It includes
/// the binary and the allocator's slack, so it is an upper bound on what the surfaces need.
fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Runs the VTK peer script on `volume`; its JSON, or why not.
fn run_peer(volume: &Path) -> Result<Value, String> {
    let dir = std::env::var_os("CUTAWAY_PEERBENCH").ok_or("CUTAWAY_PEERBENCH is not set")?;
    let script = Path::new(&dir).join("label_surfaces.py");
    let out = std::env::temp_dir().join(format!("label_surfaces_peer_{}.json", std::process::id()));
    let threads = rayon::current_num_threads().to_string();
    let status = std::process::Command::new("python3")
        .arg(&script)
        .arg(volume)
        .args(["--threads", &threads, "--json"])
        .arg(&out)
        .status()
        .map_err(|e| format!("python3: {e}"))?;
    if !status.success() {
        return Err(format!(
            "{} failed ({status}); is vtk installed?",
            script.display()
        ));
    }
    let text = std::fs::read_to_string(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let _ = std::fs::remove_file(&out);
    serde_json::from_str(&text).map_err(|e| format!("peer json: {e}"))
}

/// Per-label relative volume error and centroid offset (in voxel sizes) against the voxels:
/// median, 95th percentile and maximum, over labels of at least 1000 voxels and over all.
fn error_summary(volume: &nrrd::Volume, surfaces: &[LabelSurface]) -> Value {
    let grid = LabelGrid::new(volume.dims, &volume.data, volume.world_from_voxel).unwrap();
    let voxel_volume = grid.voxel_volume();
    let mut sums = vec![(DVec3::ZERO, 0u64); 1 << 16];
    for k in 0..grid.dims[2] {
        for j in 0..grid.dims[1] {
            for i in 0..grid.dims[0] {
                let s = &mut sums[grid.value(i, j, k) as usize];
                s.0 += DVec3::new(i as f64, j as f64, k as f64);
                s.1 += 1;
            }
        }
    }
    let mut rows = Vec::new();
    for s in surfaces {
        let expected = s.voxels as f64 * voxel_volume;
        let volume_error = (s.mesh.volume() - expected) / expected;
        let (sum, n) = sums[s.value as usize];
        let centroid = grid.world_from_voxel.transform_point3(sum / n as f64);
        let offset = (centroid_of(&s.mesh) - centroid).length() / voxel_volume.cbrt();
        rows.push((s.voxels, volume_error, offset));
    }
    let stats = |large: bool| {
        let pick: Vec<&(u64, f64, f64)> = rows.iter().filter(|r| !large || r.0 >= 1000).collect();
        let summary = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            let at = |q: f64| {
                v.get(((v.len() as f64 - 1.0) * q).round() as usize)
                    .copied()
            };
            json!({"median": at(0.5), "p95": at(0.95), "max": v.last()})
        };
        json!({
            "labels": pick.len(),
            "abs_volume_error": summary(pick.iter().map(|r| r.1.abs()).collect()),
            "signed_volume_error_median": summary(pick.iter().map(|r| r.1).collect())["median"],
            "centroid_offset_voxels": summary(pick.iter().map(|r| r.2).collect()),
        })
    };
    json!({"labels_ge_1000_voxels": stats(true), "all_labels": stats(false)})
}

fn centroid_of(mesh: &csg::Mesh) -> DVec3 {
    let origin = mesh.bbox().center();
    let (mut moment, mut volume) = (DVec3::ZERO, 0.0);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t).map(|p| p - origin);
        let v = a.dot(b.cross(c)) / 6.0;
        volume += v;
        moment += (a + b + c) * (v / 4.0);
    }
    origin + moment / volume
}
