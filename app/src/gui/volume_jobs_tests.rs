//! Label volumes in the window never hold a frame: the default scene shows its skin at once and
//! its label surfaces arrive from a background job with progress and Cancel in the status bar;
//! a 256³ volume opened in the window is surfaced off the UI thread with the fraction of its
//! labels done in the progress window, and Cancel leaves the scene as it was.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::{CutawayApp, StartOptions};
use crate::gui::app::Action;

fn state_dir(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("cutaway-volume-jobs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("state dir");
    dir
}

/// A window that is not settled: the test sees the frames while the jobs run.
pub(super) fn window(name: &str, paths: Vec<PathBuf>) -> Harness<'static, CutawayApp> {
    let start = StartOptions {
        paths,
        state_dir: state_dir(name),
        offer_recovery: false,
    };
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        // Building runs frames until the window is idle, at most this many: a few, so the test
        // sees the jobs running.
        .with_max_steps(4)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start))
}

/// Steps frames until `done` holds (at most two minutes); returns the frames stepped.
pub(super) fn step_until(
    h: &mut Harness<'_, CutawayApp>,
    what: &str,
    done: impl Fn(&CutawayApp) -> bool,
) -> usize {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut frames = 0;
    while !done(h.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        h.step();
        frames += 1;
        std::thread::sleep(Duration::from_millis(5));
    }
    frames
}

/// The default scene as the window loads it (the embedded skin at once, the labels from the
/// arrival job), but with a job that surfaces them only once the returned flag is set (or is
/// cancelled), so the test acts while they are on their way however fast the machine surfaces
/// them. The window starts on a file, so no default-scene job of its own races the test.
fn window_with_labels_held(name: &str) -> (Harness<'static, CutawayApp>, Arc<AtomicBool>) {
    let mut h = window(name, vec![skin_file()]);
    step_until(&mut h, "the skin file", |app| !app.busy());
    let open = Arc::new(AtomicBool::new(false));
    let gate = open.clone();
    let ctx = h.ctx.clone();
    let skin = crate::anatomy::default_scene::load_skin().unwrap();
    h.state_mut().add_models(skin, true, &[]);
    h.state_mut().atlas.start_with(&ctx, move |progress| {
        while !gate.load(Ordering::Relaxed) {
            progress.check()?;
            std::thread::sleep(Duration::from_millis(5));
        }
        crate::anatomy::default_scene::load_structures(&|_| !progress.is_cancelled())
    });
    h.run_steps(2);
    assert_eq!(h.state().scene.models.len(), 1, "the skin, alone");
    assert!(h.state().atlas.busy());
    (h, open)
}

/// The embedded atlas's label map in the source tree (256³, 312 labels, its colour table beside).
fn atlas_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/spl_head")
        .join(crate::anatomy::default_scene::ATLAS_FILE)
}

/// A small mesh to start the window with instead of the default scene.
pub(super) fn skin_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/spl_head")
        .join(crate::anatomy::default_scene::SKIN_FILE)
}

#[test]
fn the_default_scene_shows_its_skin_first_and_the_labels_arrive_with_progress() {
    // The window's own start: the skin at once, the labels from the background.
    let mut h = window("default-start", Vec::new());
    assert_eq!(h.state().scene.models[0].model.name, "skin");
    step_until(&mut h, "the default's labels", |app| !app.busy());
    h.run_steps(2);
    assert_eq!(
        h.state().scene.models.len(),
        1 + crate::anatomy::default_scene::selection::default_labels().count()
    );
    // The same with the labels held: the skin alone first, frames keep coming while the labels
    // surface, and the status bar shows their progress.
    let (mut h, open) = window_with_labels_held("default");
    let label = crate::gui::atlas_arrival::AtlasArrival::LABEL;
    let mut frames_with_progress = 0;
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().atlas.busy() {
        if frames_with_progress >= 3 {
            open.store(true, Ordering::Relaxed);
        }
        assert!(Instant::now() < deadline, "the labels did not arrive");
        h.step();
        if h.query_by_label_contains(label).is_some() {
            frames_with_progress += 1;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(2);
    assert!(
        frames_with_progress >= 2,
        "{frames_with_progress} frames showed the progress"
    );
    assert!(
        h.query_by_label_contains(label).is_none(),
        "progress stays after the end"
    );
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(
        app.scene.models[0].model.name, "skin",
        "the skin stays first"
    );
    assert_eq!(
        app.scene.models.len(),
        1 + crate::anatomy::default_scene::selection::default_labels().count(),
        "the skin and the default's structures"
    );
    let hippocampus = app
        .scene
        .models
        .iter()
        .find(|m| m.model.name == "left hippocampus")
        .expect("the left hippocampus arrived");
    assert_eq!(hippocampus.model.group, "limbic system");
    assert!(
        app.status.message.contains("head atlas"),
        "{}",
        app.status.message
    );
}

#[test]
fn an_edit_made_while_the_labels_surface_undoes_without_losing_them() {
    let (mut h, open) = window_with_labels_held("undo");
    // Remove the skin (an undoable scene change) before the labels arrive.
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, Action::RemoveModel(0));
    assert!(h.state().scene.models.is_empty());
    open.store(true, Ordering::Relaxed);
    step_until(&mut h, "the atlas's labels", |app| !app.atlas.busy());
    h.run_steps(2);
    let arrived = h.state().scene.models.len();
    assert_eq!(
        arrived,
        crate::anatomy::default_scene::selection::default_labels().count(),
        "{arrived} models arrived"
    );
    h.state_mut().apply(&ctx, Action::Undo);
    h.run_steps(2);
    let app = h.state();
    assert_eq!(
        app.scene.models[0].model.name, "skin",
        "the undo brought the skin back"
    );
    assert_eq!(
        app.scene.models.len(),
        arrived + 1,
        "the undo kept the labels"
    );
}

#[test]
fn cancelling_the_labels_keeps_the_skin() {
    let (mut h, open) = window_with_labels_held("cancel-default");
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    step_until(&mut h, "the cancel", |app| !app.busy());
    // A late result is never applied: let the worker go on, give it time to end and poll again.
    open.store(true, Ordering::Relaxed);
    std::thread::sleep(Duration::from_millis(200));
    h.run_steps(3);
    let app = h.state();
    assert_eq!(app.scene.models.len(), 1, "only the skin");
    assert!(
        app.status.message.contains("cancelled"),
        "{}",
        app.status.message
    );
}

#[test]
fn the_atlas_with_all_structures_opens_from_the_examples_in_the_background() {
    let mut h = window("all-structures", vec![skin_file()]);
    step_until(&mut h, "the skin", |app| !app.busy());
    let ctx = h.ctx.clone();
    let all = crate::anatomy::default_scene::ALL_NAME;
    h.state_mut()
        .apply(&ctx, Action::OpenExample(all.to_string()));
    // Frames keep coming and the fraction of labels done moves while it surfaces.
    let mut seen = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().busy() {
        assert!(Instant::now() < deadline, "the whole atlas did not open");
        h.step();
        if let Some(f) = h.state().jobs.first().and_then(|j| j.progress.fraction()) {
            seen.push(f);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(2);
    assert!(
        seen.iter().any(|&f| f > 0.0 && f < 1.0),
        "no fraction between 0 and 1 was shown: {seen:?}"
    );
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    let named = crate::anatomy::default_scene::table_values().unwrap();
    // The skin and every label the table names (311: all but the one unnamed voxel of label 1).
    assert_eq!(app.scene.models.len(), 1 + 311);
    assert!(named.len() >= 311);
    assert_eq!(app.scene.models[0].model.name, "skin");
    let gyrus = app
        .scene
        .models
        .iter()
        .find(|m| m.model.name == "left superior frontal gyrus")
        .expect("the cortex is in");
    assert_eq!(gyrus.model.group, "cerebral cortex");
    // Face forward, as the default.
    let camera = app.scene.camera;
    let toward_eye = (camera.eye - camera.target).normalize();
    assert!(
        toward_eye.dot(crate::anatomy::default_scene::FRONT) > 0.9,
        "{camera:?}"
    );
}

#[test]
fn a_volume_opened_in_the_window_surfaces_off_the_ui_thread_with_its_fraction() {
    let mut h = window("open", vec![skin_file()]);
    step_until(&mut h, "the skin", |app| !app.busy());
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, Action::Add(vec![atlas_file()]));
    // Frames keep coming and the fraction of labels done moves while it surfaces.
    let mut seen = Vec::new();
    let mut frames = 0;
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().busy() {
        assert!(Instant::now() < deadline, "the atlas did not open");
        h.step();
        frames += 1;
        if let Some(f) = h.state().jobs.first().and_then(|j| j.progress.fraction()) {
            seen.push(f);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(2);
    assert!(frames >= 2, "opening took {frames} frames");
    assert!(
        seen.iter().any(|&f| f > 0.0 && f < 1.0),
        "no fraction between 0 and 1 was shown: {seen:?}"
    );
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    let names: Vec<&str> = app
        .scene
        .models
        .iter()
        .map(|m| m.model.name.as_str())
        .collect();
    assert_eq!(names.len(), 1 + 312, "the skin and every label");
    // Added to the skin, with the table's names (as the file names them).
    assert_eq!(names[0], "skin");
    for name in ["left_hippocampus", "pons", "tongue"] {
        assert!(names.contains(&name), "{name} is missing");
    }
}

#[test]
fn cancel_leaves_the_scene_as_it_was() {
    let mut h = window("open-cancel", vec![skin_file()]);
    step_until(&mut h, "the skin", |app| !app.busy());
    let before: Vec<_> = h
        .state()
        .scene
        .models
        .iter()
        .map(|m| m.model.mesh.clone())
        .collect();
    let ctx = h.ctx.clone();
    // Cancelled at once (whatever the machine's speed): the late result is dropped.
    h.state_mut().apply(&ctx, Action::Open(vec![atlas_file()]));
    h.state().jobs[0].progress.cancel();
    step_until(&mut h, "the cancel", |app| !app.busy());
    h.run_steps(2);
    assert_eq!(
        h.state().scene.models.len(),
        before.len(),
        "a cancelled open changed the scene"
    );
    // The progress window's Cancel, shown once the job has run half a second.
    h.state_mut().apply(&ctx, Action::Open(vec![atlas_file()]));
    step_until(&mut h, "the progress window", |app| {
        app.jobs.iter().any(|j| j.wants_progress_window()) || !app.busy()
    });
    if h.state().busy() {
        h.run_steps(1);
    }
    // The job may finish in the frame that draws its window: then there is no Cancel to press.
    let cancel_shown = h.state().busy() && h.query_by_label("Cancel").is_some();
    if cancel_shown {
        h.get_by_label("Cancel").click();
        h.run_steps(2);
        step_until(&mut h, "the cancel", |app| !app.busy());
        std::thread::sleep(Duration::from_millis(200));
        h.run_steps(3);
        let app = h.state();
        assert!(
            app.status.message.contains("cancelled"),
            "{}",
            app.status.message
        );
    } else {
        // Surfaced in about half a second: the window never showed (or closed as it came), so
        // no Cancel to press; the atlas replaced the scene as opened.
        step_until(&mut h, "the open", |app| !app.busy());
        println!("the progress window's Cancel was not reached: the atlas opened within 0.5 s");
        return;
    }
    let app = h.state();
    assert_eq!(app.scene.models.len(), before.len(), "the scene changed");
    assert!(
        app.scene
            .models
            .iter()
            .zip(&before)
            .all(|(m, b)| Arc::ptr_eq(&m.model.mesh, b)),
        "a model was replaced"
    );
    assert!(
        app.status.message.contains("cancelled"),
        "{}",
        app.status.message
    );
}
