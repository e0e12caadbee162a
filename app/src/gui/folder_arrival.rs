//! A folder of masks (a TotalSegmentator output) opened structure by structure: the first
//! structures are drawn while the other files are still read, with the progress and a Cancel in
//! the status bar, and the window works as usual meanwhile (orbit, select, cut what is there).
//!
//! The worker surfaces the masks about in file order ([`crate::scene::open::stream_mask_folder`])
//! and each frame takes what has come, released in file order
//! ([`crate::scene::arrivals::InOrder`]): a structure joins the scene at its final place, so it
//! never moves and a cutter made meanwhile keeps its target. The first structures replace the
//! scene (as opening any file does); later ones are appended to it and to every undo snapshot
//! of it, their arrival no undo step of its own. While the user has not moved the camera, it
//! frames the structures shown so far. Cancel, or an error, stops the worker and restores the
//! scene the user had before; opening anything else drops the arrival.
//!
//! Added to the scene instead (File → Add Model…), the folder is one undo step, recorded when it
//! starts: its structures join the scene after the models already there, that step's after
//! snapshot and every snapshot made since, so that one Undo removes them all. The camera stays
//! where the user put it. Cancel, an error, or an Undo or Redo meanwhile stop the worker and
//! keep what has come (one Undo removes it).

use std::path::PathBuf;
use std::time::Duration;

use crate::gui::jobs::is_cancelled;
use crate::gui::state::AppState;
use crate::gui::state::folder::FolderWork;
use crate::io::Model;
use crate::scene::ViewPreset;
use crate::scene::open::file_label;

/// Starts opening the mask folder `folder` (a folder already arriving is dropped).
pub fn start(app: &mut AppState, ctx: &egui::Context, folder: PathBuf) {
    let label = format!("Opening {}", file_label(&folder));
    let dir = folder.clone();
    app.folder
        .start_with(ctx, folder, label, move |progress, send| {
            crate::scene::open::stream_mask_folder(&dir, progress, &|file, model| {
                send((file, model))
            })
        });
}

/// Starts adding the mask folder `folder` to the scene: one undo step, the structures appended
/// as they come (see the module doc). Into an empty scene the folder is opened instead. Refused
/// while another folder arrives.
pub fn start_adding(app: &mut AppState, ctx: &egui::Context, folder: PathBuf) {
    if app.scene.models.is_empty() && !app.folder.busy() {
        start(app, ctx, folder);
        return;
    }
    let dir = folder.clone();
    add_with(app, ctx, folder, move |progress, send| {
        crate::scene::open::stream_mask_folder(&dir, progress, &|file, model| send((file, model)))
    });
}

/// [`start_adding`] with the worker `work`, which sends each file's outcome.
pub(in crate::gui) fn add_with(
    app: &mut AppState,
    ctx: &egui::Context,
    folder: PathBuf,
    work: impl FolderWork,
) {
    if app.folder.busy() {
        app.complain(&anyhow::anyhow!(
            "{}: {} is still arriving; wait for it, or Cancel it first",
            folder.display(),
            file_label(&app.folder.folder)
        ));
        return;
    }
    let before = app.scene.clone();
    app.record(&format!("add {}", file_label(&folder)), before);
    let step = app.history.last_number();
    let label = format!("Adding {}", file_label(&folder));
    app.folder.start_with(ctx, folder, label, work);
    app.folder.adding = step;
}

/// Stops a folder being added, keeping what has come (on Cancel, and before an Undo or Redo:
/// the snapshots it would add to are about to change). How many structures came; 0 when no
/// folder is being added.
pub fn stop_adding(app: &mut AppState) -> usize {
    if app.folder.adding.is_none() {
        return 0;
    }
    show_what_came(app);
    let added = app.folder.order.released();
    app.folder.cancel();
    added
}

/// Shows what has come, once per frame, and ends the arrival when the worker is done.
pub fn poll(app: &mut AppState) {
    show_what_came(app);
    let Some(job) = app.folder.job.as_mut() else {
        return;
    };
    let Some(result) = job.poll() else {
        return;
    };
    let took = job.started.elapsed();
    match result {
        Ok(count) => {
            // Every outcome was sent before the result.
            show_what_came(app);
            finish(app, count, took);
        }
        Err(e) if is_cancelled(&e) => cancel(app),
        Err(e) => {
            restore(app);
            app.complain(&e);
        }
    }
}

/// Takes the outcomes the worker has sent and shows those whose turn has come.
fn show_what_came(app: &mut AppState) {
    let Some(outcomes) = app.folder.outcomes.as_ref() else {
        return;
    };
    let came: Vec<_> = outcomes.try_iter().collect();
    for (file, model) in came {
        app.folder.order.put(file, model);
    }
    let ready = app.folder.order.ready();
    if !ready.is_empty() {
        show(app, ready);
    }
}

/// Puts `models` (in file order, indices set) into the scene: the first ones replace it, unless
/// the folder is added to the scene.
fn show(app: &mut AppState, models: Vec<Model>) {
    if let Some(step) = app.folder.adding {
        if app.folder.first_shown.is_none() {
            app.folder.first_shown = app.folder.job.as_ref().map(|j| j.started.elapsed());
        }
        app.append_arrived_since(models, step);
        return;
    }
    if !app.folder.replaced {
        app.atlas.cancel();
        let mut fresh = crate::gui::app::new_scene();
        fresh.render = app.scene.render;
        let old = std::mem::replace(&mut app.scene, fresh);
        app.folder.before.get_or_insert_with(|| Box::new(old));
        app.folder.replaced = true;
        app.session_path = None;
        app.selected_model = None;
        app.history.clear();
        app.viewport.reset_editor();
        app.last_committed = app.scene.clone();
        app.folder.first_shown = app.folder.job.as_ref().map(|j| j.started.elapsed());
    }
    app.append_arrived(models);
    match app.folder.framed {
        None => {
            crate::gui::viewport::view_menu::orient_new_scene(app, false, true);
            app.folder.framed = Some(app.scene.camera);
        }
        Some(camera) if camera == app.scene.camera => {
            app.scene.camera = app.scene.preset_camera(ViewPreset::Anterior);
            app.folder.framed = Some(app.scene.camera);
        }
        Some(_) => {}
    }
}

fn finish(app: &mut AppState, count: usize, took: Duration) {
    let first = app.folder.first_shown.unwrap_or(took);
    let folder = file_label(&app.folder.folder);
    let adding = app.folder.adding.is_some();
    app.folder = Default::default();
    app.recovery.mark_dirty();
    if !adding {
        app.recovery.mark_saved();
    }
    let done = if adding { "Added" } else { "Loaded" };
    app.say(format!(
        "{done} {folder}: {count} structures in {:.1} s (the first shown after {:.1} s), {} triangles",
        took.as_secs_f64(),
        first.as_secs_f64(),
        crate::gui::panels::status_bar::grouped(crate::gui::app::triangle_count(&app.scene))
    ));
}

/// Cancel: the arrival stopped, the scene the user had brought back, and said. A folder added
/// to the scene keeps what has come.
fn cancel(app: &mut AppState) {
    let folder = file_label(&app.folder.folder);
    if app.folder.adding.is_some() {
        let added = stop_adding(app);
        app.say(format!(
            "Adding {folder} stopped: {added} structures added (Undo removes them)"
        ));
        return;
    }
    restore(app);
    app.say(format!(
        "Opening {folder} cancelled: the scene is as it was"
    ));
}

/// Stops the arrival and brings back the scene the user had before it (a folder added to the
/// scene keeps what has come).
fn restore(app: &mut AppState) {
    if let Some(before) = app.folder.cancel() {
        app.scene = *before;
        app.last_committed = app.scene.clone();
        app.selected_model = None;
        app.history.clear();
        app.viewport.reset_editor();
    }
}

/// The status bar's line while the folder arrives: what is shown, the fraction of files read,
/// and Cancel.
pub fn status_ui(ui: &mut egui::Ui, app: &mut AppState) {
    let Some(fraction) = app.folder.fraction() else {
        return;
    };
    let doing = if app.folder.adding.is_some() {
        "Adding"
    } else {
        "Opening"
    };
    let text = format!(
        "{doing} {}: {} structures shown…",
        file_label(&app.folder.folder),
        app.folder.order.released()
    );
    if crate::gui::jobs::arrival_line_ui(ui, &text, fraction) {
        cancel(app);
    }
}
