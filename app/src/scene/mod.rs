//! The in-memory scene: what the GUI edits, the session file stores and the renderer draws.
//!
//! One [`Scene`] holds the models (one per structure: a mesh file or one label of a segmentation
//! volume, with all its regions; or one per connected region for scenes from
//! `cutaway-session/1` files, see [`ModelUnit`]), the cutters (each aimed at one model), the camera and the render settings. It is cheap to clone:
//! meshes sit behind [`Arc`], so the GUI can hand a snapshot to the renderer's paint callback or
//! to an undo stack every frame without copying triangles.
//!
//! Change tracking needs no bookkeeping: the renderer remembers a [`std::sync::Weak`] to every
//! mesh it uploaded. Replacing a model's mesh (`model.mesh`) with a new `Arc` (or mutating it through
//! `Arc::make_mut`, which moves the data out while the renderer's weak pointer exists) makes the
//! old weak pointer stale, and the renderer re-uploads. A weak pointer also keeps its allocation
//! reserved, so a new mesh can never reuse the old address by accident.
//!
//! Colours are sRGB-encoded components in 0..=1, as the colour picker shows them and as the
//! session file stores them; the renderer converts them to linear light.

pub mod arrivals;
mod cutters;
pub mod image_layer;
mod model;
pub mod model_groups;
pub mod names;
pub mod open;
pub mod orientation;
pub mod regions;
pub mod risk;
pub mod ruler;
mod settings;
pub mod units;
pub mod variants;
pub mod wall_faces;

pub use cutters::{CutterViews, SceneCutter, SubCutterSpec};
pub use image_layer::{ImageLayer, WallDisplay};
pub use model::{MeshOrigin, ModelStyle, ModelUnit, SceneModel};
pub use orientation::{Orientation, ViewPreset};
pub use settings::{RenderSettings, Stereo};
pub use units::{LengthUnit, SizeDefaults};
pub use variants::{Variant, Variants};

use csg::Aabb;
use cutter::Camera;
use glam::DVec3;

use crate::scene::ruler::Ruler;

/// Everything the user sees and edits.
#[derive(Clone, Debug)]
pub struct Scene {
    pub models: Vec<SceneModel>,
    pub cutters: Vec<SceneCutter>,
    pub camera: Camera,
    pub render: RenderSettings,
    /// Which world directions are the patient's superior and anterior (guessed when files are
    /// opened, saved in the session).
    pub orientation: crate::scene::Orientation,
    /// What one file unit is (guessed from the data's size; not saved, guessed again on load).
    pub unit: crate::scene::LengthUnit,
    /// The intensity image shown on the walls, slices and ribbons (`None`: no image).
    pub image: Option<crate::scene::ImageLayer>,
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
    /// The models' names, in scene order (what the panels offer to pick from).
    pub fn model_names(&self) -> Vec<String> {
        self.models.iter().map(|m| m.model.name.clone()).collect()
    }

    /// Bounding box of the visible models (of all models if none is visible; empty if there are
    /// no models).
    pub fn bbox(&self) -> Aabb {
        let mut visible = Aabb::EMPTY;
        let mut all = Aabb::EMPTY;
        for model in &self.models {
            let b = model.model.mesh.bbox();
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
    pub fn preset_camera(&self, preset: crate::scene::ViewPreset) -> Camera {
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
                    m.model.name, m.opacity
                ));
            }
            if m.color.iter().any(|c| !c.is_finite()) {
                return Err(format!(
                    "model {i} ({}): colour is not finite",
                    m.model.name
                ));
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

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use csg::Mesh;

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
}
