//! What the user can ask of the window, and the one place each request takes effect.
//!
//! Every user command (menu item, button, shortcut, context menu, dropped file) becomes an
//! [`Action`] applied in [`CutawayApp::apply`], so the menus and panels only describe what the
//! user asked for and the undo history sees every scene change. Keys and dropped files are turned
//! into actions here too, so every input path ends in the same match.

use std::path::PathBuf;
use std::sync::Arc;

use crate::dropped::DropIntent;
use crate::scene::Scene;

use super::app::CutawayApp;
use super::app_jobs::{JobOutput, file_label};
use super::undo::Apply;
use crate::view::camera_controls;

/// What the mouse does in the viewport (thesis 3.5 C).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Drag orbits, Shift+drag pans, wheel zooms, double-click selects and centres a model.
    Camera,
    /// Mouse input goes to the cutter editor.
    Edit,
    /// Cuts executed, cutters hidden, camera controls.
    Preview,
    /// Progressive scalpel cut (when the scalpel module exists).
    Scalpel,
}

impl Mode {
    pub fn label(self) -> &'static str {
        match self {
            Mode::Camera => "Camera",
            Mode::Edit => "Edit",
            Mode::Preview => "Preview",
            Mode::Scalpel => "Scalpel",
        }
    }
}

/// What a file dialog was opened for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purpose {
    LoadModel,
    LoadDirectory,
    AddModel,
    OpenSession,
    SaveSessionAs,
    ExportImage,
    ExportMeshes,
    ExportTurntable,
    SaveGesture,
    OpenImage,
}

impl Purpose {
    pub fn title(self) -> &'static str {
        match self {
            Purpose::LoadModel => "Load Model",
            Purpose::LoadDirectory => "Load Directory",
            Purpose::AddModel => "Add Model",
            Purpose::OpenSession => "Open Session",
            Purpose::SaveSessionAs => "Save Session As",
            Purpose::ExportImage => "Export Image",
            Purpose::ExportMeshes => "Export Cut Meshes to Folder",
            Purpose::ExportTurntable => "Export Turntable to Folder",
            Purpose::SaveGesture => "Save Gesture",
            Purpose::OpenImage => "Open Image",
        }
    }
}

/// Every command the user can give.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Open a file dialog for this purpose.
    Dialog(Purpose),
    /// Replace the scene with these files (models or one session).
    Open(Vec<PathBuf>),
    /// Add these model files to the scene.
    Add(Vec<PathBuf>),
    SaveSession,
    SaveSessionTo(PathBuf),
    /// Read this intensity image and show it on the walls.
    OpenImage(PathBuf),
    ExportImageTo(PathBuf),
    ExportMeshesTo(PathBuf),
    /// Write the turntable of the Export Turntable dialog into this folder.
    ExportTurntableTo(PathBuf),
    Exit,
    Undo,
    Redo,
    SetMode(Mode),
    RemoveAllCutGeometry,
    ToggleCutters,
    ResetCamera,
    SelectModel(Option<usize>),
    /// Centre the camera on a model.
    FocusModel(usize),
    RemoveModel(usize),
    /// One model per connected region of model `i` ([`crate::scene_regions`]).
    SplitRegions(usize),
    StartGesture,
    StopGesture,
    /// Keep the current cutter; the next drag in Edit mode starts a new one.
    NewCutter,
    /// Replace the scene with an embedded example scene.
    OpenExample(String),
    /// Open scene cutter `i` in the editor.
    EditCutter(usize),
    /// Delete scene cutter `i`.
    RemoveCutter(usize),
    RestoreRecovery,
    DiscardRecovery,
    /// Turn, zoom or re-orient the view (View menu, view keys).
    View(super::view_menu::ViewCommand),
}

impl CutawayApp {
    /// Applies one user command.
    pub fn apply(&mut self, ctx: &egui::Context, action: Action) {
        match action {
            Action::Dialog(purpose) => self.open_dialog(ctx, purpose),
            Action::Open(paths) => self.open_paths(ctx, paths, true),
            Action::Add(paths) => self.open_paths(ctx, paths, false),
            Action::OpenImage(path) => {
                let label = format!("Loading image {}", file_label(&path));
                self.spawn(ctx, label, move |_| {
                    let image = crate::io::volume::intensity::read_image(&path)?;
                    Ok(JobOutput::Image(crate::intensity::ImageLayer::new(
                        Arc::new(image),
                    )))
                });
            }
            Action::SaveSession => match self.session_path.clone() {
                Some(path) => self.apply(ctx, Action::SaveSessionTo(path)),
                None => self.open_dialog(ctx, Purpose::SaveSessionAs),
            },
            Action::SaveSessionTo(path) => match self.save_session(&path) {
                Ok(()) => {
                    self.recent.add(&path);
                    self.session_path = Some(path.clone());
                    self.say(format!("Saved {}", path.display()));
                }
                Err(e) => self.complain(&e),
            },
            Action::ExportImageTo(path) => self.export_image_to(ctx, path),
            Action::ExportMeshesTo(dir) => self.export_meshes_to(ctx, dir),
            Action::ExportTurntableTo(dir) => self.export_turntable_to(ctx, dir),
            Action::Exit => {
                self.exiting = true;
                self.recovery.discard();
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            Action::Undo => self.undo(),
            Action::Redo => self.redo(),
            Action::SetMode(mode) => self.set_mode(mode),
            Action::RemoveAllCutGeometry => self.remove_all_cut_geometry(ctx),
            Action::ToggleCutters => {
                self.cutters_hidden = !self.cutters_hidden;
                self.hidden_cutters = if self.cutters_hidden {
                    self.scene.cutters.len()
                } else {
                    0
                };
                if self.cutters_hidden {
                    // The next drag makes a new, visible cutter instead of editing a hidden one.
                    self.viewport.editor.finish();
                }
                self.say(if self.cutters_hidden {
                    "Cutters hidden"
                } else {
                    "Cutters shown"
                });
            }
            Action::ResetCamera => {
                self.scene.camera = self.scene.preset_camera(crate::view::ViewPreset::Anterior);
            }
            Action::SelectModel(index) => {
                self.selected_model = index.filter(|&i| i < self.scene.models.len());
                if self.viewport.editor.target() != self.selected_model {
                    self.viewport.editor.finish();
                }
            }
            Action::FocusModel(index) => {
                if let Some(model) = self.scene.models.get(index) {
                    let name = model.name.clone();
                    let centre = model.mesh.bbox().center();
                    camera_controls::centre_on(&mut self.scene.camera, centre);
                    self.selected_model = Some(index);
                    if self.viewport.editor.target() != Some(index) {
                        self.viewport.editor.finish();
                    }
                    self.say(format!("Target: {name}"));
                }
            }
            Action::RemoveModel(index) => {
                if index < self.scene.models.len() {
                    let before = self.scene.clone();
                    let removed = self.scene.models.remove(index);
                    self.selected_model = None;
                    self.viewport.editor.finish();
                    self.scene.cutters.retain(|c| c.target != index);
                    for c in &mut self.scene.cutters {
                        if c.target > index {
                            c.target -= 1;
                        }
                    }
                    self.record(&format!("remove {}", removed.name), before);
                }
            }
            Action::SplitRegions(index) => {
                let Some(name) = self.scene.models.get(index).map(|m| m.name.clone()) else {
                    return;
                };
                let before = self.scene.clone();
                match crate::scene_regions::split_into_regions(&mut self.scene, index) {
                    Ok(count) => {
                        self.record(&format!("split {name}"), before);
                        self.say(format!("{name}: {count} regions, listed under \"{name}\""));
                    }
                    Err(why) => self.say(format!("{name} not split: {why}")),
                }
            }
            Action::StartGesture => self
                .viewport
                .start_recording(&self.scene.camera, &self.cutter_init),
            Action::StopGesture => {
                if self.viewport.recording.is_some() {
                    self.open_dialog(ctx, Purpose::SaveGesture);
                }
            }
            Action::OpenExample(name) => self.load_example(ctx, name),
            Action::NewCutter => {
                self.viewport.editor.finish();
                self.say("The next drag on the target starts a new cutter");
            }
            Action::EditCutter(i) => {
                if self.viewport.editor.edit_existing(
                    &self.scene,
                    i,
                    self.viewport.size_px,
                    &self.cutter_init,
                ) {
                    self.selected_model = self.viewport.editor.target();
                    self.selected_cutter = i;
                    // The Initialization tab shows the edited cutter's smoothing.
                    let c = &self.scene.cutters[i].cutter;
                    (self.cutter_init.smooth, self.cutter_init.levels) = (c.smooth, c.levels);
                    self.viewport
                        .editor
                        .apply_settings(&mut self.scene, &self.cutter_init);
                    self.set_mode(Mode::Edit);
                    self.say(format!("Editing cutter {}", i + 1));
                } else if let Some(target) = self.scene.cutters.get(i).map(|c| c.target) {
                    self.start_index_job(ctx, target);
                }
            }
            Action::RemoveCutter(i) => {
                if i < self.scene.cutters.len() {
                    let before = self.scene.clone();
                    self.scene.cutters.remove(i);
                    self.viewport.editor.finish();
                    self.record(&format!("remove cutter {}", i + 1), before);
                }
            }
            Action::RestoreRecovery => {
                if let Some(path) = self.pending_recovery.take() {
                    self.open_paths(ctx, vec![path], true);
                    // The restored scene lives in memory now; keep the file until the next autosave.
                }
            }
            Action::DiscardRecovery => {
                self.pending_recovery = None;
                self.recovery.discard();
            }
            Action::View(command) => super::view_menu::apply(self, command),
        }
    }

    pub(super) fn set_mode(&mut self, mode: Mode) {
        if mode == self.mode {
            return;
        }
        if mode == Mode::Scalpel && !super::bridge::SCALPEL_AVAILABLE {
            self.say("The scalpel is not available in this build");
            return;
        }
        self.viewport.cancel_drag();
        if self.mode == Mode::Scalpel {
            super::scalpel_mode::finish_stroke(self);
        }
        self.mode = mode;
        self.say(format!("{} mode", mode.label()));
    }

    pub(super) fn undo(&mut self) {
        if let Some((label, before)) = self.pending_edit.take() {
            self.history.push_scene(label, before, self.scene.clone());
        }
        let state = match self.history.undo() {
            Some(Apply::Scene(state)) => Some(state.clone()),
            // Cutter edits are recorded as scene snapshots; the editor follows the scene.
            Some(Apply::Editor) | None => None,
        };
        self.apply_history_step(state, "Undone", "Nothing to undo");
    }

    pub(super) fn redo(&mut self) {
        let state = match self.history.redo() {
            Some(Apply::Scene(state)) => Some(state.clone()),
            Some(Apply::Editor) | None => None,
        };
        self.apply_history_step(state, "Redone", "Nothing to redo");
    }

    /// Puts the scene state of an undo/redo step into effect (the editor follows the scene); the
    /// camera, the Rendering settings (anaglyph, background) and the orientation are views, not
    /// edits, and stay as they are: an undo must not turn anaglyph back on.
    pub(super) fn apply_history_step(&mut self, state: Option<Scene>, done: &str, nothing: &str) {
        let Some(state) = state else {
            self.say(nothing);
            return;
        };
        let (camera, render, orientation) =
            (self.scene.camera, self.scene.render, self.scene.orientation);
        self.scene = state;
        self.scene.camera = camera;
        self.scene.render = render;
        self.scene.orientation = orientation;
        self.fix_selection();
        self.viewport.editor.sync_from_scene(&self.scene);
        self.recovery.mark_dirty();
        self.say(done);
    }

    pub(super) fn fix_selection(&mut self) {
        if self
            .selected_model
            .is_some_and(|i| i >= self.scene.models.len())
        {
            self.selected_model = None;
        }
    }

    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) -> Vec<Action> {
        use egui::{Key, KeyboardShortcut, Modifiers};
        let mut actions = Vec::new();
        if ctx.egui_wants_keyboard_input() {
            return actions;
        }
        let redo = KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
        let redo_y = KeyboardShortcut::new(Modifiers::COMMAND, Key::Y);
        let undo = KeyboardShortcut::new(Modifiers::COMMAND, Key::Z);
        let save = KeyboardShortcut::new(Modifiers::COMMAND, Key::S);
        let open = KeyboardShortcut::new(Modifiers::COMMAND, Key::O);
        ctx.input_mut(|i| {
            // Longest modifier set first so Ctrl+Shift+Z is not taken for Ctrl+Z.
            if i.consume_shortcut(&redo) || i.consume_shortcut(&redo_y) {
                actions.push(Action::Redo);
            }
            if i.consume_shortcut(&undo) {
                actions.push(Action::Undo);
            }
            if i.consume_shortcut(&save) {
                actions.push(Action::SaveSession);
            }
            if i.consume_shortcut(&open) {
                actions.push(Action::Dialog(Purpose::LoadModel));
            }
            for (key, mode) in [
                (Key::F1, Mode::Camera),
                (Key::F2, Mode::Edit),
                (Key::F3, Mode::Preview),
                (Key::F4, Mode::Scalpel),
            ] {
                if i.consume_key(Modifiers::NONE, key) {
                    actions.push(Action::SetMode(mode));
                }
            }
        });
        actions
    }

    pub(super) fn dropped_files(&mut self, ctx: &egui::Context) -> Vec<Action> {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        if dropped.is_empty() {
            return Vec::new();
        }
        // The rule lives in `dropped.rs`: a session opens, the rest opens or is added.
        match crate::dropped::intent_of_drop(dropped, self.scene.models.is_empty()) {
            Some(DropIntent::Session(path)) => vec![Action::Open(vec![path])],
            Some(DropIntent::Open(paths)) => vec![Action::Open(paths)],
            Some(DropIntent::Add(paths)) => vec![Action::Add(paths)],
            None => Vec::new(),
        }
    }
}
