//! The eframe application: the window's state and the layout of its panels, frame by frame.
//!
//! What the user asks for is an [`Action`] (`action.rs`), background work and its results are in
//! `app_jobs.rs`, file dialogs in `dialogs.rs`; this file holds the state they share and the
//! order in which a frame polls, draws and applies.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use csg::Mesh;

use crate::cutting::editing::CutterInit;
use crate::scene::Scene;

use super::jobs::{self, Job};
use super::recovery::{self, RecentFiles, Recovery};
use super::status_bar::StatusInfo;
use super::undo::History;
use super::viewport::ViewportState;

pub use super::action::{Action, Mode, Purpose};
pub use super::app_jobs::{JobOutput, load_paths};

/// Triangles of all models of `scene`.
pub fn triangle_count(scene: &Scene) -> usize {
    scene.models.iter().map(|m| m.mesh.triangle_count()).sum()
}

/// How the app starts.
#[derive(Clone, Debug)]
pub struct StartOptions {
    /// Meshes, directories, or one session file. Empty: the embedded default scene.
    pub paths: Vec<PathBuf>,
    /// Folder of the recovery autosave and recent files (see [`recovery::state_dir`]).
    pub state_dir: PathBuf,
    /// Offer an autosave left behind by a crash.
    pub offer_recovery: bool,
}

impl StartOptions {
    /// Files named on the command line are what the user wants to see: no recovery prompt then
    /// (the autosave stays on disk until the next autosave replaces it).
    pub fn new(paths: Vec<PathBuf>) -> StartOptions {
        StartOptions {
            offer_recovery: paths.is_empty(),
            paths,
            state_dir: recovery::state_dir(),
        }
    }
}

/// The whole window.
pub struct CutawayApp {
    /// Models, cutters, camera and render settings: what is drawn and saved.
    pub scene: Scene,
    pub mode: Mode,
    pub cutter_init: CutterInit,
    /// Index into `scene.models` of the selected (target) model.
    pub selected_model: Option<usize>,
    /// Index of the cutter whose Visualization settings are shown.
    pub selected_cutter: usize,
    /// "Hide/Show Current Cutters": the first `hidden_cutters` scene cutters are hidden (those
    /// that existed when the user hid them; cutters made afterwards show).
    pub cutters_hidden: bool,
    pub hidden_cutters: usize,
    /// Undo snapshots are whole scenes (meshes shared); the camera is not part of undo.
    pub history: History<Scene>,
    pub jobs: Vec<Job<JobOutput>>,
    /// The default scene's label surfaces while they arrive after its first frame.
    pub atlas: super::atlas_arrival::AtlasArrival,
    pub recovery: Recovery,
    pub recent: RecentFiles,
    /// Where "Save Session" writes; set by Open Session and Save Session As.
    pub session_path: Option<PathBuf>,
    pub status: StatusInfo,
    pub viewport: ViewportState,
    /// A recovery file found at start-up, offered until answered.
    pub pending_recovery: Option<PathBuf>,
    /// The in-window file browser, open when no native file dialog is available.
    pub browser: Option<super::file_browser::FileBrowser>,
    /// A native file dialog can open (see [`super::file_browser::native_dialogs_available`]).
    pub native_dialogs: bool,
    /// What the in-window browser picked, handled after the frame's panels.
    pub(super) pending_manual: Option<(Purpose, PathBuf)>,
    /// Export Image settings (width, height, transparent background).
    pub export_image: super::menus::ExportImageSettings,
    /// Which cut parts Export Cut Meshes writes, and the format.
    pub export_meshes: super::menus::ExportMeshSettings,
    /// Export Turntable settings (frames, frame size, GIF).
    pub export_turntable: super::turntable_export::TurntableSettings,
    /// The GPU, when the window runs on wgpu (None under a non-wgpu test harness).
    pub wgpu: Option<egui_wgpu::RenderState>,
    /// Which cutter tab is shown.
    pub cutter_tab: super::cutter_panel::CutterTab,
    /// The Metrics panel, the Ruler tool and the Compare view.
    pub metrics: super::metrics_panel::MetricsPanel,
    pub ruler: super::ruler::RulerTool,
    pub compare: super::compare_view::CompareView,
    /// The scene as of the last committed undo step (the "before" of editor-made changes).
    pub(super) last_committed: Scene,
    /// A scene edit in progress (slider or colour drag): its label and the scene before it.
    /// Committed to the history when the pointer is released.
    pub(super) pending_edit: Option<(String, Scene)>,
    /// True once a close was requested (Exit); the recovery file is removed then.
    pub(super) exiting: bool,
    pub(super) frame_started: Instant,
}

impl CutawayApp {
    pub fn new(cc: &eframe::CreationContext<'_>, start: StartOptions) -> CutawayApp {
        crate::large_blocks::return_large_blocks_to_the_system();
        super::menus::apply_style(&cc.egui_ctx);
        let recovery = Recovery::new(start.state_dir.clone());
        let pending_recovery = if start.offer_recovery {
            recovery.pending()
        } else {
            None
        };
        let mut app = CutawayApp {
            scene: new_scene(),
            mode: Mode::Camera,
            cutter_init: CutterInit::default(),
            selected_model: None,
            selected_cutter: 0,
            cutters_hidden: false,
            hidden_cutters: 0,
            history: History::default(),
            jobs: Vec::new(),
            atlas: Default::default(),
            recent: RecentFiles::load(&start.state_dir),
            recovery,
            session_path: None,
            status: StatusInfo {
                message: "Ready".into(),
                ..Default::default()
            },
            viewport: ViewportState::new(cc.wgpu_render_state.as_ref()),
            pending_recovery,
            browser: None,
            native_dialogs: super::file_browser::native_dialogs_available(),
            pending_manual: None,
            export_image: Default::default(),
            export_meshes: Default::default(),
            export_turntable: Default::default(),
            wgpu: cc.wgpu_render_state.clone(),
            cutter_tab: Default::default(),
            metrics: Default::default(),
            ruler: Default::default(),
            compare: Default::default(),
            pending_edit: None,
            last_committed: new_scene(),
            exiting: false,
            frame_started: Instant::now(),
        };
        if start.paths.is_empty() {
            app.load_default_scene(&cc.egui_ctx);
        } else {
            app.apply(&cc.egui_ctx, Action::Open(start.paths));
        }
        app
    }

    /// True while any background job runs (tests wait on this).
    pub fn busy(&self) -> bool {
        self.jobs.iter().any(Job::is_running)
            || self.metrics.busy()
            || self.compare.busy()
            || self.atlas.busy()
    }

    /// Every scene this window holds: the current one, the last committed, the one before a
    /// pending edit, and the undo history's snapshots.
    pub(super) fn scenes_mut(&mut self) -> impl Iterator<Item = &mut Scene> {
        let pending = self.pending_edit.as_mut().map(|(_, scene)| scene);
        [&mut self.scene, &mut self.last_committed]
            .into_iter()
            .chain(pending)
            .chain(self.history.scenes_mut())
    }

    /// Sets the status message.
    pub fn say(&mut self, message: impl Into<String>) {
        self.status.message = message.into();
        self.status.is_error = false;
    }

    /// Sets an error message (one line, kept until the next message).
    pub fn complain(&mut self, error: &anyhow::Error) {
        self.status.message = crate::errors::error_line(error);
        self.status.is_error = true;
    }

    /// Records a scene change for undo (call with the state from before the change).
    pub fn record(&mut self, label: &str, before: Scene) {
        if let Some((pending_label, pending_before)) = self.pending_edit.take() {
            self.history
                .push_scene(pending_label, pending_before, before.clone());
        }
        self.history.push_scene(label, before, self.scene.clone());
        self.last_committed = self.scene.clone();
        self.recovery.mark_dirty();
    }

    /// Starts (or continues) an undoable property edit: call before changing the scene.
    pub fn begin_edit(&mut self, label: &str) {
        if self.pending_edit.is_none() {
            self.pending_edit = Some((label.to_string(), self.scene.clone()));
        }
        self.recovery.mark_dirty();
    }

    /// Commits the pending property edit once no pointer button is held (one step per drag).
    fn commit_edit_if_idle(&mut self, ctx: &egui::Context) {
        if self.pending_edit.is_some()
            && !ctx.input(|i| i.pointer.any_down())
            && let Some((label, before)) = self.pending_edit.take()
        {
            self.history.push_scene(label, before, self.scene.clone());
        }
        if self.pending_edit.is_none() {
            self.last_committed = self.scene.clone();
        }
    }

    /// The editor changed the scene's cutters: one undo step per drag (committed on release).
    pub fn cutters_changed(&mut self) {
        if self.pending_edit.is_none() {
            // `begin_edit` must see the scene before the change; the editor already changed it,
            // so the snapshot taken at the previous frame end is used.
            self.pending_edit = Some(("cutter edit".to_string(), self.last_committed.clone()));
        }
        self.recovery.mark_dirty();
    }

    /// The Initialization tab changed: the active cutter follows (smoothing is an edit).
    pub fn cutter_settings_changed(&mut self) {
        let before = self.scene.clone();
        if self
            .viewport
            .editor
            .apply_settings(&mut self.scene, &self.cutter_init)
        {
            self.record("smoothing change", before);
        }
    }
}

impl eframe::App for CutawayApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let frame_ms = self.frame_started.elapsed().as_secs_f32() * 1000.0;
        self.frame_started = Instant::now();
        self.status.frame_ms = 0.9 * self.status.frame_ms + 0.1 * frame_ms;
        self.poll_jobs(&ctx);
        super::atlas_arrival::poll(self);
        // Pick trees of new or replaced meshes are built on a worker, not at the first press.
        self.viewport.picks.prepare(&self.scene);

        let mut actions = self.shortcuts(&ctx);
        actions.extend(super::view_menu::view_shortcuts(&ctx));
        actions.extend(self.dropped_files(&ctx));

        egui::Panel::top("cutaway-menu").show(ui, |ui| {
            actions.extend(super::menus::menu_bar_ui(ui, self));
        });
        egui::Panel::top("cutaway-toolbar").show(ui, |ui| {
            actions.extend(super::menus::toolbar_ui(ui, self));
        });
        egui::Panel::bottom("cutaway-status").show(ui, |ui| {
            self.refresh_status();
            super::atlas_arrival::status_ui(ui, self);
            super::status_bar::status_bar_ui(ui, &self.status);
        });
        egui::Panel::left("cutaway-side")
            .resizable(true)
            .default_size(290.0)
            .min_size(230.0)
            .show(ui, |ui| {
                // Both ways: a wide row (a long name, a note) scrolls instead of widening the
                // panel, so the view keeps the width the user gave it.
                egui::ScrollArea::both().show(ui, |ui| {
                    actions.extend(super::models_panel::models_panel_ui(ui, self));
                    ui.add_space(10.0);
                    actions.extend(super::cutter_panel::cutter_panel_ui(ui, self));
                    super::image_panel::image_panel_ui(ui, self);
                    if self.mode == Mode::Scalpel {
                        ui.add_space(10.0);
                        super::scalpel_mode::scalpel_panel_ui(ui, self);
                    }
                });
            });
        if super::metrics_panel::side_panel_open(self) {
            egui::Panel::right("cutaway-metrics")
                .resizable(true)
                .default_size(300.0)
                .show(ui, |ui| super::metrics_panel::side_panel_ui(ui, self));
        }
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                if self.compare.open {
                    super::compare_view::compare_ui(ui, self);
                    return;
                }
                // No gap between the strip and the view (the window's clear colour showed there).
                ui.spacing_mut().item_spacing.y = 0.0;
                // Its own panel-coloured strip, so the reference never sits on the 3D view.
                egui::Frame::NONE
                    .fill(ui.visuals().panel_fill)
                    .inner_margin(egui::Margin::symmetric(8, 4))
                    .show(ui, |ui| {
                        ui.set_width(ui.available_width());
                        super::key_reference::key_reference_ui(ui, self.mode);
                    });
                actions.extend(super::viewport::viewport_ui(ui, self));
            });

        actions.extend(self.dialogs_ui(&ctx));
        if let Some((purpose, path)) = self.pending_manual.take() {
            self.picked(&ctx, purpose, vec![path]);
        }
        for i in jobs::progress_window_ui(&ctx, &self.jobs).into_iter().rev() {
            self.jobs[i].progress.cancel();
            let job = self.jobs.remove(i);
            self.say(format!("{}: cancelled", job.label));
        }
        for action in actions {
            self.apply(&ctx, action);
        }
        self.commit_edit_if_idle(&ctx);
        self.update_preview(&ctx);
        super::live_cut::update_live(self, &ctx);
        super::metrics_panel::update(self, &ctx);
        super::compare_view::update(self, &ctx);

        if !self.exiting && self.recovery.due() {
            let result = self
                .recovery
                .begin_save()
                .and_then(|path| super::bridge::save_session(self, &path));
            if let Err(e) = result {
                self.complain(&e.context("autosave"));
            }
        }
        if self.busy() {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
    }

    fn on_exit(&mut self) {
        self.recovery.discard();
    }
}

impl CutawayApp {
    fn refresh_status(&mut self) {
        self.status.models = self.scene.models.len();
        self.status.triangles = triangle_count(&self.scene);
        self.status.visible_triangles = self
            .scene
            .models
            .iter()
            .filter(|m| m.visible)
            .map(|m| m.mesh.triangle_count())
            .sum();
        self.status.cutters = self.scene.cutters.len();
        if self.mode != Mode::Preview {
            self.status.cut_triangles = 0;
        }
        // A cut that could not be made is said in the status bar, never drawn as something else.
        let notes = |g: Option<&crate::cutting::cut_scene::PreviewGeometry>| {
            g.and_then(|g| g.notes.first().cloned())
        };
        self.status.cut_problem = match self.mode {
            Mode::Preview => notes(self.viewport.preview.as_deref()),
            Mode::Edit => self
                .viewport
                .editor
                .note()
                .map(str::to_string)
                .or_else(|| notes(self.viewport.live.shown().map(|r| r.geometry.as_ref()))),
            Mode::Camera | Mode::Scalpel => None,
        };
        self.status.selected = self
            .selected_model
            .and_then(|i| self.scene.models.get(i))
            .map(|m| m.name.clone());
    }
}

/// An empty scene with the window's defaults (a soft grey background instead of the export
/// default white, so light models stand out while editing).
pub fn new_scene() -> Scene {
    let mut scene = Scene::default();
    scene.render.background = [0.80, 0.83, 0.87, 1.0];
    scene
}

pub use crate::dropped::is_session_path;

/// A small mesh for tests of the window's state handling: a closed box.
pub fn box_mesh(min: DVec3, max: DVec3) -> Mesh {
    let p = |x: bool, y: bool, z: bool| {
        DVec3::new(
            if x { max.x } else { min.x },
            if y { max.y } else { min.y },
            if z { max.z } else { min.z },
        )
    };
    let positions = vec![
        p(false, false, false),
        p(true, false, false),
        p(true, true, false),
        p(false, true, false),
        p(false, false, true),
        p(true, false, true),
        p(true, true, true),
        p(false, true, true),
    ];
    let triangles = vec![
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    Mesh {
        positions,
        triangles,
    }
}
