//! The in-window browser of File → Open… and Add Model…, used when no native file dialog can
//! open (see `file_browser.rs`): one browser for everything Cutaway opens — mesh files, label
//! volumes, sessions and whole folders of meshes — listing only those, each with what it is, and
//! starting in the folder of the last file opened or saved, that file selected.
//!
//! A click selects, a double-click opens a file or enters a folder; Open opens the selection (a
//! selected folder as a folder of meshes), "Open This Folder" the folder shown.

use std::path::{Path, PathBuf};

/// What an entry of the list is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EntryKind {
    Folder,
    Mesh,
    Volume,
    Session,
}

impl EntryKind {
    /// What a file is by its name, `None` when Cutaway does not open it.
    pub fn of_file(path: &Path) -> Option<EntryKind> {
        if crate::io::dropped::is_session_path(path) {
            return Some(EntryKind::Session);
        }
        if crate::io::volume::is_volume(path) {
            return Some(EntryKind::Volume);
        }
        crate::io::Format::from_path(path).map(|_| EntryKind::Mesh)
    }

    fn note(self) -> &'static str {
        match self {
            EntryKind::Folder => "folder",
            EntryKind::Mesh => "mesh",
            EntryKind::Volume => "volume",
            EntryKind::Session => "session",
        }
    }
}

/// One row of the list.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub path: PathBuf,
    pub kind: EntryKind,
}

impl Entry {
    fn name(&self) -> String {
        self.path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| self.path.display().to_string())
    }

    /// The row's label: the glyph of a folder or a file, then the name.
    pub fn label(&self) -> String {
        let glyph = if self.kind == EntryKind::Folder {
            '\u{1F5C0}'
        } else {
            '\u{1F5CB}'
        };
        format!("{glyph} {}", self.name())
    }
}

/// The folders and the files Cutaway opens in `dir`, folders first, each group by name; hidden
/// entries left out.
pub fn list(dir: &Path) -> std::io::Result<Vec<Entry>> {
    let mut entries = Vec::new();
    for item in std::fs::read_dir(dir)? {
        let path = item?.path();
        let hidden = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'));
        if hidden {
            continue;
        }
        // A `.seg.nrrd` or DICOM-like folder that is a volume opens as one.
        let kind = if path.is_dir() && !crate::io::volume::is_volume(&path) {
            Some(EntryKind::Folder)
        } else {
            EntryKind::of_file(&path)
        };
        if let Some(kind) = kind {
            entries.push(Entry { path, kind });
        }
    }
    entries.sort_by(|a, b| {
        (a.kind != EntryKind::Folder)
            .cmp(&(b.kind != EntryKind::Folder))
            .then_with(|| a.name().to_lowercase().cmp(&b.name().to_lowercase()))
    });
    Ok(entries)
}

/// The browser's state.
pub struct OpenBrowser {
    title: String,
    dir: PathBuf,
    path_edit: String,
    entries: Result<Vec<Entry>, String>,
    selected: Option<PathBuf>,
    /// What the user chose, once they did (empty: cancelled).
    done: Option<Vec<PathBuf>>,
}

impl OpenBrowser {
    /// A browser titled `title` starting at `start`: a folder, or a file whose folder it shows
    /// with the file selected.
    pub fn new(title: &str, start: &Path) -> OpenBrowser {
        let (dir, selected) = if start.is_dir() {
            (start.to_path_buf(), None)
        } else {
            let dir = start
                .parent()
                .filter(|d| d.is_dir())
                .map(Path::to_path_buf)
                .unwrap_or_else(|| PathBuf::from("."));
            (dir, Some(start.to_path_buf()))
        };
        let mut browser = OpenBrowser {
            title: title.to_string(),
            dir: PathBuf::new(),
            path_edit: String::new(),
            entries: Ok(Vec::new()),
            selected: None,
            done: None,
        };
        browser.enter(dir);
        browser.selected = selected.filter(|s| browser.listed(s));
        browser
    }

    /// The folder shown.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The selected entry.
    pub fn selected(&self) -> Option<&Path> {
        self.selected.as_deref()
    }

    fn listed(&self, path: &Path) -> bool {
        self.entries
            .as_ref()
            .is_ok_and(|e| e.iter().any(|e| e.path == path))
    }

    fn enter(&mut self, dir: PathBuf) {
        self.entries = list(&dir).map_err(|e| format!("{}: {e}", dir.display()));
        self.path_edit = dir.display().to_string();
        self.dir = dir;
        self.selected = None;
    }

    fn open(&mut self, paths: Vec<PathBuf>) {
        self.done = Some(paths);
    }

    /// Shows the browser. `Some(paths)` once it closed (empty when cancelled), `None` while open.
    pub fn ui(&mut self, ctx: &egui::Context) -> Option<Vec<PathBuf>> {
        let mut open = true;
        egui::Window::new(&self.title)
            .id(egui::Id::unique("cutaway-open-browser"))
            .open(&mut open)
            .collapsible(false)
            .default_size([640.0, 440.0])
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ctx, |ui| self.contents(ui));
        if !open {
            self.done = Some(Vec::new());
        }
        self.done.clone()
    }

    fn contents(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let up = self.dir.parent().map(Path::to_path_buf);
            if ui
                .add_enabled(up.is_some(), egui::Button::new("Up"))
                .on_hover_text("The folder above")
                .clicked()
                && let Some(up) = up
            {
                self.enter(up);
            }
            let edit = ui
                .add(egui::TextEdit::singleline(&mut self.path_edit).desired_width(f32::INFINITY));
            if edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                let typed = PathBuf::from(self.path_edit.trim());
                if typed.is_dir() {
                    self.enter(typed);
                } else if typed.is_file() {
                    self.open(vec![typed]);
                }
            }
        });
        ui.separator();
        let footer = 70.0;
        let mut entered = None;
        egui::ScrollArea::vertical()
            .auto_shrink([false, false])
            .max_height((ui.available_height() - footer).max(80.0))
            .show(ui, |ui| match &self.entries {
                Err(e) => {
                    ui.colored_label(ui.visuals().error_fg_color, e);
                }
                Ok(entries) if entries.is_empty() => {
                    ui.weak("No folders, meshes, volumes or sessions here");
                }
                Ok(entries) => {
                    for entry in entries {
                        let selected = self.selected.as_ref() == Some(&entry.path);
                        let row = ui
                            .horizontal(|ui| {
                                let row = ui.selectable_label(selected, entry.label());
                                ui.weak(entry.kind.note());
                                row
                            })
                            .inner;
                        if row.double_clicked() {
                            entered = Some(entry.clone());
                        } else if row.clicked() {
                            self.selected = Some(entry.path.clone());
                        }
                    }
                }
            });
        if let Some(entry) = entered {
            if entry.kind == EntryKind::Folder {
                self.enter(entry.path);
            } else {
                self.open(vec![entry.path]);
            }
        }
        ui.separator();
        let chosen = self
            .selected
            .as_ref()
            .and_then(|p| p.file_name())
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        ui.horizontal(|ui| {
            ui.label("Selected:");
            ui.strong(chosen);
        });
        ui.horizontal(|ui| {
            let folder = self
                .dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| self.dir.display().to_string());
            if ui
                .button(format!("Open This Folder ({folder})"))
                .on_hover_text("Every mesh file in this folder and its subfolders")
                .clicked()
            {
                self.open(vec![self.dir.clone()]);
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                if ui.button("Cancel").clicked() {
                    self.open(Vec::new());
                }
                if ui
                    .add_enabled(self.selected.is_some(), egui::Button::new("Open"))
                    .clicked()
                    && let Some(path) = self.selected.clone()
                {
                    self.open(vec![path]);
                }
            });
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_holds_folders_then_what_cutaway_opens_and_starts_on_the_last_file() {
        let dir = std::env::temp_dir().join(format!("cutaway-open-list-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("atlas")).unwrap();
        std::fs::create_dir_all(dir.join(".hidden")).unwrap();
        for name in [
            "b.stl",
            "A.obj",
            "s.json",
            "ct.nii.gz",
            "notes.txt",
            "seg.nrrd",
        ] {
            std::fs::write(dir.join(name), "x").unwrap();
        }
        let entries = list(&dir).unwrap();
        let shown: Vec<(String, EntryKind)> = entries.iter().map(|e| (e.name(), e.kind)).collect();
        assert_eq!(
            shown,
            [
                ("atlas".to_string(), EntryKind::Folder),
                ("A.obj".to_string(), EntryKind::Mesh),
                ("b.stl".to_string(), EntryKind::Mesh),
                ("ct.nii.gz".to_string(), EntryKind::Volume),
                ("s.json".to_string(), EntryKind::Session),
                ("seg.nrrd".to_string(), EntryKind::Volume),
            ]
        );
        let browser = OpenBrowser::new("Open", &dir.join("b.stl"));
        assert_eq!(browser.dir(), dir.as_path());
        assert_eq!(browser.selected(), Some(dir.join("b.stl").as_path()));
        // A last file that is gone: its folder, nothing selected.
        let browser = OpenBrowser::new("Open", &dir.join("gone.obj"));
        assert_eq!(browser.dir(), dir.as_path());
        assert_eq!(browser.selected(), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
