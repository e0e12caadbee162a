//! The eframe application: the app that owns the window's state and the layout of its panels,
//! frame by frame.
//!
//! The state the panels read and change is [`AppState`] (`state/`); what the user asks for is an
//! [`Action`] (`action.rs`) the panels return and `apply.rs` applies; background work and its
//! results are in `app_jobs.rs`, file dialogs in `dialogs.rs`. This file holds the order in
//! which a frame polls, draws and applies; imports go one way, app → panels → state.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use csg::Mesh;

use crate::cutting::editing::CutterInit;
use crate::scene::Scene;

use crate::gui::jobs;
use crate::gui::panels::status_bar::StatusInfo;
use crate::gui::state::AppState;
use crate::gui::state::viewport::ViewportState;
use crate::session::recovery::{self, RecentFiles, Recovery};
use crate::session::undo::History;

pub use crate::gui::action::{Action, Mode, Purpose, UnsavedAnswer};
pub use crate::gui::job_output::JobOutput;

/// Triangles of all models of `scene`.
pub fn triangle_count(scene: &Scene) -> usize {
    scene
        .models
        .iter()
        .map(|m| m.model.mesh.triangle_count())
        .sum()
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

/// The whole window: its state, and the frame loop that draws the panels and applies what they
/// ask for. Tests read the state through the app (`app.scene`, by `Deref`); panels only ever see
/// the [`AppState`], so they cannot call back into the app.
pub struct CutawayApp {
    pub state: AppState,
}

impl std::ops::Deref for CutawayApp {
    type Target = AppState;
    fn deref(&self) -> &AppState {
        &self.state
    }
}

impl std::ops::DerefMut for CutawayApp {
    fn deref_mut(&mut self) -> &mut AppState {
        &mut self.state
    }
}

impl CutawayApp {
    pub fn new(cc: &eframe::CreationContext<'_>, start: StartOptions) -> CutawayApp {
        crate::platform::large_blocks::return_large_blocks_to_the_system();
        crate::gui::panels::menus::apply_style(&cc.egui_ctx);
        let recovery = Recovery::new(start.state_dir.clone());
        let pending_recovery = if start.offer_recovery {
            recovery.pending()
        } else {
            None
        };
        let gpu = crate::gui::bridge::install_renderer(cc.wgpu_render_state.as_ref());
        let state = AppState {
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
            folder: Default::default(),
            recent: RecentFiles::load(&start.state_dir),
            recovery,
            session_path: None,
            status: StatusInfo {
                message: "Ready".into(),
                ..Default::default()
            },
            viewport: ViewportState::new(gpu),
            pending_recovery,
            browser: None,
            native_dialogs: crate::gui::panels::file_browser::native_dialogs_available(),
            pending_manual: None,
            export_image: Default::default(),
            export_meshes: Default::default(),
            export_turntable: Default::default(),
            export_webpage: Default::default(),
            wgpu: cc.wgpu_render_state.clone(),
            expose: Default::default(),
            metrics: Default::default(),
            ruler: Default::default(),
            compare: Default::default(),
            pending_edit: None,
            view_message_camera: None,
            layout: Default::default(),
            unsaved_prompt: None,
            after_save: None,
            last_committed: new_scene(),
            exiting: false,
            frame_started: Instant::now(),
        };
        let mut app = CutawayApp { state };
        if start.paths.is_empty() {
            app.load_default_scene(&cc.egui_ctx);
        } else {
            app.apply(&cc.egui_ctx, Action::Open(start.paths));
        }
        app
    }
}

impl eframe::App for CutawayApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let frame_ms = self.state.frame_started.elapsed().as_secs_f32() * 1000.0;
        self.state.frame_started = Instant::now();
        self.state.status.frame_ms = 0.9 * self.state.status.frame_ms + 0.1 * frame_ms;
        self.poll_jobs(&ctx);
        crate::gui::atlas_arrival::poll(&mut self.state);
        crate::gui::folder_arrival::poll(&mut self.state);
        // Pick trees of new or replaced meshes are built on a worker, not at the first press.
        self.state.viewport.picks.prepare(&self.state.scene);
        self.index_target_ahead(&ctx);

        // Keys take effect before this frame's pointer input: on a slow frame (a software
        // renderer) "E, then drag" arrives in one frame, and the drag must meet Edit mode.
        for action in self.shortcuts(&ctx) {
            self.apply(&ctx, action);
        }
        let mut actions = crate::gui::viewport::view_menu::view_shortcuts(&ctx);
        actions.extend(self.dropped_files(&ctx));

        egui::Panel::top("cutaway-menu").show(ui, |ui| {
            actions.extend(crate::gui::panels::menus::menu_bar_ui(ui, &mut self.state));
        });
        egui::Panel::top("cutaway-toolbar").show(ui, |ui| {
            actions.extend(crate::gui::panels::menus::toolbar_ui(ui, &mut self.state));
        });
        egui::Panel::bottom("cutaway-status").show(ui, |ui| {
            self.refresh_status();
            crate::gui::atlas_arrival::status_ui(ui, &mut self.state);
            crate::gui::folder_arrival::status_ui(ui, &mut self.state);
            crate::gui::panels::status_bar::status_bar_ui(ui, &self.state.status);
        });
        egui::Panel::left("cutaway-side")
            .resizable(true)
            .default_size(260.0)
            .min_size(210.0)
            .show(ui, |ui| {
                self.state.layout.models = ui.max_rect();
                actions.extend(crate::gui::panels::models_panel::models_panel_ui(
                    ui,
                    &mut self.state,
                ));
            });
        egui::Panel::right("cutaway-tools")
            .resizable(true)
            .default_size(crate::gui::panels::tools_panel::DEFAULT_WIDTH)
            .min_size(crate::gui::panels::tools_panel::MIN_WIDTH)
            .show(ui, |ui| {
                self.state.layout.tools = ui.max_rect();
                actions.extend(crate::gui::panels::tools_panel::tools_panel_ui(
                    ui,
                    &mut self.state,
                ));
            });
        if crate::gui::panels::metrics_panel::side_panel_open(&self.state) {
            egui::Panel::right("cutaway-metrics")
                .resizable(true)
                .default_size(300.0)
                .show(ui, |ui| {
                    crate::gui::panels::metrics_panel::side_panel_ui(ui, &mut self.state)
                });
        }
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                if self.state.compare.open {
                    crate::gui::panels::compare_view::compare_ui(ui, &mut self.state);
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
                        crate::gui::panels::key_reference::key_reference_ui(ui, self.state.mode);
                    });
                actions.extend(crate::gui::viewport::viewport_ui(ui, &mut self.state));
            });

        actions.extend(self.dialogs_ui(&ctx));
        if let Some((purpose, path)) = self.state.pending_manual.take() {
            self.picked(&ctx, purpose, vec![path]);
        }
        for i in jobs::progress_window_ui(&ctx, &self.state.jobs)
            .into_iter()
            .rev()
        {
            self.state.jobs[i].progress.cancel();
            let job = self.state.jobs.remove(i);
            self.state.say(format!("{}: cancelled", job.label));
        }
        for action in actions {
            self.apply(&ctx, action);
        }
        self.state.commit_edit_if_idle(&ctx);
        self.update_preview(&ctx);
        crate::gui::viewport::live_cut::update_live(&mut self.state, &ctx);
        crate::gui::risk_map::update(&mut self.state, &ctx);
        crate::gui::panels::metrics_panel::update(&mut self.state, &ctx);
        crate::gui::panels::compare_view::update(&mut self.state, &ctx);

        if !self.state.exiting && self.state.recovery.due() {
            let result = self
                .state
                .recovery
                .begin_save()
                .and_then(|path| crate::gui::bridge::save_session(&self.state, &path));
            if let Err(e) = result {
                self.state.complain(&e.context("autosave"));
            }
        }
        if self.state.busy() {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
    }

    fn on_exit(&mut self) {
        self.state.recovery.discard();
    }
}

impl CutawayApp {
    /// In Edit mode, a big selected structure's index is built on a worker before the first
    /// press on it (a press that comes first is held until it is there).
    fn index_target_ahead(&mut self, ctx: &egui::Context) {
        let Some(target) = self.state.selected_model else {
            return;
        };
        let viewport = &self.state.viewport;
        if self.state.mode != Mode::Edit
            || !viewport
                .editor
                .needs_background_index(&self.state.scene, target)
        {
            return;
        }
        if self
            .state
            .jobs
            .iter()
            .any(|j| j.is_running() && j.label.starts_with("Indexing"))
        {
            return;
        }
        let mesh = &self.state.scene.models[target].model.mesh;
        let started = viewport
            .index_ahead
            .as_ref()
            .and_then(std::sync::Weak::upgrade)
            .is_some_and(|m| std::sync::Arc::ptr_eq(&m, mesh));
        if !started {
            self.state.viewport.index_ahead = Some(std::sync::Arc::downgrade(mesh));
            self.start_index_job(ctx, target);
        }
    }

    fn refresh_status(&mut self) {
        self.state.forget_stale_view_message();
        self.state.status.models = self.state.scene.models.len();
        self.state.status.triangles = triangle_count(&self.state.scene);
        self.state.status.visible_triangles = self
            .state
            .scene
            .models
            .iter()
            .filter(|m| m.visible)
            .map(|m| m.model.mesh.triangle_count())
            .sum();
        self.state.status.cutters = self.state.scene.cutters.len();
        if self.state.mode != Mode::Preview {
            self.state.status.cut_triangles = 0;
        }
        // A cut that could not be made is said in the status bar, never drawn as something else.
        let notes = |g: Option<&crate::cutting::cut_scene::PreviewGeometry>| {
            g.and_then(|g| g.notes.first().cloned())
        };
        self.state.status.cut_problem = match self.state.mode {
            Mode::Preview => notes(self.state.viewport.preview.as_deref()),
            Mode::Edit => self
                .state
                .viewport
                .editor
                .note()
                .map(str::to_string)
                .or_else(|| {
                    notes(
                        self.state
                            .viewport
                            .live
                            .shown()
                            .map(|r| r.geometry.as_ref()),
                    )
                }),
            Mode::Camera | Mode::Scalpel => None,
        };
        self.state.status.selected = self
            .state
            .selected_model
            .and_then(|i| self.state.scene.models.get(i))
            .map(|m| m.model.name.clone());
    }
}

/// An empty scene with the window's defaults (a soft grey background instead of the export
/// default white, so light models stand out while editing).
pub fn new_scene() -> Scene {
    let mut scene = Scene::default();
    scene.render.background = [0.80, 0.83, 0.87, 1.0];
    scene
}

pub use crate::io::dropped::is_session_path;

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
