//! The in-memory scene: what the GUI edits, the session file stores and the renderer draws.
//!
//! One [`Scene`] holds the models (one per structure: a mesh file or one label of a segmentation
//! volume, with all its regions; or one per connected region for scenes from
//! `cutaway-session/1` files, see [`ModelUnit`]), the cutters (each aimed at one model), the camera and the render settings. It is cheap to clone:
//! meshes sit behind [`Arc`], so the GUI can hand a snapshot to the renderer's paint callback or
//! to an undo stack every frame without copying triangles.
//!
//! Change tracking needs no bookkeeping: the renderer remembers a [`std::sync::Weak`] to every
//! mesh it uploaded. Replacing `SceneModel::mesh` with a new `Arc` (or mutating it through
//! `Arc::make_mut`, which moves the data out while the renderer's weak pointer exists) makes the
//! old weak pointer stale, and the renderer re-uploads. A weak pointer also keeps its allocation
//! reserved, so a new mesh can never reuse the old address by accident.
//!
//! Colours are sRGB-encoded components in 0..=1, as the colour picker shows them and as the
//! session file stores them; the renderer converts them to linear light.

pub mod names;
pub mod regions;
pub mod risk;
pub mod ruler;
pub mod variants;
pub mod wall_faces;

use std::path::PathBuf;
use std::sync::Arc;

use csg::{Aabb, Mesh};
use cutter::Camera;
use glam::DVec3;

use crate::scene::ruler::Ruler;
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

/// What one model of a file is: the piece of `source` that [`SceneModel::region`] indexes.
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

/// Thin sub-cutters of a cutter (ribbons or slices, thesis 3.4.2): evenly spaced along the path,
/// centred on the cutting planes, or horizontal layers at depth steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubCutterView {
    /// Number of sub-cutters, at least 1 (one per plane whatever this says for `Planes`).
    pub count: u32,
    /// Width of each sub-cutter (across the path, or the layer's thickness); positive. Model
    /// units, or with `relative` the fraction of the spacing between sub-cutters each one fills.
    pub width: f64,
    pub placement: cutter::subcutters::Placement,
    pub relative: bool,
}

impl SubCutterView {
    /// What a new ribbon or slice view starts with: five evenly spaced sub-cutters, each filling
    /// a third of its interval (relative, so it looks the same in millimetres and metres).
    pub const NEW: SubCutterView = SubCutterView {
        count: 5,
        width: 0.35,
        placement: cutter::subcutters::Placement::Even,
        relative: true,
    };

    /// The sub-cutter request of the `cutter` crate.
    pub fn spec(&self) -> cutter::subcutters::SubCutterSpec {
        cutter::subcutters::SubCutterSpec {
            count: self.count as usize,
            width: self.width,
            placement: self.placement,
            relative: self.relative,
        }
    }
}

/// Which context-preserving views a cutter shows in Preview mode (thesis 3.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutterViews {
    /// Normal cut: the kept part with the walls in their own colour and a thick contour line.
    pub cut: bool,
    /// The removed piece drawn with this opacity (0..=1) by order-independent transparency.
    pub transparency: Option<f32>,
    /// Ribbons: the removed surface inside thin sub-cutters, no walls.
    pub ribbons: Option<SubCutterView>,
    /// Solid slices: ribbons closed by their walls.
    pub slices: Option<SubCutterView>,
}

impl Default for CutterViews {
    /// Normal cut only.
    fn default() -> CutterViews {
        CutterViews {
            cut: true,
            transparency: None,
            ribbons: None,
            slices: None,
        }
    }
}

impl CutterViews {
    /// True when the cutter changes the picture at all in Preview mode.
    pub fn any(&self) -> bool {
        self.cut || self.transparency.is_some() || self.ribbons.is_some() || self.slices.is_some()
    }
}

/// A cutter of the scene: the `cutter` crate's [`cutter::Cutter`] (kind, smoothing and the
/// bounded planes the editor produced), aimed at one model, with how Preview shows it.
///
/// The cutter is held as the editor, the boolean and the overlay know it, never as a copy in
/// another form: the session reader makes it once from the file's names and points, and every
/// reader (live cut, Preview, undo, `extrude`, `render`) takes its surface from
/// [`cutter::Cutter::surface`].
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCutter {
    /// Index into [`Scene::models`] of the model this cutter cuts.
    pub target: usize,
    /// At least one plane; consecutive planes bound one box of the cutter.
    pub cutter: cutter::Cutter,
    pub views: CutterViews,
}

impl SceneCutter {
    /// `cutter` aimed at model `target`, shown as a Normal Cut.
    pub fn new(target: usize, cutter: cutter::Cutter) -> SceneCutter {
        SceneCutter {
            target,
            cutter,
            views: CutterViews::default(),
        }
    }
}

/// Stereo output of the renderer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Stereo {
    #[default]
    None,
    /// Red/blue anaglyph: left eye in red, right eye in blue.
    Anaglyph,
}

impl Stereo {
    pub fn as_str(self) -> &'static str {
        match self {
            Stereo::None => "none",
            Stereo::Anaglyph => "anaglyph",
        }
    }

    pub fn parse(text: &str) -> Option<Stereo> {
        match text {
            "none" => Some(Stereo::None),
            "anaglyph" => Some(Stereo::Anaglyph),
            _ => None,
        }
    }
}

/// The Rendering menu.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// sRGB background colour with straight alpha; alpha 0 exports a transparent PNG.
    /// Default: white, opaque.
    pub background: [f32; 4],
    /// Supersampling (2×2) when true. Default: true.
    pub antialias: bool,
    /// Default: none.
    pub stereo: Stereo,
}

impl Default for RenderSettings {
    fn default() -> RenderSettings {
        RenderSettings {
            background: [1.0, 1.0, 1.0, 1.0],
            antialias: true,
            stereo: Stereo::None,
        }
    }
}

/// Everything the user sees and edits.
#[derive(Clone, Debug)]
pub struct Scene {
    pub models: Vec<SceneModel>,
    pub cutters: Vec<SceneCutter>,
    pub camera: Camera,
    pub render: RenderSettings,
    /// Which world directions are the patient's superior and anterior (guessed when files are
    /// opened, saved in the session).
    pub orientation: crate::view::Orientation,
    /// What one file unit is (guessed from the data's size; not saved, guessed again on load).
    pub unit: crate::view::LengthUnit,
    /// The intensity image shown on the walls, slices and ribbons (`None`: no image).
    pub image: Option<crate::intensity::ImageLayer>,
    /// Named cutter sets; `cutters` are those of the active one (see `scene/variants.rs`).
    pub variants: Variants,
    /// Distances measured between surface points ([`crate::scene::ruler`]).
    pub rulers: Vec<Ruler>,
    /// The walls coloured by their distance to critical structures ([`crate::scene::risk`]).
    pub risk: risk::RiskSettings,
}

impl Default for Scene {
    fn default() -> Scene {
        Scene {
            models: Vec::new(),
            cutters: Vec::new(),
            camera: Camera {
                eye: DVec3::new(0.0, -300.0, 0.0),
                target: DVec3::ZERO,
                up: DVec3::Z,
                fov_y_deg: 30.0,
            },
            render: RenderSettings::default(),
            orientation: Default::default(),
            unit: Default::default(),
            image: None,
            variants: Variants::default(),
            rulers: Vec::new(),
            risk: Default::default(),
        }
    }
}

impl Scene {
    /// Bounding box of the visible models (of all models if none is visible; empty if there are
    /// no models).
    pub fn bbox(&self) -> Aabb {
        let mut visible = Aabb::EMPTY;
        let mut all = Aabb::EMPTY;
        for model in &self.models {
            let b = model.mesh.bbox();
            all = all.union(&b);
            if model.visible {
                visible = visible.union(&b);
            }
        }
        if visible.is_empty() { all } else { visible }
    }

    /// A camera framing every visible model from the front (−Y toward +Y, +Z up), as after a load.
    pub fn framing_camera(&self) -> Camera {
        self.framing_camera_from(DVec3::NEG_Y)
    }

    /// A camera framing every visible model from `direction` (pointing from the models toward
    /// the eye), +Z up: `DVec3::Y` faces RAS anatomy, whose front is +Y.
    pub fn framing_camera_from(&self, direction: DVec3) -> Camera {
        let bbox = self.bbox();
        if bbox.is_empty() {
            return Scene::default().camera;
        }
        Camera::framing(&bbox, direction, DVec3::Z, 30.0)
    }

    /// A camera framing every visible model from `preset`'s side of the patient
    /// ([`Scene::orientation`]), superior up: the first view of opened files and the View menu.
    pub fn preset_camera(&self, preset: crate::view::ViewPreset) -> Camera {
        let bbox = self.bbox();
        if bbox.is_empty() {
            return Scene::default().camera;
        }
        let (toward_eye, up) = self.orientation.preset_axes(preset);
        Camera::framing(&bbox, toward_eye, up, self.camera.fov_y_deg)
    }

    /// Checks what the renderer and the cut code rely on: cutter targets in range, at least one
    /// plane per cutter, finite values, opacities in 0..=1. Returns a one-line description of the
    /// first problem.
    pub fn sanity_check(&self) -> Result<(), String> {
        let Scene {
            models,
            cutters,
            camera,
            render,
            orientation: _,
            unit: _,
            image,
            variants: _,
            rulers,
            risk,
        } = self;
        risk.check().map_err(|e| format!("risk: {e}"))?;
        if let Some(i) = rulers
            .iter()
            .position(|r| !(r.a.is_finite() && r.b.is_finite()))
        {
            return Err(format!("ruler {i}: an end is not finite"));
        }
        if let Some(layer) = image {
            let w = layer.window;
            if !(w.level.is_finite() && w.width.is_finite() && w.width > 0.0) {
                return Err(format!(
                    "image window [{}, {}] needs a finite level and a positive width",
                    w.level, w.width
                ));
            }
        }
        for (i, m) in models.iter().enumerate() {
            if !(0.0..=1.0).contains(&m.opacity) {
                return Err(format!(
                    "model {i} ({}): opacity {} is outside 0..1",
                    m.name, m.opacity
                ));
            }
            if m.color.iter().any(|c| !c.is_finite()) {
                return Err(format!("model {i} ({}): colour is not finite", m.name));
            }
        }
        for (i, c) in cutters.iter().enumerate() {
            if c.target >= models.len() {
                return Err(format!(
                    "cutter {i}: target {} does not exist (the scene has {} models)",
                    c.target,
                    models.len()
                ));
            }
            if c.cutter.planes.is_empty() {
                return Err(format!("cutter {i}: has no planes"));
            }
            if c.cutter
                .planes
                .iter()
                .flat_map(|p| p.corners())
                .any(|p| !p.is_finite())
            {
                return Err(format!("cutter {i}: a plane point is not finite"));
            }
            if let Some(t) = c.views.transparency
                && !(0.0..=1.0).contains(&t)
            {
                return Err(format!("cutter {i}: transparency {t} is outside 0..1"));
            }
            for (what, v) in [("ribbons", c.views.ribbons), ("slices", c.views.slices)] {
                if let Some(v) = v
                    && (v.count == 0 || !(v.width.is_finite() && v.width > 0.0))
                {
                    return Err(format!(
                        "cutter {i}: {what} need a count of at least 1 and a positive width (got {} and {})",
                        v.count, v.width
                    ));
                }
                if let Some(v) = v
                    && v.relative
                    && v.width > 1.0
                {
                    return Err(format!(
                        "cutter {i}: {what} width {} is relative (a fraction of the spacing) and must be at most 1",
                        v.width
                    ));
                }
            }
        }
        if !(camera.eye.is_finite() && camera.target.is_finite() && camera.up.is_finite()) {
            return Err("camera: eye, target or up is not finite".to_string());
        }
        if camera.eye == camera.target {
            return Err("camera: eye and target are the same point".to_string());
        }
        if !(camera.fov_y_deg > 0.0 && camera.fov_y_deg < 180.0) {
            return Err(format!(
                "camera: fov_y_deg {} is outside (0, 180)",
                camera.fov_y_deg
            ));
        }
        if render.background.iter().any(|c| !(0.0..=1.0).contains(c)) {
            return Err("render: background components must lie in 0..1".to_string());
        }
        self.check_variants()
    }
}

/// `count` colours that are easy to tell apart (golden-angle hues, moderate saturation), for
/// models loaded without a colour.
pub fn distinct_colors(count: usize) -> Vec<[f32; 3]> {
    (0..count)
        .map(|i| {
            let hue = (0.08 + i as f32 * 0.381_966) % 1.0;
            hsv_to_rgb(hue, 0.45, 0.9)
        })
        .collect()
}

fn hsv_to_rgb(h: f32, s: f32, v: f32) -> [f32; 3] {
    let h6 = h * 6.0;
    let sector = h6.floor() as i32 % 6;
    let f = h6 - h6.floor();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    match sector {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

/// One named cutter set (`scene/variants.rs` switches and creates them).
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    pub name: String,
    /// The variant's cutters; for the active variant this copy is stale: the scene's `cutters`
    /// are its cutters.
    pub cutters: Vec<SceneCutter>,
}

/// The variants of a scene: empty (one implicit variant, the scene's cutters) or every variant,
/// the active one included, in the order they are shown.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Variants {
    pub list: Vec<Variant>,
    /// Index into `list` of the variant whose cutters the scene holds (0 when `list` is empty).
    pub active: usize,
}

impl Variants {
    /// Longest variant name, in characters.
    pub const MAX_NAME_CHARS: usize = 80;

    /// Whether the scene defines variants of its own.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// A variant name is 1..=[`Self::MAX_NAME_CHARS`] characters without control characters.
    pub fn check_name(name: &str) -> Result<(), String> {
        if name.trim().is_empty() {
            return Err("a variant name cannot be empty".to_string());
        }
        if name.chars().count() > Self::MAX_NAME_CHARS {
            return Err(format!(
                "variant name '{}…' is longer than {} characters",
                name.chars().take(20).collect::<String>(),
                Self::MAX_NAME_CHARS
            ));
        }
        if name.chars().any(char::is_control) {
            return Err(format!("variant name {name:?} holds a control character"));
        }
        Ok(())
    }
}

impl Scene {
    /// Checks the variants: names usable and distinct, the active index inside the list, every
    /// other variant's cutters valid for the models (the same rules as the scene's cutters).
    pub fn check_variants(&self) -> Result<(), String> {
        let v = &self.variants;
        if v.is_empty() {
            return Ok(());
        }
        if v.active >= v.list.len() {
            return Err(format!(
                "active variant {} does not exist (there are {})",
                v.active,
                v.list.len()
            ));
        }
        for (k, variant) in v.list.iter().enumerate() {
            Variants::check_name(&variant.name).map_err(|e| format!("variant {k}: {e}"))?;
            if v.list[..k].iter().any(|w| w.name == variant.name) {
                return Err(format!(
                    "variant {k}: the name '{}' is used twice",
                    variant.name
                ));
            }
            if k != v.active {
                let mut shown = self.clone();
                shown.cutters = variant.cutters.clone();
                shown.variants = Variants::default();
                shown
                    .sanity_check()
                    .map_err(|e| format!("variant {k} ('{}'): {e}", variant.name))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle() -> Arc<Mesh> {
        Arc::new(Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2]],
        })
    }

    #[test]
    fn sanity_check_rejects_bad_cutter_target() {
        let mut scene = Scene::default();
        scene
            .models
            .push(SceneModel::new("a", "a.obj", triangle(), [1.0, 0.0, 0.0]));
        scene.cutters.push(SceneCutter::new(
            0,
            cutter::Cutter {
                kind: cutter::CutKind::Curving,
                smooth: false,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: vec![cutter::BoundedPlane::from_corners([
                    DVec3::ZERO,
                    DVec3::X,
                    DVec3::Y,
                    DVec3::Z,
                ])],
            },
        ));
        assert!(scene.sanity_check().is_ok());
        scene.cutters[0].target = 3;
        let err = scene.sanity_check().unwrap_err();
        assert!(err.contains("target 3"), "{err}");
    }

    #[test]
    fn distinct_colors_differ() {
        let colors = distinct_colors(6);
        for i in 0..6 {
            for j in 0..i {
                let d: f32 = (0..3).map(|k| (colors[i][k] - colors[j][k]).abs()).sum();
                assert!(
                    d > 0.1,
                    "{i} and {j} look alike: {:?} {:?}",
                    colors[i],
                    colors[j]
                );
            }
        }
    }
}
