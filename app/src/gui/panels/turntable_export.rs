//! File → Export Turntable…: the dialog (frames, frame size, GIF) and the background job that
//! writes the orbit with [`crate::export::turntable`], the same code as
//! `cutaway render --turntable`. The job's progress bar counts frames and its Cancel stops the
//! export before the next frame without committing the output set, so nothing is written.

use std::path::Path;

use crate::export::turntable::{MAX_FRAMES, TurntableProgress, export_turntable};
use crate::gui::action::{Action, Purpose};
use crate::gui::jobs::Progress;
use crate::gui::panels::export_dialog::{ExportDialog, size_rows};
use crate::gui::state::AppState;
use crate::render::ViewMode;
use crate::scene::Scene;
use crate::view::RenderPngOptions;

pub use crate::gui::state::export_settings::{MAX_TURNTABLE_SIDE, TurntableSettings};

/// The job's progress bar counts frames; its Cancel stops the export.
impl TurntableProgress for Progress {
    fn frame_done(&self, done: u32, total: u32) {
        self.set(done as u64, total as u64);
        self.set_message(format!("frame {done} of {total}"));
    }
    fn cancelled(&self) -> bool {
        self.is_cancelled()
    }
}

/// Writes the turntable of `scene` into `dir` (the job's work); `preview` draws the cut as the
/// window's Preview does, otherwise the uncut models. Returns the status line.
pub fn export(
    scene: &Scene,
    preview: bool,
    settings: &TurntableSettings,
    dir: &Path,
    progress: &Progress,
) -> anyhow::Result<String> {
    let mut picture = RenderPngOptions::new(settings.width, settings.height);
    picture.mode = Some(if preview {
        ViewMode::Preview
    } else {
        ViewMode::Camera
    });
    progress.set(0, settings.options.frames as u64);
    let summary = export_turntable(scene, &picture, &settings.options, dir, progress, None)?;
    Ok(format!(
        "Exported a turntable of {} frames{} to {}",
        summary.frames,
        if summary.gif { " and a GIF" } else { "" },
        dir.display()
    ))
}

/// The Export Turntable dialog; "Choose Folder…" asks for the output folder.
pub fn window_ui(ctx: &egui::Context, app: &mut AppState) -> Vec<Action> {
    let dialog = ExportDialog {
        title: "Export Turntable",
        button: "Choose Folder…",
        purpose: Purpose::ExportTurntable,
    };
    dialog.show(ctx, &mut app.export_turntable, |ui, s| {
        ui.label("An orbit around the cut about the camera's up axis, starting at this view:");
        egui::Grid::new("export-turntable-grid")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label("Frames");
                ui.add(egui::DragValue::new(&mut s.options.frames).range(1..=MAX_FRAMES));
                ui.end_row();
                size_rows(ui, &mut s.width, &mut s.height, MAX_TURNTABLE_SIDE);
            });
        ui.checkbox(&mut s.options.gif, "Animated GIF (turntable.gif)");
        ui.add_enabled_ui(s.options.gif, |ui| {
            ui.horizontal(|ui| {
                ui.label("Frame time");
                ui.add(
                    egui::DragValue::new(&mut s.options.delay_ms)
                        .range(10..=10_000)
                        .suffix(" ms"),
                );
            });
        });
        ui.label(
            egui::RichText::new("Writes frames/frame-0001.png … into the chosen folder.").weak(),
        );
        true
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::time::Duration;

    use glam::DVec3;

    use super::*;
    use crate::export::turntable::TurntableOptions;
    use crate::gui::jobs::{Job, is_cancelled};

    fn off_centre_box() -> Scene {
        let mut scene = crate::gui::app::new_scene();
        let mesh = csg::testkit::cube(DVec3::new(5.0, -4.0, -3.0), DVec3::new(25.0, 4.0, 9.0));
        scene.models.push(crate::scene::SceneModel::new(
            "box",
            "box.obj",
            Arc::new(mesh),
            [0.9, 0.6, 0.5],
        ));
        scene.camera = scene.framing_camera();
        scene
    }

    /// The window's job: progress counts frames; a Cancel pressed after the second frame
    /// stops the export, the job ends cancelled and the folder is never created.
    #[test]
    fn the_export_job_reports_frames_and_a_cancel_writes_nothing() {
        if let Err(e) = crate::render::HeadlessRenderer::new() {
            return csg::testkit::skip(csg::testkit::Resource::Gpu, format!("{e:#}"));
        }
        let root =
            std::env::temp_dir().join(format!("cutaway-gui-turntable-{}", std::process::id()));
        std::fs::remove_dir_all(&root).ok();
        let settings = TurntableSettings {
            width: 48,
            height: 32,
            options: TurntableOptions {
                frames: 3,
                gif: true,
                delay_ms: 80,
            },
            ..Default::default()
        };

        let done_dir = root.join("done");
        let (scene, s, dir) = (off_centre_box(), settings.clone(), done_dir.clone());
        let job = Job::spawn(
            "turntable",
            || {},
            move |p| export(&scene, false, &s, &dir, p),
        );
        let progress = job.progress.clone();
        let message = job.wait(Duration::from_secs(300)).unwrap();
        assert!(message.contains("3 frames and a GIF"), "{message}");
        assert_eq!(progress.fraction(), Some(1.0));
        assert_eq!(progress.message(), "frame 3 of 3");
        assert!(done_dir.join("frames/frame-0003.png").is_file());
        assert!(done_dir.join("turntable.gif").is_file());

        let cancel_dir = root.join("cancelled");
        let (scene, dir) = (off_centre_box(), cancel_dir.clone());
        let mut s = settings.clone();
        s.options.frames = 50;
        let mut job = Job::spawn(
            "turntable",
            || {},
            move |p| export(&scene, false, &s, &dir, p),
        );
        let deadline = std::time::Instant::now() + Duration::from_secs(300);
        while job.progress.fraction().unwrap_or(0.0) < 2.0 / 50.0 {
            assert!(std::time::Instant::now() < deadline, "no progress");
            std::thread::sleep(Duration::from_millis(5));
        }
        job.progress.cancel();
        let result = loop {
            if let Some(r) = job.poll() {
                break r;
            }
            assert!(
                std::time::Instant::now() < deadline,
                "the cancel was not honoured"
            );
            std::thread::sleep(Duration::from_millis(5));
        };
        let err = result.unwrap_err();
        assert!(is_cancelled(&err), "{err:#}");
        assert!(job.progress.fraction().unwrap() < 1.0, "it ran to the end");
        // The worker may still be between its last frame and dropping the set: wait for it.
        let gone = std::time::Instant::now() + Duration::from_secs(60);
        while cancel_dir.exists() && std::time::Instant::now() < gone {
            std::thread::sleep(Duration::from_millis(20));
        }
        assert!(
            !cancel_dir.exists(),
            "a cancelled export left {}",
            cancel_dir.display()
        );
        std::fs::remove_dir_all(&root).ok();
    }
}
