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

/// One model of the scene: one structure of a file, or one connected region of it (see
/// [`ModelUnit`]).
#[derive(Clone, Debug)]
pub struct SceneModel {
    /// Display name: the structure's name (`left hippocampus`), or for a region the file stem +
    /// region number (`knee_skin 1`).
    pub name: String,
    /// The file the model came from (absolute or relative to the working directory; sessions
    /// store it relative to the session file).
    pub source: PathBuf,
    /// Index of this model among the pieces of `source` of kind `unit`, in file order (0-based).
    /// Together with `source` and `unit` it says which model a session entry is.
    pub region: usize,
    /// Whether `region` counts structures or connected regions of `source`.
    pub unit: ModelUnit,
    /// The model list's group: folder names from the opened folder down, `/` between them
    /// (`head_brain_spl_atlas/sub`); `""` for no group.
    pub group: String,
    /// The welded, validated mesh of the structure (all its regions) or of the region.
    pub mesh: Arc<Mesh>,
    /// How `mesh` relates to `source`, which decides how a session stores it. Whoever replaces
    /// `mesh` with other geometry sets [`MeshOrigin::Edited`] (see [`SceneModel::replace_mesh`]);
    /// nobody compares meshes to find out.
    pub origin: MeshOrigin,
    /// sRGB colour, each component in 0..=1.
    pub color: [f32; 3],
    /// 1 = opaque, 0 = invisible; below 1 the model is drawn with order-independent transparency.
    pub opacity: f32,
    pub style: ModelStyle,
    pub visible: bool,
    /// The faces of `mesh` that are incision walls (drawn as the inside of the tissue); marks
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
        SceneModel {
            name: name.into(),
            source: source.into(),
            region: 0,
            unit: ModelUnit::Region,
            group: String::new(),
            mesh,
            origin: MeshOrigin::Region,
            color,
            opacity: 1.0,
            style: ModelStyle::Solid,
            visible: true,
            walls: None,
        }
    }

    /// The faces of `mesh` that are incision walls, ascending (none when the marks were made for
    /// another mesh).
    pub fn wall_faces(&self) -> &[u32] {
        WallFaces::for_mesh(&self.walls, &self.mesh)
    }
}

/// Where a model's mesh came from (see `crate::session::meshes`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MeshOrigin {
    /// Region `region` of `source`, as loading that file gives it: a session names the file and
    /// the region.
    #[default]
    Region,
    /// The whole of `source`, read verbatim (no welding, no region split): a mesh file a session
    /// wrote. A session names the file with `"exact": true`.
    Exact,
    /// Changed since it was loaded (scalpel strokes, a detached piece, Remove All Cut Geometry):
    /// `source` and `region` only say where it came from. Saving a session writes the mesh to a
    /// file of its own next to the session.
    Edited,
}

impl SceneModel {
    /// A visible, opaque, solid model of structure `index` of `source` in `group`.
    pub fn structure(model: crate::io::Model, color: [f32; 3]) -> SceneModel {
        let crate::io::Model {
            name,
            source,
            index,
            color: _,
            group,
            mesh,
        } = model;
        let mut entry = SceneModel::new(name, source, Arc::new(mesh), color);
        entry.region = index;
        entry.unit = ModelUnit::Structure;
        entry.group = group;
        entry
    }

    /// Replaces the mesh with other geometry and marks the model edited, so that saving a
    /// session writes the new mesh instead of naming the file it was loaded from.
    pub fn replace_mesh(&mut self, mesh: Arc<Mesh>) {
        self.mesh = mesh;
        self.origin = MeshOrigin::Edited;
    }

    /// [`SceneModel::replace_mesh`] with the faces of the new mesh that are incision walls.
    pub fn replace_mesh_with_walls(&mut self, mesh: Arc<Mesh>, walls: Vec<u32>) {
        self.walls = WallFaces::new(&mesh, walls);
        self.replace_mesh(mesh);
    }
}
