//! What the user can ask of the window: the modes, the purposes of file dialogs and every
//! [`Action`].
//!
//! Panels, menus, keys and dropped files only describe what the user asked for as actions; the
//! app applies them (`apply.rs`), so the panels never call back into the app and the undo history
//! sees every scene change. This file is data only and imports nothing of the window.

use std::path::PathBuf;

use crate::scene::{Orientation, ViewPreset};

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
    /// Files, a folder, a volume or a session: what replaces the scene (File → Open…).
    Open,
    /// A folder of meshes (the native dialogs pick files or folders, never both).
    OpenFolder,
    AddModel,
    SaveSessionAs,
    ExportImage,
    ExportMeshes,
    ExportTurntable,
    ExportWebPage,
    SaveGesture,
    OpenImage,
}

impl Purpose {
    pub fn title(self) -> &'static str {
        match self {
            Purpose::Open => "Open",
            Purpose::OpenFolder => "Open Folder",
            Purpose::AddModel => "Add Model",
            Purpose::SaveSessionAs => "Save Session As",
            Purpose::ExportImage => "Export Image",
            Purpose::ExportMeshes => "Export Cut Meshes to Folder",
            Purpose::ExportTurntable => "Export Turntable to Folder",
            Purpose::ExportWebPage => "Export Web Page",
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
    /// Write the scene as the web page of the Export Web Page dialog to this file.
    ExportWebPageTo(PathBuf),
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
    /// One model per connected region of model `i` ([`crate::scene::regions`]).
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
    /// Build the cutters that open the view onto model `i` through everything in front of it
    /// ([`crate::expose`], a background job) and select it.
    Expose(usize),
    /// [`Action::Expose`] of the selected model (the X key); says how to select one when none is.
    ExposeSelected,
    /// Build model `i`'s spatial index, which the cutter editor needs before a press can start a
    /// cutter on it (a background job).
    IndexModel(usize),
    RestoreRecovery,
    DiscardRecovery,
    /// The answer to "save the changes first?", asked before the scene is replaced.
    Unsaved(UnsavedAnswer),
    /// Turn, zoom or re-orient the view (View menu, view keys).
    View(ViewCommand),
}

/// What the user answered when opening over unsaved changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnsavedAnswer {
    /// Save the scene (asking where when it has no file yet), then go on.
    Save,
    /// Go on without saving.
    Discard,
    /// Keep the scene; do not open.
    Cancel,
}

/// A change of what the camera looks at (never an undoable scene edit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewCommand {
    /// Look from one side of the patient, framing every visible model.
    Preset(ViewPreset),
    /// Keep the direction, frame every visible model.
    ZoomToFit,
    /// Keep the direction, frame the selected model.
    ZoomToSelection,
    /// Take these axes as the patient's (the View → Up Axis choice); saved with the session.
    Orient(Orientation),
}
