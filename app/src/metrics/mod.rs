//! Measures of a session's cuts, for comparing cut variants: what each cut removes, how much of a
//! focus structure the camera sees with and without the cuts, and how close the cut walls come
//! to critical structures. Units are mm, mm² and mm³: a scene in metres (guessed from its size by
//! [`LengthUnit::guess`], as the window does) is converted, so a body in metres and the same body
//! in millimetres measure the same.
//!
//! - [`removal`]: removed volume and area, wall area and depth, per cutter and per structure,
//!   from the exact boolean (the same cuts Preview draws);
//! - [`exposure`]: the visible share of a surface from the camera eye, by ray casting to
//!   area-spread samples;
//! - [`distance`]: the smallest distance between two meshes with the closest points.
//!
//! A structure is a model of the scene, named as the model list names it.

pub mod distance;
pub mod exposure;
pub mod removal;
pub mod table;
pub mod variants;

use csg::Mesh;

use crate::cutting::cut_scene::{PartKind, preview_geometry};
use crate::scene::LengthUnit;
use crate::scene::{ModelStyle, Scene};

/// What to measure besides the removal of every cut.
#[derive(Clone, Debug)]
pub struct MetricsOptions {
    /// Structure whose exposure is measured (none by default).
    pub focus: Option<String>,
    /// Structures whose distance to the cut walls is measured (none by default).
    pub critical: Vec<String>,
    /// Surface samples of the exposure estimate (default [`exposure::DEFAULT_SAMPLES`]).
    pub samples: usize,
}

impl Default for MetricsOptions {
    fn default() -> MetricsOptions {
        MetricsOptions {
            focus: None,
            critical: Vec::new(),
            samples: exposure::DEFAULT_SAMPLES,
        }
    }
}

/// The measures of one structure.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StructureMeasures {
    pub name: String,
    /// Whether the structure's surface is closed (volumes are reported only then).
    pub closed: bool,
    /// mm³ removed by all cuts (0 when uncut; `None` for an open surface).
    pub removed_volume: Option<f64>,
    /// mm² of the structure's own surface removed.
    pub removed_area: f64,
    /// mm² of walls the cuts leave on it.
    pub wall_area: f64,
    /// For a critical structure: mm from the nearest cut wall (0 when a wall touches or crosses
    /// it); `None` otherwise or when there are no walls.
    pub min_distance: Option<f64>,
    /// The closest point on the structure, and on the walls.
    pub closest_point: Option<[f64; 3]>,
    pub wall_point: Option<[f64; 3]>,
}

/// Exposure of the focus structure.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FocusMeasures {
    pub name: String,
    /// Share (0..=1) of its surface area visible from the camera without the cuts.
    pub exposure_before: f64,
    /// The same with the cuts (its surface as drawn: kept part and walls when it is cut itself).
    pub exposure_after: f64,
    /// Surface samples, each one ray from the camera eye.
    pub samples: usize,
}

/// Everything `cutaway metrics` prints.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Metrics {
    pub cutters: Vec<removal::CutterMeasures>,
    pub structures: Vec<StructureMeasures>,
    pub focus: Option<FocusMeasures>,
}

/// Measures the cuts of `scene`. Fails when a named structure does not exist or a cut is not
/// exact.
pub fn measure(scene: &Scene, options: &MetricsOptions) -> anyhow::Result<Metrics> {
    let find = |name: &str| crate::scene::names::model_named(scene, name, "");
    let focus = options.focus.as_deref().map(find).transpose()?;
    let critical = options
        .critical
        .iter()
        .map(|n| find(n))
        .collect::<anyhow::Result<Vec<_>>>()?;
    if !(1..=10_000_000).contains(&options.samples) {
        anyhow::bail!("--samples {} is outside 1..10000000", options.samples);
    }

    let cuts = removal::cut_models(scene)?;
    let mut walls = Mesh::default();
    for cut in &cuts {
        walls.append(&cut.walls());
    }
    let mut structures = Vec::new();
    for (m, model) in scene.models.iter().enumerate() {
        let cut = cuts.iter().find(|c| c.model == m);
        let closed = cut.map_or_else(|| model.model.mesh.report().closed, |c| c.model_closed);
        let cutters = cut.map_or(&[][..], |c| &c.cutters[..]);
        // Folded from +0 (an empty `sum` of floats is −0).
        let total = |value: fn(&removal::CutterMeasures) -> f64| {
            cutters.iter().map(value).fold(0.0, |a, b| a + b)
        };
        let removed_volume = closed.then(|| total(|c| c.removed_volume.unwrap_or(0.0)));
        let pair = critical
            .contains(&m)
            .then(|| distance::min_distance(&walls, &model.model.mesh))
            .flatten();
        structures.push(StructureMeasures {
            name: model.model.name.clone(),
            closed,
            removed_volume,
            removed_area: total(|c| c.removed_area),
            wall_area: total(|c| c.wall_area),
            min_distance: pair.map(|p| p.distance),
            closest_point: pair.map(|p| p.on_second.to_array()),
            wall_point: pair.map(|p| p.on_first.to_array()),
        });
    }
    let mut cutters: Vec<removal::CutterMeasures> =
        cuts.into_iter().flat_map(|c| c.cutters).collect();
    cutters.sort_by_key(|c| c.index);
    let focus = match focus {
        Some(f) => Some(focus_measures(scene, f, options.samples)?),
        None => None,
    };
    let mut metrics = Metrics {
        cutters,
        structures,
        focus,
    };
    metrics.scale_to_mm(LengthUnit::guess(&scene.bbox(), false).mm_per_unit());
    Ok(metrics)
}

/// The index of the structure (model) named `name`; the error lists every structure, so a
/// mistyped `--focus` or `--critical` says what the names are.
pub fn structure_index(scene: &Scene, name: &str) -> anyhow::Result<usize> {
    crate::scene::names::model_named(scene, name, "")
}

impl Metrics {
    /// Converts lengths, areas and volumes from file units to mm, mm² and mm³ (`mm` millimetres
    /// per file unit: 1000 for a body in metres). Points stay in file coordinates, where the
    /// window draws them.
    fn scale_to_mm(&mut self, mm: f64) {
        if mm == 1.0 {
            return;
        }
        let (area, volume) = (mm * mm, mm * mm * mm);
        for c in &mut self.cutters {
            c.removed_volume = c.removed_volume.map(|v| v * volume);
            c.removed_area *= area;
            c.wall_area *= area;
            c.depth *= mm;
        }
        for s in &mut self.structures {
            s.removed_volume = s.removed_volume.map(|v| v * volume);
            s.removed_area *= area;
            s.wall_area *= area;
            s.min_distance = s.min_distance.map(|d| d * mm);
        }
    }
}

/// Exposure of model `focus` without and with the cuts.
fn focus_measures(scene: &Scene, focus: usize, samples: usize) -> anyhow::Result<FocusMeasures> {
    Ok(FocusMeasures {
        name: scene.models[focus].model.name.clone(),
        exposure_before: exposure_uncut(scene, focus, samples)?,
        exposure_after: exposure_as_drawn(scene, focus, samples)?,
        samples,
    })
}

/// True when model `m` hides what lies behind it from the camera: drawn, opaque and solid (a
/// translucent or wireframe structure does not), and not the focus itself.
fn hides(scene: &Scene, m: usize, focus: usize) -> bool {
    let model = &scene.models[m];
    m != focus && model.visible && model.opacity >= 1.0 && model.style == ModelStyle::Solid
}

/// The error of a focus with no surface area.
fn no_area(scene: &Scene, focus: usize) -> anyhow::Error {
    anyhow::anyhow!(
        "{}: the structure has no surface area",
        scene.models[focus].model.name
    )
}

/// Share (0..=1) of model `focus`'s surface the camera sees with no cut made, every other
/// opaque visible structure in the way (`samples` rays, see [`exposure::exposure`]).
pub fn exposure_uncut(scene: &Scene, focus: usize, samples: usize) -> anyhow::Result<f64> {
    let occluders: Vec<&Mesh> = (0..scene.models.len())
        .filter(|&m| hides(scene, m, focus))
        .map(|m| &*scene.models[m].model.mesh)
        .collect();
    let camera = &scene.camera;
    exposure::exposure(
        &scene.models[focus].model.mesh,
        &occluders,
        camera.eye,
        camera.forward(),
        samples,
    )
    .ok_or_else(|| no_area(scene, focus))
}

/// Share (0..=1) of model `focus`'s surface the camera sees with nothing else in the way (every
/// other structure hidden): the most any cut can show of it from this view.
pub fn exposure_unoccluded(scene: &Scene, focus: usize, samples: usize) -> anyhow::Result<f64> {
    let camera = &scene.camera;
    exposure::exposure(
        &scene.models[focus].model.mesh,
        &[],
        camera.eye,
        camera.forward(),
        samples,
    )
    .ok_or_else(|| no_area(scene, focus))
}

/// Share (0..=1) of model `focus`'s surface the camera sees in the cut scene as drawn: every
/// structure's kept part and walls (its own too, when it is cut) in the way. Fails when a cut is
/// not exact.
pub fn exposure_as_drawn(scene: &Scene, focus: usize, samples: usize) -> anyhow::Result<f64> {
    let geometry = preview_geometry(scene);
    if let Some(note) = geometry.notes.first() {
        anyhow::bail!("{note}; metrics need exact cuts");
    }
    let drawn = |m: usize| -> Vec<&Mesh> {
        if geometry.replaced[m] {
            geometry
                .parts
                .iter()
                .filter(|p| p.model == m && p.kind != PartKind::Removed)
                .map(|p| &p.mesh)
                .collect()
        } else {
            vec![&*scene.models[m].model.mesh]
        }
    };
    let occluders: Vec<&Mesh> = (0..scene.models.len())
        .filter(|&m| hides(scene, m, focus))
        .flat_map(drawn)
        .collect();
    let mut focus_surface = Mesh::default();
    for part in drawn(focus) {
        focus_surface.append(part);
    }
    let camera = &scene.camera;
    Ok(exposure::exposure(
        &focus_surface,
        &occluders,
        camera.eye,
        camera.forward(),
        samples,
    )
    .unwrap_or(0.0))
}
