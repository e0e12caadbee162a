//! The export dialogs' settings (Export Image, Export Cut Meshes, Export Turntable, Export Web
//! Page): what the dialogs show and the exports read.

use crate::export::turntable::TurntableOptions;

/// The largest exported image side (8k).
pub const MAX_EXPORT_SIDE: u32 = 8192;

/// The Export Image dialog's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportImageSettings {
    /// The dialog is open.
    pub open: bool,
    /// Output size in pixels, each in 1..=[`MAX_EXPORT_SIDE`].
    pub width: u32,
    pub height: u32,
    /// Write a transparent background instead of the scene's background colour.
    pub transparent: bool,
    /// Labels, scale bar and orientation marker drawn over the picture (none by default).
    pub annotations: crate::annotate::picture::AnnotationChoice,
}

impl Default for ExportImageSettings {
    fn default() -> Self {
        ExportImageSettings {
            open: false,
            width: 3840,
            height: 2160,
            transparent: false,
            annotations: crate::annotate::picture::AnnotationChoice {
                extras: crate::annotate::labelled::Extras {
                    scale_bar: false,
                    marker: false,
                },
                ..Default::default()
            },
        }
    }
}

/// Mesh file format of Export Cut Meshes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Obj,
    Stl,
    Ply,
}

impl MeshFormat {
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Stl => "stl",
            MeshFormat::Ply => "ply",
        }
    }
}

/// The Export Cut Meshes dialog's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportMeshSettings {
    pub open: bool,
    pub format: MeshFormat,
    pub kept: bool,
    pub walls: bool,
    pub removed: bool,
}

impl Default for ExportMeshSettings {
    fn default() -> Self {
        ExportMeshSettings {
            open: false,
            format: MeshFormat::Obj,
            kept: true,
            walls: true,
            removed: true,
        }
    }
}

/// The largest turntable frame side.
pub const MAX_TURNTABLE_SIDE: u32 = 4096;

/// The Export Turntable dialog's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct TurntableSettings {
    /// The dialog is open.
    pub open: bool,
    /// Frame size in pixels, each in 1..=[`MAX_TURNTABLE_SIDE`].
    pub width: u32,
    pub height: u32,
    pub options: TurntableOptions,
}

impl Default for TurntableSettings {
    fn default() -> Self {
        TurntableSettings {
            open: false,
            width: 640,
            height: 480,
            options: TurntableOptions::default(),
        }
    }
}

/// The Export Web Page dialog's settings.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WebPageSettings {
    /// The dialog is open.
    pub open: bool,
    /// The page's title; empty: [`crate::export::webpage::DEFAULT_TITLE`].
    pub title: String,
}
