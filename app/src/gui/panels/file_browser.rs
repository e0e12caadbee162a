//! The in-window file browser: used when no native file dialog can open (no desktop portal on
//! D-Bus and no zenity, as on a bare X server or in a container), so File → Open never silently
//! does nothing. Opening (File → Open…, Add Model…) uses Cutaway's own browser
//! (`open_browser.rs`: files, folders, volumes and sessions in one list); saving and exporting
//! use the `egui_file` crate with the native dialog's purposes and extensions.

use std::path::{Path, PathBuf};

use crate::gui::action::Purpose;

/// True when a native dialog can be expected to open: not turned off with `CUTAWAY_NO_DIALOGS`,
/// and a desktop portal (reached over the session D-Bus) or zenity is there. A native dialog
/// that still closes at once is caught afterwards (see `finish_job`).
pub fn native_dialogs_available() -> bool {
    if std::env::var_os("CUTAWAY_NO_DIALOGS").is_some() {
        return false;
    }
    let dbus = std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some_and(|v| !v.is_empty());
    dbus || on_path("zenity")
}

fn on_path(program: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|dir| dir.join(program).is_file()))
}

/// An open in-window browser for one purpose.
pub struct FileBrowser {
    pub purpose: Purpose,
    kind: Kind,
}

/// Opening goes through Cutaway's own browser (files, folders, volumes, sessions in one list);
/// saving, exporting and the image through `egui_file`.
enum Kind {
    Open(crate::gui::panels::open_browser::OpenBrowser),
    Dialog(Box<egui_file::FileDialog>),
}

impl FileBrowser {
    /// A browser for `purpose` starting at `start`: a folder, or the last file opened or saved
    /// (its folder, the file selected); the home folder when `None`.
    pub fn new(purpose: Purpose, start: Option<PathBuf>) -> FileBrowser {
        let start = start
            .or_else(|| std::env::var_os("HOME").map(PathBuf::from))
            .unwrap_or_else(|| PathBuf::from("."));
        if matches!(purpose, Purpose::Open | Purpose::AddModel) {
            return FileBrowser {
                purpose,
                kind: Kind::Open(crate::gui::panels::open_browser::OpenBrowser::new(
                    purpose.title(),
                    &start,
                )),
            };
        }
        let start = if start.is_dir() {
            start
        } else {
            start.parent().map(Path::to_path_buf).unwrap_or(start)
        };
        let dialog = match purpose {
            Purpose::OpenFolder | Purpose::ExportMeshes | Purpose::ExportTurntable => {
                egui_file::FileDialog::select_folder()
            }
            Purpose::SaveSessionAs => {
                egui_file::FileDialog::save_file().default_filename("session.json")
            }
            Purpose::ExportImage => {
                egui_file::FileDialog::save_file().default_filename("cutaway.png")
            }
            Purpose::ExportWebPage => {
                egui_file::FileDialog::save_file().default_filename("scene.html")
            }
            Purpose::SaveGesture => {
                egui_file::FileDialog::save_file().default_filename("gesture.json")
            }
            Purpose::Open | Purpose::AddModel | Purpose::OpenImage => {
                egui_file::FileDialog::open_file()
            }
        };
        let mut dialog = dialog
            .initial_path(start)
            .title(purpose.title())
            .id(egui::Id::unique("cutaway-file-browser"))
            .default_size([640.0, 420.0])
            .show_new_folder(false)
            .show_rename(false);
        if let Some(extensions) = extensions(purpose) {
            dialog = dialog.show_files_filter(Box::new(move |path: &Path| {
                path.extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| extensions.iter().any(|x| x.eq_ignore_ascii_case(e)))
            }));
        }
        dialog.open();
        FileBrowser {
            purpose,
            kind: Kind::Dialog(Box::new(dialog)),
        }
    }

    /// Shows the browser. `Some(paths)` once it closed (empty when cancelled), `None` while open.
    pub fn ui(&mut self, ctx: &egui::Context) -> Option<Vec<PathBuf>> {
        let dialog = match &mut self.kind {
            Kind::Open(browser) => return browser.ui(ctx),
            Kind::Dialog(dialog) => dialog,
        };
        dialog.show(ctx);
        match dialog.state() {
            egui_file::State::Open => None,
            egui_file::State::Selected => {
                Some(dialog.path().map(Path::to_path_buf).into_iter().collect())
            }
            egui_file::State::Closed | egui_file::State::Cancelled => Some(Vec::new()),
        }
    }
}

/// The files a purpose opens (`None`: anything; the readers say what they cannot read).
fn extensions(purpose: Purpose) -> Option<&'static [&'static str]> {
    match purpose {
        Purpose::OpenImage => Some(&["nrrd", "nhdr", "nii", "gz"]),
        _ => None,
    }
}
