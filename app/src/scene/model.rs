//! A model of the scene: one structure of a file (or one connected region of it), its mesh
//! behind an `Arc`, and how it is drawn.

use std::path::PathBuf;
use std::sync::Arc;

use csg::Mesh;

pub use crate::io::ModelUnit;
use crate::scene::wall_faces::WallFaces;

/// How a model's surface is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ModelStyle {
    /// Shaded triangles (default).
    #[default]
    Solid,
    /// Every triangle edge as a thin line, no surface.
    Wireframe,
}

/// One model of the scene: a file's named mesh ([`crate::io::Model`]: one structure of a file, or
/// one connected region of it, see [`ModelUnit`]) and how the scene shows it.
#[derive(Clone, Debug)]
pub struct SceneModel {
    /// Name, file, index in the file (of kind `unit`), group and mesh. `model.source` is
    /// absolute or relative to the working directory (sessions store it relative to the session
    /// file); `model.source`, `model.index` and `unit` say which model a session entry is;
    /// `model.color` is the colour the file gave (the shown colour is [`SceneModel::color`]).
    pub model: crate::io::Model,
    /// Whether `model.index` counts structures or connected regions of `model.source`.
    pub unit: ModelUnit,
    /// How `model.mesh` relates to `model.source`, which decides how a session stores it.
    /// Whoever replaces the mesh with other geometry sets [`MeshOrigin::Edited`] (see
    /// [`SceneModel::replace_mesh`]); nobody compares meshes to find out.
    pub origin: MeshOrigin,
    /// sRGB colour, each component in 0..=1.
    pub color: [f32; 3],
    /// 1 = opaque, 0 = invisible; below 1 the model is drawn with order-independent transparency.
    pub opacity: f32,
    pub style: ModelStyle,
    pub visible: bool,
    /// The faces of the mesh that are incision walls (drawn as the inside of the tissue); marks
    /// made for another mesh count as none ([`SceneModel::wall_faces`]).
    pub walls: Option<Arc<WallFaces>>,
}

impl SceneModel {
    /// A visible, opaque, solid model of region 0 of `source`, with the given colour and no group.
    pub fn new(
        name: impl Into<String>,
        source: impl Into<PathBuf>,
        mesh: Arc<Mesh>,
        color: [f32; 3],
    ) -> SceneModel {
        let model = crate::io::Model {
            name: name.into(),
            source: source.into(),
            mesh,
            ..crate::io::Model::default()
        };
        SceneModel::of(model, ModelUnit::Region, color)
    }

    /// A visible, opaque, solid model of `model`, a piece of kind `unit` of its file.
    pub fn of(model: crate::io::Model, unit: ModelUnit, color: [f32; 3]) -> SceneModel {
        SceneModel {
            model,
            unit,
            origin: MeshOrigin::Region,
            color,
            opacity: 1.0,
            style: ModelStyle::Solid,
            visible: true,
            walls: None,
        }
    }

    /// The faces of the mesh that are incision walls, ascending (none when the marks were made
    /// for another mesh).
    pub fn wall_faces(&self) -> &[u32] {
        WallFaces::for_mesh(&self.walls, &self.model.mesh)
    }
}

/// Where a model's mesh came from (see `crate::session::meshes`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MeshOrigin {
    /// Piece `model.index` of `model.source`, as loading that file gives it: a session names the file and
    /// the region.
    #[default]
    Region,
    /// The whole of `model.source`, read verbatim (no welding, no region split): a mesh file a session
    /// wrote. A session names the file with `"exact": true`.
    Exact,
    /// Changed since it was loaded (scalpel strokes, a detached piece, Remove All Cut Geometry):
    /// `model.source` and `model.index` only say where it came from. Saving a session writes the mesh to a
    /// file of its own next to the session.
    Edited,
}

impl SceneModel {
    /// A visible, opaque, solid model of structure `index` of `source` in `group`.
    pub fn structure(model: crate::io::Model, color: [f32; 3]) -> SceneModel {
        SceneModel::of(model, ModelUnit::Structure, color)
    }

    /// Replaces the mesh with other geometry and marks the model edited, so that saving a
    /// session writes the new mesh instead of naming the file it was loaded from.
    pub fn replace_mesh(&mut self, mesh: Arc<Mesh>) {
        self.model.mesh = mesh;
        self.origin = MeshOrigin::Edited;
    }

    /// [`SceneModel::replace_mesh`] with the faces of the new mesh that are incision walls.
    pub fn replace_mesh_with_walls(&mut self, mesh: Arc<Mesh>, walls: Vec<u32>) {
        self.walls = WallFaces::new(&mesh, walls);
        self.replace_mesh(mesh);
    }
}
