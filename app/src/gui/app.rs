//! The eframe application: window state, actions, jobs, and the layout of the panels.
//!
//! Every user command (menu item, button, shortcut, context menu, dropped file) becomes an
//! [`Action`] applied in one place ([`CutawayApp::apply`]), so the menus and panels only describe
//! what the user asked for and the undo history sees every scene change.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;

use csg::Mesh;

use crate::scene::{CutKind, Scene, SceneModel};

use super::camera_controls;
use super::jobs::{self, Job, Progress};
use super::recovery::{self, RecentFiles, Recovery};
use super::status_bar::StatusInfo;
use super::undo::{Apply, History};
use super::viewport::ViewportState;
use crate::dropped::DropIntent;

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

/// Cut settings applied to the next cutter (thesis 3.5 E, Initialization tab).
#[derive(Clone, Debug, PartialEq)]
pub struct CutterInit {
    /// Segment spacing ω: a new box starts each ω·δ of extrusion.
    pub spacing: f64,
    /// Curving (freeform path) or wedge; Shift while extruding gives the straight path.
    pub kind: CutKind,
    /// Rounded (subdivided) cutter.
    pub smooth: bool,
}

impl Default for CutterInit {
    fn default() -> Self {
        CutterInit {
            spacing: 20.0,
            kind: CutKind::Curving,
            smooth: false,
        }
    }
}

/// Triangles of all models of `scene`.
pub fn triangle_count(scene: &Scene) -> usize {
    scene.models.iter().map(|m| m.mesh.triangle_count()).sum()
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

/// Result of a background job.
pub enum JobOutput {
    /// A file dialog closed; `paths` is empty when it was cancelled.
    Picked {
        purpose: Purpose,
        paths: Vec<PathBuf>,
        took: std::time::Duration,
    },
    /// Models were read.
    Models {
        models: Vec<crate::io::Model>,
        replace: bool,
        sources: Vec<PathBuf>,
        /// A volume among the files that holds an intensity image, not labels.
        image: Option<crate::intensity::ImageLayer>,
    },
    /// A session was read (models included).
    Session { path: PathBuf, scene: Box<Scene> },
    /// An intensity image was read, to show on the walls.
    Image(crate::intensity::ImageLayer),
    /// A target's spatial index was built.
    Index {
        model: usize,
        mesh: std::sync::Weak<csg::Mesh>,
        index: Arc<csg::SpatialIndex>,
    },
    /// Preview cut parts for the scene state `key`, and the wall time of the cut in ms.
    Preview {
        geometry: Arc<crate::cutaway_geometry::PreviewGeometry>,
        key: super::bridge::PreviewKey,
        ms: f64,
    },
    /// "Remove All Cut Geometry": new meshes for the cut models, for the scene state `key`.
    CutsApplied {
        meshes: Vec<(usize, Arc<csg::Mesh>)>,
        key: super::bridge::PreviewKey,
    },
    /// Something finished that only needs a message.
    Done(String),
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
    pending_manual: Option<(Purpose, PathBuf)>,
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
    last_committed: Scene,
    /// A scene edit in progress (slider or colour drag): its label and the scene before it.
    /// Committed to the history when the pointer is released.
    pending_edit: Option<(String, Scene)>,
    /// True once a close was requested (Exit); the recovery file is removed then.
    exiting: bool,
    frame_started: Instant,
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

    fn spawn(
        &mut self,
        ctx: &egui::Context,
        label: impl Into<String>,
        work: impl FnOnce(&Progress) -> anyhow::Result<JobOutput> + Send + 'static,
    ) {
        let ctx = ctx.clone();
        self.jobs
            .push(Job::spawn(label, move || ctx.request_repaint(), work));
    }

    /// The skin at once (milliseconds), the atlas's labels from a background job.
    fn load_default_scene(&mut self, ctx: &egui::Context) {
        match crate::default_anatomy::load_skin() {
            Ok(skin) => self.add_models(skin, true, &[]),
            Err(e) => return self.complain(&e),
        }
        self.atlas.start(ctx);
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

    fn load_example(&mut self, ctx: &egui::Context, name: String) {
        if name == crate::default_anatomy::NAME {
            return self.load_default_scene(ctx);
        }
        self.spawn(
            ctx,
            format!("Loading the {name} example"),
            move |progress| {
                let models = super::bridge::example_scene_models(&name, progress)?;
                Ok(JobOutput::Models {
                    models,
                    replace: true,
                    sources: Vec::new(),
                    image: None,
                })
            },
        );
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

    fn set_mode(&mut self, mode: Mode) {
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

    fn undo(&mut self) {
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

    fn redo(&mut self) {
        let state = match self.history.redo() {
            Some(Apply::Scene(state)) => Some(state.clone()),
            Some(Apply::Editor) | None => None,
        };
        self.apply_history_step(state, "Redone", "Nothing to redo");
    }

    /// Puts the scene state of an undo/redo step into effect (the editor follows the scene); the
    /// camera, the Rendering settings (anaglyph, background) and the orientation are views, not
    /// edits, and stay as they are: an undo must not turn anaglyph back on.
    fn apply_history_step(&mut self, state: Option<Scene>, done: &str, nothing: &str) {
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

    fn fix_selection(&mut self) {
        if self
            .selected_model
            .is_some_and(|i| i >= self.scene.models.len())
        {
            self.selected_model = None;
        }
    }

    fn remove_all_cut_geometry(&mut self, ctx: &egui::Context) {
        if self.scene.cutters.is_empty() {
            self.say("There are no cutters to apply");
            return;
        }
        let scene = self.scene.clone();
        let key = super::bridge::PreviewKey::of(&scene);
        self.spawn(ctx, "Removing all cut geometry", move |progress| {
            let meshes = super::bridge::apply_all_cuts(&scene, progress)?;
            Ok(JobOutput::CutsApplied { meshes, key })
        });
    }

    /// Starts building the spatial index of model `target` in the background (big targets).
    pub fn start_index_job(&mut self, ctx: &egui::Context, target: usize) {
        let Some(model) = self.scene.models.get(target) else {
            return;
        };
        if self.jobs.iter().any(|j| j.label.starts_with("Indexing")) {
            return;
        }
        let mesh = model.mesh.clone();
        let name = model.name.clone();
        self.say(format!("Indexing {name} for editing…"));
        self.spawn(ctx, format!("Indexing {name}"), move |progress| {
            let (weak, index) = super::bridge::build_index(&mesh, progress)?;
            Ok(JobOutput::Index {
                model: target,
                mesh: weak,
                index,
            })
        });
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

    fn open_dialog(&mut self, ctx: &egui::Context, purpose: Purpose) {
        let start_dir = self
            .session_path
            .as_ref()
            .and_then(|p| p.parent().map(Path::to_path_buf))
            .or_else(|| {
                self.recent
                    .paths
                    .first()
                    .and_then(|p| p.parent().map(Path::to_path_buf))
            });
        if !self.native_dialogs {
            self.browser = Some(super::file_browser::FileBrowser::new(purpose, start_dir));
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
            let paths: Vec<PathBuf> = pollster::block_on(async move {
                match purpose {
                    Purpose::LoadModel | Purpose::AddModel => dialog
                        .add_filter("Meshes", &meshes)
                        .add_filter("Label volumes", &volumes)
                        .add_filter("Session", &["json"])
                        .pick_files()
                        .await
                        .map(|files| files.iter().map(|f| f.path().to_path_buf()).collect())
                        .unwrap_or_default(),
                    Purpose::LoadDirectory | Purpose::ExportMeshes | Purpose::ExportTurntable => {
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
                    Purpose::OpenSession => dialog
                        .add_filter("Cutaway session", &["json"])
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

    /// What happens once a dialog (native or manual) gave paths.
    fn picked(&mut self, ctx: &egui::Context, purpose: Purpose, paths: Vec<PathBuf>) {
        let Some(first) = paths.first().cloned() else {
            return;
        };
        match purpose {
            Purpose::LoadModel | Purpose::LoadDirectory => self.apply(ctx, Action::Open(paths)),
            Purpose::AddModel => self.apply(ctx, Action::Add(paths)),
            Purpose::OpenSession => self.apply(ctx, Action::Open(vec![first])),
            Purpose::SaveSessionAs => {
                self.apply(ctx, Action::SaveSessionTo(with_extension(first, "json")))
            }
            Purpose::ExportImage => {
                self.apply(ctx, Action::ExportImageTo(with_extension(first, "png")))
            }
            Purpose::ExportMeshes => self.apply(ctx, Action::ExportMeshesTo(first)),
            Purpose::ExportTurntable => self.apply(ctx, Action::ExportTurntableTo(first)),
            Purpose::OpenImage => self.apply(ctx, Action::OpenImage(first)),
            Purpose::SaveGesture => {
                let path = with_extension(first, "json");
                match self.viewport.save_recording(&path) {
                    Ok(n) => self.say(format!("Saved gesture of {n} events to {}", path.display())),
                    Err(e) => self.complain(&e),
                }
            }
        }
    }

    /// Opens files: a session replaces everything; meshes and directories load in the background.
    fn open_paths(&mut self, ctx: &egui::Context, paths: Vec<PathBuf>, replace: bool) {
        if paths.is_empty() {
            return;
        }
        if paths.len() == 1 && is_session_path(&paths[0]) {
            let path = paths[0].clone();
            self.load_session(ctx, &path);
            return;
        }
        for p in &paths {
            self.recent.add(p);
        }
        let label = match paths.as_slice() {
            [one] => format!("Loading {}", file_label(one)),
            many => format!("Loading {} items", many.len()),
        };
        let sources = paths.clone();
        self.spawn(ctx, label, move |progress| {
            let (models, image) = load_paths(&paths, progress)?;
            Ok(JobOutput::Models {
                models,
                replace,
                sources,
                image,
            })
        });
    }

    fn finish_job(&mut self, ctx: &egui::Context, output: JobOutput) {
        match output {
            JobOutput::Picked {
                purpose,
                paths,
                took,
            } => {
                // A dialog that "closes" within a blink never opened: no portal and no zenity.
                if paths.is_empty() && took < std::time::Duration::from_millis(150) {
                    self.browser = Some(super::file_browser::FileBrowser::new(purpose, None));
                    self.say("No native file dialog opened; choose in the window's browser");
                } else {
                    self.picked(ctx, purpose, paths);
                }
            }
            JobOutput::Models {
                models,
                replace,
                sources,
                image,
            } => {
                let image = image.or_else(|| super::image_panel::image_kept(self, replace));
                self.add_models(models, replace, &sources);
                if let Some(layer) = image {
                    super::image_panel::image_loaded(self, layer);
                }
            }
            JobOutput::Session { path, scene } => {
                self.atlas.cancel();
                self.scene = *scene;
                // A restored autosave has no file of its own: Save asks where to put it.
                let restored = path == self.recovery.session_path();
                self.session_path = (!restored).then(|| path.clone());
                self.selected_model = None;
                self.selected_cutter = 0;
                self.history.clear();
                self.viewport.reset_editor();
                self.last_committed = self.scene.clone();
                self.recovery.mark_dirty();
                if !restored {
                    self.recent.add(&path);
                }
                self.say(format!(
                    "Opened {}: {} models, {} cutters",
                    path.display(),
                    self.scene.models.len(),
                    self.scene.cutters.len()
                ));
            }
            JobOutput::Image(layer) => super::image_panel::image_loaded(self, layer),
            JobOutput::Index { model, mesh, index } => {
                self.viewport.editor.store_index(mesh, index);
                self.say(format!(
                    "{} is ready: drag on it to start a cutter",
                    self.scene
                        .models
                        .get(model)
                        .map(|m| m.name.as_str())
                        .unwrap_or("the target")
                ));
            }
            JobOutput::Preview { geometry, key, ms } => {
                if key == super::bridge::PreviewKey::of(&self.scene) {
                    self.status.last_cut_ms = Some(ms);
                    self.status.cut_triangles = geometry.triangle_count();
                    self.viewport.preview = Some(geometry);
                    self.viewport.preview_key = Some(key);
                }
            }
            JobOutput::CutsApplied { meshes, key } => {
                if key != super::bridge::PreviewKey::of(&self.scene) {
                    self.say("The cutters changed while cutting; Remove All Cut Geometry was not applied");
                    return;
                }
                let before = self.scene.clone();
                let count = meshes.len();
                for (i, mesh) in meshes {
                    if let Some(m) = self.scene.models.get_mut(i) {
                        m.replace_mesh(mesh);
                    }
                }
                self.scene.cutters.clear();
                self.viewport.editor.finish();
                self.viewport.preview = None;
                self.viewport.preview_key = None;
                self.record("remove all cut geometry", before);
                self.say(format!(
                    "Applied the cuts to {count} models; new cuts reach the structures behind"
                ));
            }
            JobOutput::Done(message) => self.say(message),
        }
    }

    fn add_models(&mut self, models: Vec<crate::io::Model>, replace: bool, sources: &[PathBuf]) {
        let before = self.scene.clone();
        if replace {
            self.atlas.cancel();
            let render = self.scene.render;
            self.scene = new_scene();
            self.scene.render = render;
            self.session_path = None;
            self.selected_model = None;
            self.history.clear();
            self.viewport.reset_editor();
        }
        let first_new = self.scene.models.len();
        let count = models.len();
        let default_scene = crate::default_anatomy::is_default_scene(&models);
        let from_volume = sources.iter().any(|p| crate::io::volume::is_volume(p));
        for (i, model) in models.into_iter().enumerate() {
            let color =
                crate::anatomy_colors::structure_color(&model.name, model.color, first_new + i);
            self.scene.models.push(SceneModel::structure(model, color));
        }
        if replace {
            super::view_menu::orient_new_scene(self, default_scene, from_volume);
            self.last_committed = self.scene.clone();
            self.recovery.mark_dirty();
        } else {
            self.record(&format!("add {count} models"), before);
        }
        let what = match sources {
            [] => "the example scene".to_string(),
            [one] => file_label(one),
            many => format!("{} items", many.len()),
        };
        self.say(format!(
            "Loaded {what}: {count} models, {} triangles",
            super::status_bar::grouped(triangle_count(&self.scene))
        ));
    }

    fn save_session(&mut self, path: &Path) -> anyhow::Result<()> {
        super::bridge::save_session(self, path)
    }

    fn load_session(&mut self, ctx: &egui::Context, path: &Path) {
        let path = path.to_path_buf();
        self.spawn(
            ctx,
            format!("Opening {}", file_label(&path)),
            move |progress| {
                let scene = super::bridge::load_session(&path, progress)?;
                Ok(JobOutput::Session {
                    path,
                    scene: Box::new(scene),
                })
            },
        );
    }

    fn export_image_to(&mut self, ctx: &egui::Context, path: PathBuf) {
        let scene = self.scene.clone();
        // Camera and Scalpel modes show the cut too: the picture shows it as well.
        let preview = super::cut_view::shows_cut(self.mode) && !self.scene.cutters.is_empty();
        let settings = self.export_image.clone();
        self.spawn(
            ctx,
            format!("Exporting {}×{} image", settings.width, settings.height),
            move |progress| {
                progress.set_message(file_label(&path));
                Ok(JobOutput::Done(super::bridge::export_image(
                    &scene, preview, &settings, &path,
                )?))
            },
        );
    }

    fn export_meshes_to(&mut self, ctx: &egui::Context, dir: PathBuf) {
        let scene = self.scene.clone();
        let settings = self.export_meshes.clone();
        self.spawn(ctx, "Exporting cut meshes", move |progress| {
            let files = super::bridge::export_meshes(&scene, &settings, &dir, progress)?;
            Ok(JobOutput::Done(format!(
                "Exported {} meshes to {}",
                files.len(),
                dir.display()
            )))
        });
    }

    fn export_turntable_to(&mut self, ctx: &egui::Context, dir: PathBuf) {
        let scene = self.scene.clone();
        let preview = super::cut_view::shows_cut(self.mode) && !self.scene.cutters.is_empty();
        let settings = self.export_turntable.clone();
        let label = format!(
            "Exporting a turntable of {} frames",
            settings.options.frames
        );
        self.spawn(ctx, label, move |progress| {
            let message =
                super::turntable_export::export(&scene, preview, &settings, &dir, progress)?;
            Ok(JobOutput::Done(message))
        });
    }

    /// In Preview, recompute the cut parts whenever the cutters or their targets changed.
    fn update_preview(&mut self, ctx: &egui::Context) {
        if !super::cut_view::shows_cut(self.mode) || self.scene.cutters.is_empty() {
            return;
        }
        let key = super::bridge::PreviewKey::of(&self.scene);
        if self.viewport.preview_key.as_ref() == Some(&key)
            || self.jobs.iter().any(|j| j.label == PREVIEW_JOB)
        {
            return;
        }
        let scene = self.scene.clone();
        self.spawn(ctx, PREVIEW_JOB, move |_| {
            let (geometry, ms) = super::bridge::compute_preview(&scene);
            Ok(JobOutput::Preview { geometry, key, ms })
        });
    }

    fn poll_jobs(&mut self, ctx: &egui::Context) {
        let mut finished = Vec::new();
        for job in &mut self.jobs {
            if let Some(result) = job.poll() {
                finished.push((job.label.clone(), result));
            }
        }
        self.jobs.retain(Job::is_running);
        for (label, result) in finished {
            match result {
                Ok(output) => self.finish_job(ctx, output),
                Err(e) if jobs::is_cancelled(&e) => self.say(format!("{label}: cancelled")),
                Err(e) => self.complain(&e),
            }
        }
    }

    fn shortcuts(&mut self, ctx: &egui::Context) -> Vec<Action> {
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

    fn dropped_files(&mut self, ctx: &egui::Context) -> Vec<Action> {
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

    fn dialogs_ui(&mut self, ctx: &egui::Context) -> Vec<Action> {
        let mut actions = Vec::new();
        if let Some(path) = self.pending_recovery.clone() {
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
        if let Some(browser) = &mut self.browser
            && let Some(paths) = browser.ui(ctx)
        {
            let purpose = browser.purpose;
            self.browser = None;
            if let Some(path) = paths.into_iter().next() {
                self.pending_manual = Some((purpose, path));
            }
        }
        actions
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
        let notes = |g: Option<&crate::cutaway_geometry::PreviewGeometry>| {
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

/// Label of the preview job (at most one runs).
const PREVIEW_JOB: &str = "Cutting (Preview)";

pub use crate::dropped::is_session_path;

fn with_extension(path: PathBuf, ext: &str) -> PathBuf {
    if path.extension().is_some() {
        path
    } else {
        path.with_extension(ext)
    }
}

fn file_label(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Reads files and folders (recursively) as structures, one file at a time, reporting progress
/// per file and stopping between files when cancelled. A folder's files are grouped by the
/// folders between it and them, its own name first. A volume file whose values are not labels
/// becomes the scene's image.
pub fn load_paths(
    paths: &[PathBuf],
    progress: &Progress,
) -> anyhow::Result<(Vec<crate::io::Model>, Option<crate::intensity::ImageLayer>)> {
    let mut files: Vec<(PathBuf, String)> = Vec::new();
    for path in paths {
        if path.is_dir() {
            let found = crate::io::mesh_files(path)?;
            if found.is_empty() {
                anyhow::bail!(
                    "{}: no .obj, .stl, .ply or .vtk files in this folder",
                    path.display()
                );
            }
            let root = path.parent().unwrap_or(Path::new(""));
            files.extend(found.into_iter().map(|f| {
                let group = crate::io::group_of(&f, root);
                (f, group)
            }));
        } else {
            files.push((path.clone(), String::new()));
        }
    }
    let mut models = Vec::new();
    let mut image = None;
    // Per mille of each file, so a volume's label surfacing moves the bar within its file.
    let total = files.len() as u64 * 1000;
    for (i, (file, group)) in files.iter().enumerate() {
        progress.check()?;
        let start = i as u64 * 1000;
        progress.set(start, total);
        progress.set_message(file_label(file));
        let surfacing = |fraction: f32| {
            progress.set(start + (fraction.clamp(0.0, 1.0) * 1000.0) as u64, total);
            !progress.is_cancelled()
        };
        crate::intensity::open::read_file_into(file, group, &mut models, &mut image, &surfacing)?;
    }
    progress.set(total, total);
    Ok((models, image))
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_paths_names_an_empty_folder() {
        let dir = std::env::temp_dir().join(format!("cutaway-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let err = load_paths(std::slice::from_ref(&dir), &Progress::default()).unwrap_err();
        assert!(format!("{err:#}").contains(&dir.display().to_string()));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
