//! The page's data besides the glTF documents: one JSON object the viewer reads at start.
//!
//! Positions and directions are in the scene's own coordinates (file units); the viewer maps them
//! into the glTF frame with the document's root node (`cutaway scene`: millimetres to metres, Z up
//! to Y up), so the page and the `.glb` agree by construction. Colours are sRGB 0..=1 as the
//! session stores them.

use super::VariantPage;
use crate::export::gltf::{MaterialPart, MaterialRole};
use crate::metrics::MetricsOptions;
use crate::metrics::table::rows;
use crate::metrics::variants::VariantMetrics;
use crate::render::{
    BACK_FACE, CONTOUR_COLOR, CONTOUR_OFFSET, CONTOUR_WIDTH_PX, WALL_MIX, WALL_TINT,
};
use crate::scene::Scene;
use crate::scene::{LengthUnit, ViewPreset};

/// Format name of the data, so a viewer can tell what it reads.
pub const FORMAT: &str = "cutaway-webpage/1";

/// The viewer's data.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Manifest {
    pub format: &'static str,
    pub title: String,
    /// `cutaway <version>`.
    pub generator: String,
    /// sRGB with straight alpha (the session's background).
    pub background: [f32; 4],
    /// The session's camera: the page's first view.
    pub camera: CameraData,
    /// The six standard views, as the window's View menu frames them.
    pub views: Vec<ViewData>,
    /// The patient's axes in scene coordinates, for the orientation marker.
    pub orientation: OrientationData,
    /// The box of the visible models (scene coordinates): the renderer's depth range follows it.
    pub bounds: BoundsData,
    /// Millimetres per scene unit (1 for millimetres, 1000 for a body in metres).
    pub mm_per_unit: f64,
    /// The listed structures (the visible models, in model order): glTF node `i` under the root
    /// node is structure `i` in every variant's document.
    pub structures: Vec<StructureData>,
    pub variants: Vec<VariantData>,
    /// Index of the variant the session had active.
    pub active_variant: usize,
    pub metrics: MetricsData,
    /// Where the anatomy comes from and its licence, when the scene shows the embedded atlas.
    pub attribution: Option<Attribution>,
    /// How the renderer draws (so the page shades as `cutaway render` does).
    pub style: StyleData,
    /// Licence of the inlined three.js.
    pub three: ThreeData,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct CameraData {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub up: [f64; 3],
    pub fov_y_deg: f64,
}

impl From<&cutter::Camera> for CameraData {
    fn from(c: &cutter::Camera) -> CameraData {
        CameraData {
            eye: c.eye.to_array(),
            target: c.target.to_array(),
            up: c.up.to_array(),
            fov_y_deg: c.fov_y_deg,
        }
    }
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct BoundsData {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct ViewData {
    /// `Anterior`, … as the View menu names it.
    pub name: &'static str,
    /// The window's key for it (`1`, `Ctrl+1`, …); the page uses the same keys.
    pub key: &'static str,
    pub camera: CameraData,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct OrientationData {
    pub superior: [f64; 3],
    pub anterior: [f64; 3],
    pub right: [f64; 3],
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct StructureData {
    pub name: String,
    /// The model list's folder path (`/` between names), `""` for none.
    pub group: String,
    pub color: [f32; 3],
    pub opacity: f32,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct VariantData {
    pub name: String,
    /// What each material of this variant's document draws, by glTF material index.
    pub materials: Vec<MaterialData>,
    /// The removed piece's opacity the session shows (`None`: no removed piece).
    pub removed_opacity: Option<f32>,
    pub triangles: usize,
    pub lines: usize,
    /// Size of the `.glb`.
    pub bytes: usize,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct MaterialData {
    pub part: MaterialPart,
    /// The structure (index into [`Manifest::structures`]) whose colour it carries.
    pub structure: Option<usize>,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct MetricsData {
    pub focus: Option<String>,
    pub critical: Vec<String>,
    pub samples: usize,
    /// The table `cutaway compare` draws: one row per measure, one cell per variant.
    pub rows: Vec<RowData>,
    /// Per variant, exactly what `cutaway metrics --json` prints for it.
    pub variants: Vec<crate::metrics::Metrics>,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct RowData {
    pub label: String,
    pub cells: Vec<String>,
}

#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Attribution {
    pub text: String,
    pub links: Vec<(String, String)>,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct StyleData {
    /// Brightness of back faces relative to front faces.
    pub back_face: f32,
    /// Contour line width in pixels at an 800-pixel-high view.
    pub contour_width_px: f32,
    pub contour_color: [f32; 3],
    /// How far contour lines are pulled toward the eye, in scene units.
    pub contour_offset: f64,
    pub wall_tint: [f32; 3],
    pub wall_mix: f32,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct ThreeData {
    pub version: &'static str,
    pub license: &'static str,
}

impl Manifest {
    /// The data of `scene` exported as `variants` (in variant order) with their measures.
    pub fn new(
        scene: &Scene,
        title: &str,
        variants: &[VariantPage],
        measured: &[VariantMetrics],
        options: &MetricsOptions,
    ) -> Manifest {
        // Scene model index → structure index (visible models only, as the glTF's nodes).
        let mut structure_of = vec![None; scene.models.len()];
        let mut structures = Vec::new();
        for (m, model) in scene.models.iter().enumerate() {
            if model.visible {
                structure_of[m] = Some(structures.len());
                structures.push(StructureData {
                    name: model.model.name.clone(),
                    group: model.model.group.clone(),
                    color: model.color,
                    opacity: model.opacity,
                });
            }
        }
        let material = |role: &MaterialRole| MaterialData {
            part: role.part,
            structure: role
                .model
                .and_then(|m| structure_of.get(m).copied().flatten()),
        };
        let o = &scene.orientation;
        let bounds = match scene.bbox() {
            b if b.is_empty() => csg::Aabb {
                min: glam::DVec3::ZERO,
                max: glam::DVec3::ZERO,
            },
            b => b,
        };
        Manifest {
            format: FORMAT,
            title: title.to_string(),
            generator: format!("cutaway {}", env!("CARGO_PKG_VERSION")),
            background: scene.render.background,
            camera: CameraData::from(&scene.camera),
            views: ViewPreset::ALL
                .iter()
                .map(|&preset| ViewData {
                    name: preset.label(),
                    key: preset.key_hint(),
                    camera: CameraData::from(&scene.preset_camera(preset)),
                })
                .collect(),
            orientation: OrientationData {
                superior: o.superior.to_array(),
                anterior: o.anterior.to_array(),
                right: o.right().to_array(),
            },
            bounds: BoundsData {
                min: bounds.min.to_array(),
                max: bounds.max.to_array(),
            },
            mm_per_unit: LengthUnit::guess(&bounds, false).mm_per_unit(),
            structures,
            variants: variants
                .iter()
                .map(|v| VariantData {
                    name: v.name.clone(),
                    materials: v.materials.iter().map(material).collect(),
                    removed_opacity: v.removed_opacity,
                    triangles: v.document.triangles,
                    lines: v.document.lines,
                    bytes: v.glb.len(),
                })
                .collect(),
            active_variant: if scene.variants.is_empty() {
                0
            } else {
                scene.variants.active
            },
            metrics: MetricsData {
                focus: options.focus.clone(),
                critical: options.critical.clone(),
                samples: options.samples,
                rows: rows(measured)
                    .into_iter()
                    .map(|r| RowData {
                        label: r.label,
                        cells: r.cells,
                    })
                    .collect(),
                variants: measured.iter().map(|v| v.metrics.clone()).collect(),
            },
            attribution: atlas_attribution(scene),
            style: StyleData {
                back_face: BACK_FACE,
                contour_width_px: CONTOUR_WIDTH_PX,
                contour_color: CONTOUR_COLOR,
                contour_offset: CONTOUR_OFFSET * 0.5 * bounds.diagonal(),
                wall_tint: WALL_TINT,
                wall_mix: WALL_MIX,
            },
            three: ThreeData {
                version: super::three::THREE_VERSION,
                license: super::three::THREE_LICENSE,
            },
        }
    }
}

/// The embedded head atlas's attribution when a visible model comes from it (a path ending in
/// `assets/spl_head/<file>`, as the default scene and sessions saved from it name its files).
pub fn atlas_attribution(scene: &Scene) -> Option<Attribution> {
    let from_atlas = |path: &std::path::Path| {
        let mut parts = path.iter().rev().skip(1);
        parts
            .next()
            .is_some_and(|f| f == crate::anatomy::default_scene::FOLDER)
            && parts.next().is_some_and(|a| a == "assets")
    };
    scene
        .models
        .iter()
        .any(|m| m.visible && from_atlas(&m.model.source))
        .then(|| Attribution {
            text: "Anatomy: SPL-PNL Brain Atlas (Surgical Planning Laboratory and Psychiatry \
                   Neuroimaging Laboratory, Brigham and Women's Hospital; NIH P41 EB015902, \
                   P41 RR013218, R01 MH050740), distributed with 3D Slicer under the 3D Slicer \
                   License. Research use only, not for clinical use."
                .to_string(),
            links: vec![
                (
                    "SPL-PNL Brain Atlas".to_string(),
                    "http://www.spl.harvard.edu/publications/item/view/1265".to_string(),
                ),
                (
                    "3D Slicer License".to_string(),
                    "https://github.com/Slicer/Slicer/blob/main/License.txt".to_string(),
                ),
            ],
        })
}
