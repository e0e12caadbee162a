//! The window's state: what the panels read and change, owned by the app (`gui/app.rs`).
//!
//! Imports go one way: the app owns an [`AppState`] and calls the panels; the panels take the
//! state (or parts of it) and return [`crate::gui::action::Action`]s for what only the app can do
//! (jobs, dialogs, opening files); this module imports no panel. The state of a panel that has
//! more than a few fields lives in a file of its own here.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use crate::cutting::editing::CutterInit;
use crate::gui::action::{Mode, Purpose};
use crate::gui::job_output::JobOutput;
use crate::gui::jobs::Job;
use crate::gui::panels::status_bar::StatusInfo;
use crate::scene::Scene;
use crate::session::recovery::{RecentFiles, Recovery};
use crate::session::undo::History;

pub mod atlas;
pub mod compare;
pub mod export_settings;
pub mod folder;
pub mod metrics;
pub mod viewport;

use viewport::ViewportState;

/// The whole window's state.
pub struct AppState {
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
    pub atlas: atlas::AtlasArrival,
    /// A folder of masks while its structures arrive, shown as they come.
    pub folder: folder::FolderArrival,
    pub recovery: Recovery,
    pub recent: RecentFiles,
    /// Where "Save Session" writes; set by opening a session and by Save Session As.
    pub session_path: Option<PathBuf>,
    pub status: StatusInfo,
    pub viewport: ViewportState,
    /// A recovery file found at start-up, offered until answered.
    pub pending_recovery: Option<PathBuf>,
    /// The in-window file browser, open when no native file dialog is available.
    pub browser: Option<crate::gui::panels::file_browser::FileBrowser>,
    /// A native file dialog can open (see `file_browser::native_dialogs_available`).
    pub native_dialogs: bool,
    /// What the in-window browser picked, handled after the frame's panels.
    pub(super) pending_manual: Option<(Purpose, PathBuf)>,
    /// Export Image settings (width, height, transparent background).
    pub export_image: export_settings::ExportImageSettings,
    /// Which cut parts Export Cut Meshes writes, and the format.
    pub export_meshes: export_settings::ExportMeshSettings,
    /// Export Turntable settings (frames, frame size, GIF).
    pub export_turntable: export_settings::TurntableSettings,
    /// Export Web Page settings (title).
    pub export_webpage: export_settings::WebPageSettings,
    /// The GPU, when the window runs on wgpu (None under a non-wgpu test harness).
    pub wgpu: Option<egui_wgpu::RenderState>,
    /// The margin Expose leaves around a structure's silhouette.
    pub expose: crate::expose::ExposeSettings,
    /// The Metrics panel, the Ruler tool and the Compare view.
    pub metrics: metrics::MetricsPanel,
    pub ruler: RulerTool,
    pub compare: compare::CompareView,
    /// The scene as of the last committed undo step (the "before" of editor-made changes).
    pub(super) last_committed: Scene,
    /// A scene edit in progress (slider or colour drag): its label and the scene before it.
    /// Committed to the history when the pointer is released.
    pub(super) pending_edit: Option<(String, Scene)>,
    /// What waits on the answer to "save the changes first?" (opening over unsaved work).
    pub unsaved_prompt: Option<crate::gui::action::Action>,
    /// What goes on once the scene is saved (Save As… was asked for first).
    pub(super) after_save: Option<crate::gui::action::Action>,
    /// Where the side panels were laid out at the last frame.
    pub layout: LayoutRects,
    /// The camera a message about the view ("Anterior view") described: the message goes once
    /// the camera moves on (an orbit), so the status never names a view that is no longer shown.
    pub(super) view_message_camera: Option<cutter::Camera>,
    /// True once a close was requested (Exit); the recovery file is removed then.
    pub(super) exiting: bool,
    pub(super) frame_started: Instant,
}

/// The inner rectangles (points) of the side panels at the last frame: what a panel draws must
/// lie inside its own (tests check that nothing is clipped).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayoutRects {
    /// The Models panel, left of the view.
    pub models: egui::Rect,
    /// The Tools panel, right of the view.
    pub tools: egui::Rect,
}

impl Default for LayoutRects {
    fn default() -> Self {
        LayoutRects {
            models: egui::Rect::NOTHING,
            tools: egui::Rect::NOTHING,
        }
    }
}

/// The Ruler tool's state.
#[derive(Clone, Debug, Default)]
pub struct RulerTool {
    /// Clicks in the 3D view place ruler ends.
    pub active: bool,
    /// The first end of the ruler being placed.
    pub first: Option<DVec3>,
}

impl AppState {
    /// True while any background job runs (tests wait on this).
    pub fn busy(&self) -> bool {
        self.jobs.iter().any(Job::is_running)
            || self.metrics.busy()
            || self.compare.busy()
            || self.atlas.busy()
            || self.folder.busy()
            || self.viewport.risk.busy()
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

    /// Structures that arrive from a background job (the default scene's labels, a folder of
    /// masks) join the scene after its models, and every undo snapshot of it: no model moves,
    /// so cutters keep their targets, and undoing an edit made meanwhile keeps them; their
    /// arrival is no undo step of its own.
    pub(in crate::gui) fn append_arrived(&mut self, models: Vec<crate::io::Model>) {
        let added = crate::scene::open::structures(models, self.scene.models.len());
        for scene in self.scenes_mut() {
            scene.models.extend(added.iter().cloned());
        }
    }

    /// Structures that arrive for undo step `step` (a folder of masks added to the scene): they
    /// join the scene after its models, that step's after snapshot and every snapshot made
    /// since, and not the snapshots before it, so that undoing the step removes them all and
    /// undoing an edit made meanwhile keeps them.
    pub(in crate::gui) fn append_arrived_since(
        &mut self,
        models: Vec<crate::io::Model>,
        step: u64,
    ) {
        let added = crate::scene::open::structures(models, self.scene.models.len());
        let pending = self.pending_edit.as_mut().map(|(_, scene)| scene);
        for scene in [&mut self.scene, &mut self.last_committed]
            .into_iter()
            .chain(pending)
            .chain(self.history.scenes_since_mut(step))
        {
            scene.models.extend(added.iter().cloned());
        }
    }

    /// Sets the status message.
    pub fn say(&mut self, message: impl Into<String>) {
        self.status.message = message.into();
        self.status.is_error = false;
        self.view_message_camera = None;
    }

    /// Sets a status message about the current view, cleared once the camera moves.
    pub fn say_about_view(&mut self, message: impl Into<String>) {
        self.say(message);
        self.view_message_camera = Some(self.scene.camera);
    }

    /// Clears a message about the view once the camera no longer shows that view.
    pub(super) fn forget_stale_view_message(&mut self) {
        if self
            .view_message_camera
            .is_some_and(|camera| camera != self.scene.camera)
        {
            self.view_message_camera = None;
            self.status.message.clear();
            self.status.is_error = false;
        }
    }

    /// Says the edited cutter's depth and what it reaches ("42 mm: reaches left lateral
    /// ventricle"), when a cutter is edited.
    pub fn say_depth(&mut self) {
        if let Some(line) = self.viewport.editor.depth_status(&self.scene) {
            self.say(line);
        }
    }

    /// Sets an error message (one line, kept until the next message).
    pub fn complain(&mut self, error: &anyhow::Error) {
        self.status.message = crate::platform::errors::error_line(error);
        self.status.is_error = true;
        self.view_message_camera = None;
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
    pub(super) fn commit_edit_if_idle(&mut self, ctx: &egui::Context) {
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
