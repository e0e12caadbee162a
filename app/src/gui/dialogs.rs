//! File dialogs: the native one on a worker thread, the in-window browser when no native dialog
//! can open, the recovery prompt, and what a picked path turns into.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::gui::action::{Action, Purpose, UnsavedAnswer};
use crate::gui::app::CutawayApp;
use crate::gui::job_output::JobOutput;

impl CutawayApp {
    pub(super) fn open_dialog(&mut self, ctx: &egui::Context, purpose: Purpose) {
        let last_file = self.last_file();
        let start_dir = last_file
            .as_ref()
            .and_then(|p| p.parent().map(Path::to_path_buf));
        if !self.state.native_dialogs {
            self.state.browser = Some(crate::gui::panels::file_browser::FileBrowser::new(
                purpose, last_file,
            ));
            return;
        }
        self.spawn(ctx, purpose.title(), move |_| {
            let started = Instant::now();
            let mut dialog = rfd::AsyncFileDialog::new().set_title(purpose.title());
            if let Some(dir) = &start_dir {
                dialog = dialog.set_directory(dir);
            }
            let meshes = ["obj", "stl", "ply", "vtk"];
            // `.seg.nrrd` ends in `nrrd`; `.nii.gz` in `gz` (a filter names one extension).
            let volumes = ["nrrd", "nhdr", "nii", "gz"];
            let everything = [meshes.as_slice(), &volumes, &["json"]].concat();
            let paths: Vec<PathBuf> = pollster::block_on(async move {
                match purpose {
                    Purpose::Open | Purpose::AddModel => dialog
                        .add_filter("Meshes, volumes and sessions", &everything)
                        .add_filter("Meshes", &meshes)
                        .add_filter("Label volumes", &volumes)
                        .add_filter("Session", &["json"])
                        .pick_files()
                        .await
                        .map(|files| files.iter().map(|f| f.path().to_path_buf()).collect())
                        .unwrap_or_default(),
                    Purpose::OpenFolder | Purpose::ExportMeshes | Purpose::ExportTurntable => {
                        dialog
                            .pick_folder()
                            .await
                            .map(|f| vec![f.path().to_path_buf()])
                            .unwrap_or_default()
                    }
                    Purpose::OpenImage => dialog
                        .add_filter("Image volume", &["nrrd", "nhdr", "nii", "gz"])
                        .pick_file()
                        .await
                        .map(|f| vec![f.path().to_path_buf()])
                        .unwrap_or_default(),
                    Purpose::SaveSessionAs => dialog
                        .add_filter("Cutaway session", &["json"])
                        .set_file_name("session.json")
                        .save_file()
                        .await
                        .map(|f| vec![f.path().to_path_buf()])
                        .unwrap_or_default(),
                    Purpose::ExportWebPage => dialog
                        .add_filter("Web page", &["html"])
                        .set_file_name("scene.html")
                        .save_file()
                        .await
                        .map(|f| vec![f.path().to_path_buf()])
                        .unwrap_or_default(),
                    Purpose::ExportImage => dialog
                        .add_filter("PNG image", &["png"])
                        .set_file_name("cutaway.png")
                        .save_file()
                        .await
                        .map(|f| vec![f.path().to_path_buf()])
                        .unwrap_or_default(),
                    Purpose::SaveGesture => dialog
                        .add_filter("Gesture", &["json"])
                        .set_file_name("gesture.json")
                        .save_file()
                        .await
                        .map(|f| vec![f.path().to_path_buf()])
                        .unwrap_or_default(),
                }
            });
            Ok(JobOutput::Picked {
                purpose,
                paths,
                took: started.elapsed(),
            })
        });
    }

    /// Where a file dialog starts: the file most recently opened or saved (both go to the recent
    /// list), else the session's.
    pub(super) fn last_file(&self) -> Option<PathBuf> {
        self.state
            .recent
            .paths
            .first()
            .or(self.state.session_path.as_ref())
            .cloned()
    }

    /// What happens once a dialog (native or manual) gave paths.
    pub(super) fn picked(&mut self, ctx: &egui::Context, purpose: Purpose, paths: Vec<PathBuf>) {
        let Some(first) = paths.first().cloned() else {
            if purpose == Purpose::SaveSessionAs && self.state.after_save.take().is_some() {
                self.state.say("Not saved; nothing was opened");
            }
            return;
        };
        match purpose {
            Purpose::Open | Purpose::OpenFolder => self.apply(ctx, Action::Open(paths)),
            Purpose::AddModel => self.apply(ctx, Action::Add(paths)),
            Purpose::SaveSessionAs => {
                self.apply(ctx, Action::SaveSessionTo(with_extension(first, "json")))
            }
            Purpose::ExportImage => {
                self.apply(ctx, Action::ExportImageTo(with_extension(first, "png")))
            }
            Purpose::ExportMeshes => self.apply(ctx, Action::ExportMeshesTo(first)),
            Purpose::ExportTurntable => self.apply(ctx, Action::ExportTurntableTo(first)),
            Purpose::ExportWebPage => {
                self.apply(ctx, Action::ExportWebPageTo(web_page_path(first)))
            }
            Purpose::OpenImage => self.apply(ctx, Action::OpenImage(first)),
            Purpose::SaveGesture => {
                let path = with_extension(first, "json");
                match self.state.viewport.save_recording(&path) {
                    Ok(n) => self
                        .state
                        .say(format!("Saved gesture of {n} events to {}", path.display())),
                    Err(e) => self.state.complain(&e),
                }
            }
        }
    }

    pub(super) fn dialogs_ui(&mut self, ctx: &egui::Context) -> Vec<Action> {
        let mut actions = Vec::new();
        if let Some(path) = self.state.pending_recovery.clone() {
            egui::Modal::new(egui::Id::unique("cutaway-recovery")).show(ctx, |ui| {
                ui.heading("Restore the previous session?");
                ui.label("Cutaway did not exit cleanly last time. An autosaved session was found:");
                ui.label(
                    egui::RichText::new(path.display().to_string())
                        .monospace()
                        .small(),
                );
                ui.add_space(8.0);
                ui.horizontal(|ui| {
                    if ui.button("Restore").clicked() {
                        actions.push(Action::RestoreRecovery);
                    }
                    if ui.button("Discard").clicked() {
                        actions.push(Action::DiscardRecovery);
                    }
                });
            });
        }
        if let Some(waiting) = &self.state.unsaved_prompt {
            let what = match waiting {
                Action::Open(paths) => match paths.as_slice() {
                    [one] => format!(
                        "opening {}",
                        one.file_name()
                            .map(|n| n.to_string_lossy().into_owned())
                            .unwrap_or_else(|| one.display().to_string())
                    ),
                    many => format!("opening {} items", many.len()),
                },
                Action::OpenExample(name) => format!("opening the {name} example"),
                Action::Exit => "exiting".to_string(),
                _ => "going on".to_string(),
            };
            egui::Modal::new(egui::Id::unique("cutaway-unsaved")).show(ctx, |ui| {
                ui.heading("Save the changes first?");
                ui.label(format!(
                    "The scene has changes that are not saved. Save them before {what}?"
                ));
                ui.add_space(8.0);
                ui.horizontal(|ui| {
                    for (label, answer) in [
                        ("Save", UnsavedAnswer::Save),
                        ("Don't Save", UnsavedAnswer::Discard),
                        ("Cancel", UnsavedAnswer::Cancel),
                    ] {
                        if ui.button(label).clicked() {
                            actions.push(Action::Unsaved(answer));
                        }
                    }
                });
            });
        }
        if let Some(browser) = &mut self.state.browser
            && let Some(paths) = browser.ui(ctx)
        {
            let purpose = browser.purpose;
            self.state.browser = None;
            if let Some(path) = paths.into_iter().next() {
                self.state.pending_manual = Some((purpose, path));
            }
        }
        actions
    }
}

fn with_extension(path: PathBuf, ext: &str) -> PathBuf {
    if path.extension().is_some() {
        path
    } else {
        path.with_extension(ext)
    }
}

/// A page's file: `.html` or `.htm` as chosen, else `.html` added (`scene` → `scene.html`,
/// `scene.v2` → `scene.v2.html`), so the file opens as a page.
fn web_page_path(path: PathBuf) -> PathBuf {
    let is_page = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"));
    if is_page {
        path
    } else {
        let mut name = path.into_os_string();
        name.push(".html");
        PathBuf::from(name)
    }
}
