//! File → Export Web Page…: the dialog (the page's title; the measures it shows follow the
//! Metrics panel's focus and critical structures) and the background job that writes the page
//! with [`crate::export::webpage`], the same code as `cutaway export … --out scene.html`. The
//! job's progress bar counts the steps (each variant cut and measured, then the page written);
//! its Cancel stops the export between steps and nothing is written.

use std::path::Path;

use crate::export::webpage::{WebPageOptions, export_webpage};
use crate::gui::action::{Action, Purpose};
use crate::gui::jobs::Progress;
use crate::gui::panels::export_dialog::ExportDialog;
use crate::gui::state::AppState;
use crate::metrics::MetricsOptions;
use crate::scene::Scene;

pub use crate::gui::state::export_settings::WebPageSettings;

/// Writes `scene` (every variant) as a page to `path` (the job's work). Returns the status line.
pub fn export(
    scene: &Scene,
    settings: &WebPageSettings,
    metrics: MetricsOptions,
    path: &Path,
    progress: &Progress,
) -> anyhow::Result<String> {
    let title = settings.title.trim();
    let options = WebPageOptions {
        title: (!title.is_empty()).then(|| title.to_string()),
        metrics,
    };
    let summary = export_webpage(scene, path, &options, progress)?;
    Ok(format!(
        "Exported a web page of {} structures{} ({:.1} MB) to {}",
        summary.structures,
        if summary.variants > 1 {
            format!(" and {} variants", summary.variants)
        } else {
            String::new()
        },
        summary.bytes as f64 / (1024.0 * 1024.0),
        path.display()
    ))
}

/// The Export Web Page dialog; "Choose File…" asks where to write the page.
pub fn window_ui(ctx: &egui::Context, app: &mut AppState) -> Vec<Action> {
    let dialog = ExportDialog {
        title: "Export Web Page",
        button: "Choose File…",
        purpose: Purpose::ExportWebPage,
    };
    dialog.show(ctx, &mut app.export_webpage, |ui, s| {
        let variants = crate::scene::variants::names(&app.scene).len();
        let focus = app.metrics.focus.clone();
        let critical = app.metrics.critical.clone();
        ui.label(
            "One HTML file that opens in any current browser, from disk, with no install: \
             the cut scene to turn and zoom, the structure list, the standard views and \
             the measures.",
        );
        ui.horizontal(|ui| {
            ui.label("Title");
            ui.add(
                egui::TextEdit::singleline(&mut s.title)
                    .hint_text(crate::export::webpage::DEFAULT_TITLE)
                    .char_limit(crate::export::webpage::MAX_TITLE_CHARS)
                    .desired_width(260.0),
            );
        });
        let mut notes = vec![if variants > 1 {
            format!("All {variants} cut variants, switchable in the page.")
        } else {
            "The cut as Preview shows it.".to_string()
        }];
        match (&focus, critical.is_empty()) {
            (None, true) => notes.push(
                "Measures: removal per structure (mark a focus or critical structures in \
                 the Metrics panel to add exposure and distances)."
                    .to_string(),
            ),
            _ => notes.push(format!(
                "Measures: removal{}{}.",
                focus
                    .as_ref()
                    .map(|f| format!(", exposure of {f}"))
                    .unwrap_or_default(),
                if critical.is_empty() {
                    String::new()
                } else {
                    format!(", distance to {}", critical.join(", "))
                }
            )),
        }
        for note in notes {
            ui.label(egui::RichText::new(note).weak());
        }
        true
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::time::Duration;

    use glam::DVec3;

    use super::*;
    use crate::gui::jobs::{Job, is_cancelled};

    fn cut_box() -> Scene {
        let mut scene = crate::gui::app::new_scene();
        let mesh = csg::testkit::cube(DVec3::splat(-10.0), DVec3::splat(10.0));
        scene.models.push(crate::scene::SceneModel::new(
            "box",
            "box.obj",
            Arc::new(mesh),
            [0.9, 0.6, 0.5],
        ));
        scene.camera = scene.framing_camera();
        scene
    }

    /// The window's job writes the page and says so; a job cancelled before it starts its
    /// first step ends cancelled and writes nothing.
    #[test]
    fn the_export_job_writes_the_page_and_a_cancel_writes_nothing() {
        let root = std::env::temp_dir().join(format!("cutaway-gui-webpage-{}", std::process::id()));
        std::fs::remove_dir_all(&root).ok();
        std::fs::create_dir_all(&root).unwrap();
        let settings = WebPageSettings {
            open: false,
            title: "  A box  ".to_string(),
        };
        let path = root.join("box.html");
        let (scene, s, p) = (cut_box(), settings.clone(), path.clone());
        let job = Job::spawn(
            "web page",
            || {},
            move |progress| export(&scene, &s, MetricsOptions::default(), &p, progress),
        );
        let progress = job.progress.clone();
        let message = job.wait(Duration::from_secs(300)).unwrap();
        assert!(message.contains("1 structures"), "{message}");
        assert_eq!(progress.fraction(), Some(1.0));
        let html = std::fs::read_to_string(&path).unwrap();
        assert!(html.contains("<title>A box</title>"));

        let cancelled = root.join("cancelled.html");
        let progress = Progress::default();
        progress.cancel();
        let err = export(
            &cut_box(),
            &settings,
            MetricsOptions::default(),
            &cancelled,
            &progress,
        )
        .unwrap_err();
        assert!(is_cancelled(&err), "{err:#}");
        assert!(!cancelled.exists());
        std::fs::remove_dir_all(&root).ok();
    }
}
