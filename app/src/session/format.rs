//! The session file's types as they are on disk (serde), with the format tags: what
//! [`crate::session`] parses and writes, what [`crate::session::limits`] bounds before anything is
//! loaded. In a file of their own so that the bounds check and the loader both build on them
//! without importing each other.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

pub use crate::session::cutters::{
    CutterEntry, SubCutterEntry, ViewsEntry, cutter_entry, cutter_from_entry,
};

/// The `format` value of the structure-based version, written whenever a scene holds structures.
pub const FORMAT: &str = "cutaway-session/2";

/// The `format` value of the region-based version: loaded with its meaning, written for scenes
/// made only of regions.
pub const FORMAT_V1: &str = "cutaway-session/1";

/// The file as it is on disk.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SessionFile {
    pub format: String,
    pub models: Vec<ModelEntry>,
    #[serde(default)]
    pub cutters: Vec<CutterEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub render: Option<RenderEntry>,
    /// The patient's axes in world space; absent in older files (then guessed from the data).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<OrientationEntry>,
    /// The intensity image on the walls ([`crate::session::image`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<crate::session::image::ImageEntry>,
    /// Named cutter sets ([`crate::session::variants`]); `cutters` are the active one's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub variants: Vec<crate::session::variants::VariantEntry>,
    /// Index into `variants` of the variant `cutters` belong to.
    #[serde(default, skip_serializing_if = "crate::session::variants::is_zero")]
    pub active_variant: usize,
    /// Measured distances ([`crate::session::rulers`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rulers: Vec<crate::session::rulers::RulerEntry>,
    /// Walls coloured by their distance to critical structures ([`crate::session::risk`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub risk: Option<crate::session::risk::RiskEntry>,
}

/// `orientation`: world directions of the patient's superior and anterior (unit, orthogonal).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct OrientationEntry {
    pub superior: [f64; 3],
    pub anterior: [f64; 3],
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelEntry {
    /// Relative to the session file's folder (or absolute).
    pub path: PathBuf,
    /// Which region of the file (0-based, file order); in `/1` absent means every region.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<usize>,
    /// `/2` only: which structure of the file (0-based); absent (and no `region`): every
    /// structure of the file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub structure: Option<usize>,
    /// `/2` only: the model list's group (folder names, `/` between them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// sRGB, 0..=1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f32; 3]>,
    #[serde(default = "one")]
    pub opacity: f32,
    /// `solid` or `wireframe`.
    #[serde(default = "solid")]
    pub style: String,
    #[serde(default = "yes")]
    pub visible: bool,
    /// The file is this one model exactly as stored (a mesh Cutaway wrote for an edited model,
    /// see [`crate::session::meshes`]): read verbatim, no welding, no region split.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub exact: bool,
    /// The model's display name (written for `exact` entries, whose file name is not the name,
    /// and for structures in `/2`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CameraEntry {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub up: [f64; 3],
    pub fov_y_deg: f64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RenderEntry {
    #[serde(default = "white")]
    pub background: [f32; 4],
    #[serde(default = "yes")]
    pub antialias: bool,
    /// `none` or `anaglyph`.
    #[serde(default = "none")]
    pub stereo: String,
}

fn one() -> f32 {
    1.0
}
fn yes() -> bool {
    true
}
fn solid() -> String {
    "solid".to_string()
}
fn none() -> String {
    "none".to_string()
}
fn white() -> [f32; 4] {
    [1.0, 1.0, 1.0, 1.0]
}
