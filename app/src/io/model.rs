//! The one record of a named, coloured mesh: what a file holds and what the scene shows.
//!
//! A reader gives one [`Model`] per part of a file (an OBJ object or group, a label of a volume,
//! the whole file for formats without parts); [`super::load_structures`] and
//! [`super::load_models`] give one per structure or connected region, with the file, the index
//! and the group filled in. The scene composes it (`crate::scene::SceneModel` adds how it is
//! drawn and where its mesh came from) instead of copying its fields.

use std::path::PathBuf;
use std::sync::Arc;

use csg::Mesh;

/// A named, coloured mesh: one part, structure or connected region of a file.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// A structure's name (`left hippocampus`), a region's file stem + region number as in the
    /// thesis's Models list (`knee_skin 1`), or a part's own name (OBJ object/group).
    pub name: String,
    /// The colour the file gives it (sRGB, 0..=1), if any: label volumes name a colour per
    /// label. A scene model's shown colour is its own (`crate::scene::SceneModel::color`).
    pub color: Option<[f32; 3]>,
    /// Welded (bit-identical positions merged), validated, compacted mesh.
    pub mesh: Arc<Mesh>,
    /// The file it came from (empty for bytes parsed without a file, [`super::parse_bytes`]).
    pub source: PathBuf,
    /// Index of this piece among the pieces of `source` of the same kind (parts, structures or
    /// regions), in file order, 0-based.
    pub index: usize,
    /// The group it belongs to in the model list: the folder path from the opened folder down
    /// (`head_brain_spl_atlas/sub`), `""` for a file opened on its own.
    pub group: String,
}

impl Model {
    /// A part as a reader gives it: named and coloured, in no file yet.
    pub fn part(name: impl Into<String>, color: Option<[f32; 3]>, mesh: Mesh) -> Model {
        Model {
            name: name.into(),
            color,
            mesh: Arc::new(mesh),
            ..Model::default()
        }
    }
}

/// What one model of a file is: the piece of `source` that [`Model::index`] counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ModelUnit {
    /// One connected region of the file, counted through the whole file in file order: the
    /// meaning `cutaway-session/1` gives its models, kept for scenes loaded from such files.
    #[default]
    Region,
    /// One structure: the whole mesh file, or one label of a segmentation volume (ascending
    /// label value). What the model list shows and what `cutaway-session/2` indexes; a cutter on
    /// it cuts every region of it.
    Structure,
}
