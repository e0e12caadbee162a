//! First open of the default scene: from creating the window (headless, egui_kittest with the
//! real wgpu renderer) to the first frame drawn with the scene in it (`start_to_first_frame_ms`,
//! what a user waits for: the skin, while the atlas's label surfaces arrive in the background)
//! and to the frame with every label surface (`start_to_all_labels_ms`), the same from File →
//! Open Example (`open_to_…`), for the default (the embedded head atlas) and, as the peer
//! measured in the same run, the synthetic knee phantom that was the default before, with the
//! ratio of the two, and with `CUTAWAY_ANATOMY` set the HuBMAP female body opened from its folder.
//! With `CUTAWAY_MASK_FOLDER=DIR` (a folder of masks as TotalSegmentator writes it, e.g. the
//! `label_folders` bench's inputs kept with `--keep`) it also opens that folder: milliseconds to
//! the first structure drawn, to every structure drawn, and the process's peak resident memory
//! during the opens (reset before them).
//! Best of five runs each.
//!
//! Run: `WGPU_BACKEND=vulkan cargo bench -p cutaway --bench first_open` (release; on a machine
//! without a GPU, Mesa's lavapipe draws). Goal: the default scene's first frame within 1.5 s on
//! two cores.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cutaway::gui::app::Action;
use cutaway::gui::{CutawayApp, StartOptions};
use egui_kittest::Harness;

/// One open: milliseconds to the first frame that shows the scene (for the default scene: its
/// skin, the label surfaces still arriving), milliseconds until every background job is done
/// and drawn (the default scene's labels included), and the scene's triangle count then.
struct Opened {
    first_frame_ms: f64,
    complete_ms: f64,
    triangles: usize,
}

/// Opens the window. `example`: `None` for the default scene, else an example's name or an
/// absolute path of files to open, loaded right after start (its times measured from the click).
fn first_frame_ms(example: Option<&str>) -> Opened {
    let state_dir = std::env::temp_dir().join(format!(
        "cutaway-bench-first-open-{}-{}",
        std::process::id(),
        example.unwrap_or("default")
    ));
    std::fs::create_dir_all(&state_dir).expect("state folder");
    let start = StartOptions {
        paths: Vec::new(),
        state_dir: state_dir.clone(),
        offer_recovery: false,
    };
    let started = Instant::now();
    let mut h = Harness::builder()
        .wgpu()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_max_steps(100_000)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start));
    let mut clock = started;
    if let Some(name) = example {
        settle(&mut h);
        clock = Instant::now();
        let ctx = h.ctx.clone();
        let action = if Path::new(name).is_absolute() {
            Action::Open(vec![PathBuf::from(name)])
        } else {
            Action::OpenExample(name.to_string())
        };
        h.state_mut().apply(&ctx, action);
    }
    // The first frame with models in the scene (the default scene's skin before its labels).
    let deadline = Instant::now() + Duration::from_secs(120);
    h.step();
    while h.state().scene.models.is_empty() {
        assert!(Instant::now() < deadline, "loading took over 120 s");
        h.step();
        std::thread::sleep(Duration::from_millis(1));
    }
    h.render().expect("render the first frame");
    let first_frame_ms = clock.elapsed().as_secs_f64() * 1000.0;
    settle(&mut h);
    h.render().expect("render the complete scene");
    let complete_ms = clock.elapsed().as_secs_f64() * 1000.0;
    let triangles = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| m.model.mesh.triangle_count())
        .sum();
    std::fs::remove_dir_all(&state_dir).ok();
    Opened {
        first_frame_ms,
        complete_ms,
        triangles,
    }
}

fn settle(h: &mut Harness<'_, CutawayApp>) {
    let deadline = Instant::now() + Duration::from_secs(120);
    h.step();
    while h.state().busy() {
        assert!(Instant::now() < deadline, "loading took over 120 s");
        h.step();
        std::thread::sleep(Duration::from_millis(1));
    }
    h.step();
}

fn main() {
    // `cargo bench` passes `--bench`; a plain `cargo test --benches` run passes nothing and
    // only checks that the bench runs once.
    let runs = if std::env::args().any(|a| a == "--bench") {
        5
    } else {
        1
    };
    let best = |example: Option<&str>| {
        let runs: Vec<Opened> = (0..runs).map(|_| first_frame_ms(example)).collect();
        let min = |f: fn(&Opened) -> f64| runs.iter().map(f).fold(f64::INFINITY, f64::min);
        Opened {
            first_frame_ms: min(|o| o.first_frame_ms),
            complete_ms: min(|o| o.complete_ms),
            triangles: runs.last().map_or(0, |o| o.triangles),
        }
    };
    let cold = best(None);
    let atlas = best(Some(cutaway::anatomy::default_scene::NAME));
    let knee = best(Some("knee"));
    println!(
        "{{\"scene\":\"head atlas (default)\",\"start_to_first_frame_ms\":{:.1},\"start_to_all_labels_ms\":{:.1},\"open_to_first_frame_ms\":{:.1},\"open_to_all_labels_ms\":{:.1},\"triangles\":{},\"goal_ms\":1500,\"runs\":{runs}}}",
        cold.first_frame_ms,
        cold.complete_ms,
        atlas.first_frame_ms,
        atlas.complete_ms,
        cold.triangles
    );
    println!(
        "{{\"scene\":\"knee phantom (previous default)\",\"open_to_first_frame_ms\":{:.1},\"triangles\":{},\"runs\":{runs}}}",
        knee.complete_ms, knee.triangles
    );
    println!(
        "{{\"atlas_over_knee\":{:.2}}}",
        atlas.first_frame_ms / knee.complete_ms
    );
    if let Some(folder) = std::env::var_os("CUTAWAY_MASK_FOLDER").map(PathBuf::from) {
        let folder = std::path::absolute(&folder).expect("absolute path");
        let files = std::fs::read_dir(&folder).map_or(0, |d| d.count());
        // Peak resident memory from here on (Linux: writing 5 to clear_refs resets VmHWM).
        std::fs::write("/proc/self/clear_refs", "5").ok();
        let opened = best(Some(folder.to_str().expect("UTF-8 path")));
        println!(
            "{{\"scene\":\"mask folder ({files} files)\",\"open_to_first_structure_ms\":{:.1},\"open_to_all_ms\":{:.1},\"triangles\":{},\"peak_mb\":{},\"runs\":{runs}}}",
            opened.first_frame_ms,
            opened.complete_ms,
            opened.triangles,
            peak_mb().map_or("null".to_string(), |mb| format!("{mb:.0}"))
        );
    }
    // The HuBMAP female body (metres, Y up: opens upright), when the anatomy folder is there.
    let body = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("../shared/anatomy"))
        .join("hubmap_vhf_body");
    let body = body.is_dir().then_some(body);
    match body {
        Some(body) => {
            let body = std::path::absolute(&body).expect("absolute path");
            let body = best(Some(body.to_str().expect("UTF-8 path")));
            println!(
                "{{\"scene\":\"HuBMAP female body\",\"open_to_first_frame_ms\":{:.1},\"triangles\":{},\"runs\":{runs},\"over_atlas\":{:.2}}}",
                body.complete_ms,
                body.triangles,
                body.complete_ms / atlas.complete_ms
            );
        }
        None => println!("HuBMAP body skipped: set CUTAWAY_ANATOMY to the anatomy folder"),
    }
}

/// This process's peak resident memory (`VmHWM`), in MB.
fn peak_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}
