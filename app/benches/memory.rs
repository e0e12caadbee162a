//! Peak resident memory of the window on real anatomy, against `cutaway render` of the same
//! session: the scripted session of the `memory` test (10 cutters of 50 drag frames each, every
//! view toggled, everything undone and redone; `tests/support/memory_script.rs`) on the HuBMAP female
//! body and on the SPL brain atlas. Each measurement runs in a fresh child process, so one does
//! not inherit another's memory.
//!
//! Prints per scene: triangles and their data, the resident size after loading with the bound
//! 4× data + 300 MB, the level after the first cut, the highest later level with the 10 % limit,
//! the window's peak, and the peak of `cutaway render` of the session the window saved, with the
//! ratio of the two; then one JSON line per scene.
//!
//! Run: `cargo bench -p cutaway --bench memory` with `CUTAWAY_ANATOMY` set to the anatomy folder
//! (`WGPU_BACKEND=vulkan` on lavapipe).

#[path = "../../tests/support/memory_script.rs"]
mod memory_script;

use std::path::{Path, PathBuf};
use std::process::Command;

use memory_script::{Options, mb};

/// Set in a child process: what it measures ("window" or "render") and its input.
const CHILD: &str = "CUTAWAY_MEMORY_BENCH_CHILD";
const INPUT: &str = "CUTAWAY_MEMORY_BENCH_INPUT";
const SESSION: &str = "CUTAWAY_MEMORY_BENCH_SESSION";

const SCENES: [(&str, &str); 2] = [
    ("HuBMAP female body", "hubmap_vhf_body"),
    ("SPL brain atlas", "head_brain_spl_atlas"),
];

fn main() {
    match std::env::var(CHILD).as_deref() {
        Ok("window") => return window_child(),
        Ok("render") => return render_child(),
        _ => {}
    }
    if let Some(reason) = memory_script::no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let Some(anatomy) = anatomy_dir() else {
        println!("skipped: set CUTAWAY_ANATOMY to the anatomy folder (with SOURCES.md)");
        return;
    };
    let scratch = std::env::temp_dir().join(format!("cutaway-bench-memory-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch folder");
    for (name, folder) in SCENES {
        let session = scratch.join(format!("{folder}.json"));
        let window = child("window", &anatomy.join(folder), &session);
        let render = child("render", &anatomy.join(folder), &session);
        let get = |v: &serde_json::Value, k: &str| v[k].as_u64().unwrap_or(0);
        let data = get(&window, "data_bytes");
        let bound = get(&window, "load_bound");
        let first = get(&window, "first_cut");
        let limit = get(&window, "growth_limit");
        let (peak, render_peak) = (get(&window, "peak"), get(&render, "peak"));
        println!(
            "{name}: {} triangles, {:.1} MB of triangle data",
            get(&window, "triangles"),
            mb(data)
        );
        println!(
            "  window after loading   {:>8.1} MB   bound 4x data + 300 MB {:>8.1} MB  ({:.2} of it)",
            mb(get(&window, "loaded")),
            mb(bound),
            get(&window, "loaded") as f64 / bound as f64
        );
        println!("  after the first cut    {:>8.1} MB", mb(first));
        println!(
            "  highest later level    {:>8.1} MB   limit +10 %             {:>8.1} MB  ({})",
            mb(get(&window, "worst")),
            mb(limit),
            window["worst_step"].as_str().unwrap_or("")
        );
        println!(
            "  every view shown       {:>8.1} MB   highest after          {:>8.1} MB  (limit {:.1} MB)",
            mb(get(&window, "all_shown")),
            mb(get(&window, "worst_after_all_shown")),
            mb(get(&window, "repeat_limit"))
        );
        println!(
            "  window peak            {:>8.1} MB   cutaway render peak    {:>8.1} MB  (ratio {:.2})",
            mb(peak),
            mb(render_peak),
            peak as f64 / render_peak.max(1) as f64
        );
        if let Some(refused) = render["refused"].as_str() {
            println!(
                "  cutaway render refused the saved session (peak up to the refusal): {refused}"
            );
        }
        let line = serde_json::json!({
            "scene": folder,
            "triangles": get(&window, "triangles"),
            "data_bytes": data,
            "loaded_bytes": get(&window, "loaded"),
            "load_bound_bytes": bound,
            "first_cut_bytes": first,
            "highest_later_bytes": get(&window, "worst"),
            "growth_limit_bytes": limit,
            "window_peak_bytes": peak,
            "render_peak_bytes": render_peak,
            "window_over_render": peak as f64 / render_peak.max(1) as f64,
            "render_refused": render["refused"],
            "cutters": get(&window, "cutters"),
            "seconds": window["seconds"],
        });
        println!("{line}");
    }
    let _ = std::fs::remove_dir_all(&scratch);
}

/// Runs this bench again as a child measuring `what`; returns the JSON it printed last.
fn child(what: &str, input: &Path, session: &Path) -> serde_json::Value {
    let exe = std::env::current_exe().expect("bench executable");
    let out = Command::new(exe)
        .env(CHILD, what)
        .env(INPUT, input)
        .env(SESSION, session)
        .output()
        .expect("run the bench child");
    let stderr = String::from_utf8_lossy(&out.stderr);
    eprint!("{stderr}");
    assert!(
        out.status.success(),
        "{what} child failed on {}",
        input.display()
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout
        .lines()
        .rev()
        .find(|l| l.starts_with('{'))
        .unwrap_or("{}");
    serde_json::from_str(last).expect("child JSON")
}

fn window_child() {
    let input = PathBuf::from(std::env::var_os(INPUT).expect("input"));
    let session = PathBuf::from(std::env::var_os(SESSION).expect("session"));
    eprintln!("window on {}:", input.display());
    let mut paths = Vec::new();
    mesh_files(&input, &mut paths);
    paths.sort();
    let report = memory_script::run(Options {
        paths,
        cutters: 10,
        drag_frames: 50,
        save_session: Some(session),
    });
    let line = serde_json::json!({
        "triangles": report.triangles,
        "data_bytes": report.data_bytes,
        "loaded": report.loaded,
        "load_bound": report.load_bound(),
        "growth_limit": report.growth_limit(),
        "growth_guard": report.growth_guard(),
        "all_shown": report.all_shown,
        "worst_after_all_shown": report.worst_after_all_shown.1,
        "repeat_limit": report.repeat_limit(),
        "first_cut": report.first_cut,
        "worst": report.worst.1,
        "worst_step": report.worst.0,
        "peak": report.peak,
        "cutters": report.cutters_made,
        "seconds": report.seconds,
    });
    println!("{line}");
}

/// Every mesh file under `dir`, subfolders included (a folder opens only its own files).
fn mesh_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            mesh_files(&path, out);
        } else if path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
            ["ply", "vtk", "obj", "stl"].contains(&e.to_ascii_lowercase().as_str())
        }) {
            out.push(path);
        }
    }
}

fn render_child() {
    let session = std::env::var_os(SESSION).expect("session");
    let png = PathBuf::from(&session).with_extension("png");
    // A cutter the exact boolean refuses fails `cutaway render` (the contract); the bench then
    // reports the refusal with the peak reached so far instead of stopping the other scenes.
    let refused = cutaway::cli::run([
        "cutaway".into(),
        "render".into(),
        session,
        "--out".into(),
        png.into_os_string(),
    ])
    .err()
    .map(|e| format!("{e:#}"));
    println!(
        "{}",
        serde_json::json!({ "peak": memory_script::peak_rss(), "refused": refused })
    );
}

/// `$CUTAWAY_ANATOMY` (relative to the workspace root or the working directory), else the
/// `shared/anatomy` folder beside the workspace.
fn anatomy_dir() -> Option<PathBuf> {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let candidates = match std::env::var_os("CUTAWAY_ANATOMY") {
        Some(dir) => vec![workspace.join(&dir), PathBuf::from(dir)],
        None => vec![workspace.join("../shared/anatomy")],
    };
    candidates
        .into_iter()
        .find(|c| c.join("SOURCES.md").is_file())
}
