//! The one place each user [`Action`] takes effect, and how keys and dropped files become actions.
//!
//! Every user command (menu item, button, shortcut, context menu, dropped file) becomes an
//! [`Action`] applied in [`CutawayApp::apply`], so every input path ends in the same match.

use std::path::PathBuf;
use std::sync::Arc;

use crate::io::dropped::DropIntent;
use crate::scene::Scene;

use crate::gui::action::{Action, Mode, Purpose, UnsavedAnswer};
use crate::gui::app::CutawayApp;
use crate::gui::job_output::JobOutput;
use crate::scene::open::file_label;
use crate::session::undo::Apply;
use crate::view::camera_controls;

impl CutawayApp {
    /// Applies one user command.
    pub fn apply(&mut self, ctx: &egui::Context, action: Action) {
        match action {
            Action::Dialog(purpose) => self.open_dialog(ctx, purpose),
            Action::Open(paths) => {
                if !self.asks_to_save(Action::Open(paths.clone())) {
                    self.open_paths(ctx, paths, true);
                }
            }
            Action::Unsaved(answer) => self.unsaved_answered(ctx, answer),
            Action::Add(paths) => self.open_paths(ctx, paths, false),
            Action::OpenImage(path) => {
                let label = format!("Loading image {}", file_label(&path));
                self.spawn(ctx, label, move |_| {
                    let image = crate::io::volume::intensity::read_image(&path)?;
                    Ok(JobOutput::Image(crate::scene::ImageLayer::new(Arc::new(
                        image,
                    ))))
                });
            }
            Action::SaveSession => match self.state.session_path.clone() {
                Some(path) => self.apply(ctx, Action::SaveSessionTo(path)),
                None => self.open_dialog(ctx, Purpose::SaveSessionAs),
            },
            Action::SaveSessionTo(path) => match self.save_session(&path) {
                Ok(()) => {
                    self.state.recent.add(&path);
                    self.state.session_path = Some(path.clone());
                    self.state.recovery.mark_saved();
                    self.state.say(format!("Saved {}", path.display()));
                    if let Some(next) = self.state.after_save.take() {
                        self.apply(ctx, next);
                    }
                }
                Err(e) => {
                    self.state.after_save = None;
                    self.state.complain(&e);
                }
            },
            Action::ExportImageTo(path) => self.export_image_to(ctx, path),
            Action::ExportMeshesTo(dir) => self.export_meshes_to(ctx, dir),
            Action::ExportTurntableTo(dir) => self.export_turntable_to(ctx, dir),
            Action::ExportWebPageTo(path) => self.export_webpage_to(ctx, path),
            Action::Exit => {
                if self.asks_to_save(Action::Exit) {
                    return;
                }
                self.state.exiting = true;
                self.state.recovery.discard();
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            Action::Undo => self.undo(),
            Action::Redo => self.redo(),
            Action::SetMode(mode) => self.set_mode(mode),
            Action::RemoveAllCutGeometry => self.remove_all_cut_geometry(ctx),
            Action::ToggleCutters => {
                self.state.cutters_hidden = !self.state.cutters_hidden;
                self.state.hidden_cutters = if self.state.cutters_hidden {
                    self.state.scene.cutters.len()
                } else {
                    0
                };
                if self.state.cutters_hidden {
                    // The next drag makes a new, visible cutter instead of editing a hidden one.
                    self.state.viewport.editor.finish();
                }
                self.state.say(if self.state.cutters_hidden {
                    "Cutters hidden"
                } else {
                    "Cutters shown"
                });
            }
            Action::ResetCamera => {
                self.state.scene.camera = self
                    .state
                    .scene
                    .preset_camera(crate::scene::ViewPreset::Anterior);
            }
            Action::SelectModel(index) => {
                self.state.selected_model = index.filter(|&i| i < self.state.scene.models.len());
                if self.state.viewport.editor.target() != self.state.selected_model {
                    self.state.viewport.editor.finish();
                }
            }
            Action::FocusModel(index) => {
                if let Some(model) = self.state.scene.models.get(index) {
                    let name = model.model.name.clone();
                    let centre = model.model.mesh.bbox().center();
                    camera_controls::centre_on(&mut self.state.scene.camera, centre);
                    self.state.selected_model = Some(index);
                    if self.state.viewport.editor.target() != Some(index) {
                        self.state.viewport.editor.finish();
                    }
                    self.state.say(format!("Target: {name}"));
                }
            }
            Action::RemoveModel(index) => {
                if index < self.state.scene.models.len() {
                    let before = self.state.scene.clone();
                    let removed = self.state.scene.models.remove(index);
                    self.state.selected_model = None;
                    self.state.viewport.editor.finish();
                    self.state.scene.cutters.retain(|c| c.target != index);
                    for c in &mut self.state.scene.cutters {
                        if c.target > index {
                            c.target -= 1;
                        }
                    }
                    self.state
                        .record(&format!("remove {}", removed.model.name), before);
                }
            }
            Action::SplitRegions(index) => {
                let Some(name) = self
                    .state
                    .scene
                    .models
                    .get(index)
                    .map(|m| m.model.name.clone())
                else {
                    return;
                };
                let before = self.state.scene.clone();
                match crate::scene::regions::split_into_regions(&mut self.state.scene, index) {
                    Ok(count) => {
                        self.state.record(&format!("split {name}"), before);
                        self.state
                            .say(format!("{name}: {count} regions, listed under \"{name}\""));
                    }
                    Err(why) => self.state.say(format!("{name} not split: {why}")),
                }
            }
            Action::StartGesture => self
                .state
                .viewport
                .start_recording(&self.state.scene.camera, &self.state.cutter_init),
            Action::StopGesture => {
                if self.state.viewport.recording.is_some() {
                    self.open_dialog(ctx, Purpose::SaveGesture);
                }
            }
            Action::OpenExample(name) => {
                if !self.asks_to_save(Action::OpenExample(name.clone())) {
                    self.load_example(ctx, name);
                }
            }
            Action::NewCutter => {
                self.state.viewport.editor.finish();
                self.state
                    .say("The next drag on the target starts a new cutter");
            }
            Action::EditCutter(i) => {
                if self.state.viewport.editor.edit_existing(
                    &self.state.scene,
                    i,
                    self.state.viewport.size_px,
                    &self.state.cutter_init,
                    &mut self.state.viewport.picks,
                ) {
                    self.state.selected_model = self.state.viewport.editor.target();
                    self.state.selected_cutter = i;
                    // The Initialization tab shows the edited cutter's smoothing and direction,
                    // so it goes on as it was made.
                    let c = &self.state.scene.cutters[i].cutter;
                    (self.state.cutter_init.smooth, self.state.cutter_init.levels) =
                        (c.smooth, c.levels);
                    self.state.cutter_init.direction = c.direction;
                    self.state
                        .viewport
                        .editor
                        .apply_settings(&mut self.state.scene, &self.state.cutter_init);
                    self.set_mode(Mode::Edit);
                    self.state.say(format!("Editing cutter {}", i + 1));
                } else if let Some(target) = self.state.scene.cutters.get(i).map(|c| c.target) {
                    self.start_index_job(ctx, target);
                }
            }
            Action::IndexModel(target) => self.start_index_job(ctx, target),
            Action::Expose(index) => {
                if index < self.state.scene.models.len() {
                    self.apply(ctx, Action::SelectModel(Some(index)));
                    self.start_expose_job(ctx, index);
                }
            }
            Action::ExposeSelected => match self.state.selected_model {
                Some(index) => self.start_expose_job(ctx, index),
                None => self.state.say(
                    "Select a structure first (click it in the list or double-click it in the \
                     view), then press X to expose it",
                ),
            },
            Action::RemoveCutter(i) => {
                if i < self.state.scene.cutters.len() {
                    let before = self.state.scene.clone();
                    self.state.scene.cutters.remove(i);
                    self.state.viewport.editor.finish();
                    self.state
                        .record(&format!("remove cutter {}", i + 1), before);
                }
            }
            Action::RestoreRecovery => {
                if let Some(path) = self.state.pending_recovery.take() {
                    self.open_paths(ctx, vec![path], true);
                    // The restored scene lives in memory now; keep the file until the next autosave.
                }
            }
            Action::DiscardRecovery => {
                self.state.pending_recovery = None;
                self.state.recovery.discard();
            }
            Action::View(command) => {
                crate::gui::viewport::view_menu::apply(&mut self.state, command)
            }
        }
    }

    /// True when `action` would replace a scene with unsaved changes: it then waits for the
    /// answer to "save the changes first?" (`dialogs.rs` asks).
    fn asks_to_save(&mut self, action: Action) -> bool {
        if !self.state.recovery.has_unsaved() || self.state.scene.models.is_empty() {
            return false;
        }
        self.state.unsaved_prompt = Some(action);
        true
    }

    fn unsaved_answered(&mut self, ctx: &egui::Context, answer: UnsavedAnswer) {
        let Some(next) = self.state.unsaved_prompt.take() else {
            return;
        };
        match answer {
            UnsavedAnswer::Cancel => self.state.say("Kept the scene; nothing was opened"),
            UnsavedAnswer::Discard => {
                // The scene is given up: what comes next replaces it without asking again.
                self.state.recovery.mark_saved();
                self.apply(ctx, next);
            }
            UnsavedAnswer::Save => {
                self.state.after_save = Some(next);
                match self.state.session_path.clone() {
                    Some(path) => self.apply(ctx, Action::SaveSessionTo(path)),
                    None => self.open_dialog(ctx, Purpose::SaveSessionAs),
                }
            }
        }
    }

    pub(super) fn set_mode(&mut self, mode: Mode) {
        if mode == self.state.mode {
            return;
        }
        if mode == Mode::Scalpel && !crate::gui::bridge::SCALPEL_AVAILABLE {
            self.state.say("The scalpel is not available in this build");
            return;
        }
        self.state.viewport.cancel_drag();
        self.state.viewport.held = None;
        if self.state.mode == Mode::Scalpel {
            crate::gui::viewport::scalpel_mode::finish_stroke(&mut self.state);
        }
        self.state.mode = mode;
        self.state.say(format!("{} mode", mode.label()));
    }

    pub(super) fn undo(&mut self) {
        crate::gui::folder_arrival::stop_adding(&mut self.state);
        if let Some((label, before)) = self.state.pending_edit.take() {
            self.state
                .history
                .push_scene(label, before, self.state.scene.clone());
        }
        let state = match self.state.history.undo() {
            Some(Apply::Scene(state)) => Some(state.clone()),
            // Cutter edits are recorded as scene snapshots; the editor follows the scene.
            Some(Apply::Editor) | None => None,
        };
        self.apply_history_step(state, "Undone", "Nothing to undo");
    }

    pub(super) fn redo(&mut self) {
        crate::gui::folder_arrival::stop_adding(&mut self.state);
        let state = match self.state.history.redo() {
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
            self.state.say(nothing);
            return;
        };
        let (camera, render, orientation) = (
            self.state.scene.camera,
            self.state.scene.render,
            self.state.scene.orientation,
        );
        self.state.scene = state;
        self.state.scene.camera = camera;
        self.state.scene.render = render;
        self.state.scene.orientation = orientation;
        self.fix_selection();
        self.state
            .viewport
            .editor
            .sync_from_scene(&self.state.scene);
        self.state.recovery.mark_dirty();
        self.state.say(done);
    }

    pub(super) fn fix_selection(&mut self) {
        if self
            .state
            .selected_model
            .is_some_and(|i| i >= self.state.scene.models.len())
        {
            self.state.selected_model = None;
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
                actions.push(Action::Dialog(Purpose::Open));
            }
            // E for Edit, as the view's first-use hint says (F2 too).
            if i.consume_key(Modifiers::NONE, Key::E) {
                actions.push(Action::SetMode(Mode::Edit));
            }
            if i.consume_key(Modifiers::NONE, Key::X) {
                actions.push(Action::ExposeSelected);
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
        // The rule lives in `io/dropped.rs`: a session opens, the rest opens or is added.
        match crate::io::dropped::intent_of_drop(dropped, self.state.scene.models.is_empty()) {
            Some(DropIntent::Session(path)) => vec![Action::Open(vec![path])],
            Some(DropIntent::Open(paths)) => vec![Action::Open(paths)],
            Some(DropIntent::Add(paths)) => vec![Action::Add(paths)],
            None => Vec::new(),
        }
    }
}
