//! Expose: the cutaway built for the user. A structure is chosen (the **focus**); Cutaway builds
//! the cutters that open the current view onto it through every structure in front of it, and
//! adds them to the scene as ordinary cutters, one per occluder (each scene cutter cuts the one
//! structure it is aimed at), editable, saved and shown in variants like painted ones.
//!
//! The geometry is the `cutter` crate's ([`cutter::expose`]); this module picks the structures
//! that hide (drawn, opaque and solid ones, as the exposure measure counts them), turns the
//! user's millimetres into model units, aims each cutter at its structure and says what was
//! opened. The window (a background job) and `cutaway expose` call the same [`plan`] and
//! [`apply`]; [`report`] measures the result for the CLI and the status line;
//! [`scene_expose`] does all three for a named focus (the CLI, batches, Python).

pub mod report;
pub mod scene_expose;

use std::sync::Arc;
use std::time::Instant;

use crate::cutting::scene_cuts::cut_each_in_turn;
use crate::platform::jobs::{Cancelled, Progress};
use crate::scene::LengthUnit;
use crate::scene::{ModelStyle, Scene, SceneCutter};

/// Margin around the focus's silhouette when the user gives none, in mm.
pub const DEFAULT_MARGIN_MM: f64 = 3.0;
/// Largest margin accepted, in mm.
pub const MAX_MARGIN_MM: f64 = 100.0;
/// Gap kept between a cutter's faces and what they clear, in mm.
pub const CLEARANCE_MM: f64 = 0.5;

/// What the user chooses about an exposure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExposeSettings {
    /// Margin around the focus's silhouette, in mm, measured across the view at the focus's
    /// nearest point. Default [`DEFAULT_MARGIN_MM`].
    pub margin_mm: f64,
}

impl Default for ExposeSettings {
    fn default() -> ExposeSettings {
        ExposeSettings {
            margin_mm: DEFAULT_MARGIN_MM,
        }
    }
}

impl ExposeSettings {
    /// Checks the margin: finite, 0..=[`MAX_MARGIN_MM`].
    pub fn check(&self) -> anyhow::Result<()> {
        if !(self.margin_mm.is_finite() && (0.0..=MAX_MARGIN_MM).contains(&self.margin_mm)) {
            anyhow::bail!(
                "margin {} mm is outside 0..{MAX_MARGIN_MM} mm",
                self.margin_mm
            );
        }
        Ok(())
    }
}

/// The cutters an exposure adds, and what they open.
#[derive(Clone, Debug)]
pub struct Exposed {
    /// The focus: index into the scene's models.
    pub focus: usize,
    /// The new cutters, each aimed at the structure it opens, nearest first.
    pub cutters: Vec<SceneCutter>,
    /// The structures opened, in the order of their first cutter (each once).
    pub opened: Vec<usize>,
    /// Share (0..=1) of the focus's image that something hid before.
    pub hidden: f64,
    /// Cutters that could not be made, one line each (the cut is then incomplete).
    pub notes: Vec<String>,
    /// Wall time of building and checking the cutters, in ms.
    pub expose_ms: f64,
}

/// The structures that may hide `focus`: drawn, opaque, solid and with a surface (as the
/// exposure measure counts them), other than the focus.
pub fn occluders_of(scene: &Scene, focus: usize) -> Vec<usize> {
    (0..scene.models.len())
        .filter(|&m| {
            let model = &scene.models[m];
            m != focus
                && model.visible
                && model.opacity >= 1.0
                && model.style == ModelStyle::Solid
                && !model.model.mesh.triangles.is_empty()
        })
        .collect()
}

/// The cutters that open the scene camera's view onto model `focus` (see the module docs).
/// The scene's cutters are taken into account: the structures are looked at as they are drawn,
/// cut, and each new cutter cuts what the cutters before it left. `progress` is checked between
/// steps; a cancelled plan fails with [`crate::platform::jobs::Cancelled`].
pub fn plan(
    scene: &Scene,
    focus: usize,
    settings: &ExposeSettings,
    progress: &Progress,
) -> anyhow::Result<Exposed> {
    settings.check()?;
    let Some(model) = scene.models.get(focus) else {
        anyhow::bail!(
            "no structure {focus} (the scene has {})",
            scene.models.len()
        );
    };
    let started = Instant::now();
    let surfaces = drawn_surfaces(scene, progress)?;
    let unit = LengthUnit::guess(&scene.bbox(), false);
    let options = cutter::expose::ExposeOptions::default()
        .with_margin(unit.from_mm(settings.margin_mm))
        .with_clearance(unit.from_mm(CLEARANCE_MM));
    let occluders = occluders_of(scene, focus);
    let meshes: Vec<&csg::Mesh> = occluders.iter().map(|&m| &*surfaces[m]).collect();
    let view = cutter::expose::ExposeView::of_camera(&scene.camera);
    let keep_going = || !progress.is_cancelled();
    let exposure = cutter::expose::expose(&surfaces[focus], &meshes, &view, &options, &keep_going)
        .map_err(|e| match e {
            cutter::expose::ExposeError::Cancelled => anyhow::Error::new(Cancelled),
            e => anyhow::anyhow!("{}: {e}", model.model.name),
        })?;
    let mut opened = Vec::new();
    let cutters: Vec<SceneCutter> = exposure
        .cutters
        .into_iter()
        .map(|c| {
            let target = occluders[c.occluder];
            if !opened.contains(&target) {
                opened.push(target);
            }
            SceneCutter::new(target, c.cutter)
        })
        .collect();
    let notes = exposure
        .notes
        .iter()
        .map(|n| name_occluder(n, scene, &occluders))
        .collect();
    Ok(Exposed {
        focus,
        cutters,
        opened,
        hidden: exposure.hidden,
        notes,
        expose_ms: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// Every model's surface as drawn: a model its cutters cut (those that show anything) is its
/// kept part closed by the walls, as the next cutter aimed at it cuts it; the others their mesh.
fn drawn_surfaces(scene: &Scene, progress: &Progress) -> anyhow::Result<Vec<Arc<csg::Mesh>>> {
    let mut shown = scene.clone();
    shown.cutters.retain(|c| c.views.any());
    let cut = if shown.cutters.is_empty() {
        vec![None; scene.models.len()]
    } else {
        cut_each_in_turn(&shown, progress, |_, _| Ok(()))?
    };
    Ok(cut
        .into_iter()
        .zip(&scene.models)
        .map(|(cut, model)| cut.unwrap_or_else(|| model.model.mesh.clone()))
        .collect())
}

/// A note of the cutter crate (`occluder k: …`) with the structure's name.
fn name_occluder(note: &str, scene: &Scene, occluders: &[usize]) -> String {
    let named = note.strip_prefix("occluder ").and_then(|rest| {
        let (k, why) = rest.split_once(": ")?;
        let model = occluders.get(k.parse::<usize>().ok()?)?;
        Some(format!("{}: {why}", scene.models[*model].model.name))
    });
    named.unwrap_or_else(|| note.to_string())
}

/// Adds the exposure's cutters to the scene (the active variant's cutters) and shows the focus.
pub fn apply(scene: &mut Scene, exposed: &Exposed) {
    if let Some(model) = scene.models.get_mut(exposed.focus) {
        model.visible = true;
    }
    scene.cutters.extend(exposed.cutters.iter().cloned());
}

/// The one line that says what an exposure did: "Exposed left caudate: 2 cutters through skin,
/// left putamen; 41 mm³ removed" (`removed_mm3` when it was measured).
pub fn summary(scene: &Scene, exposed: &Exposed, removed_mm3: Option<f64>) -> String {
    let focus = scene
        .models
        .get(exposed.focus)
        .map_or("the structure", |m| m.model.name.as_str());
    if exposed.cutters.is_empty() {
        return if exposed.notes.is_empty() {
            format!("{focus} is in full view: nothing to open")
        } else {
            format!("{focus} could not be exposed: {}", exposed.notes.join("; "))
        };
    }
    let names: Vec<&str> = exposed
        .opened
        .iter()
        .map(|&m| scene.models[m].model.name.as_str())
        .collect();
    let count = exposed.cutters.len();
    let mut line = format!(
        "Exposed {focus}: {count} cutter{} through {}",
        if count == 1 { "" } else { "s" },
        list_names(&names)
    );
    if let Some(v) = removed_mm3 {
        line.push_str(&format!("; {} mm³ removed", format_volume(v)));
    }
    if !exposed.notes.is_empty() {
        line.push_str(&format!(" (not opened: {})", exposed.notes.join("; ")));
    }
    line
}

/// Names joined with commas, at most three (the nearest), then "and N more": the line fits the
/// status bar.
fn list_names(names: &[&str]) -> String {
    const SHOWN: usize = 3;
    if names.len() <= SHOWN {
        return names.join(", ");
    }
    format!(
        "{} and {} more",
        names[..SHOWN].join(", "),
        names.len() - SHOWN
    )
}

/// A volume in mm³ with the digits that matter: 41, 1,250, 0.42.
fn format_volume(v: f64) -> String {
    if v >= 100.0 {
        let digits = format!("{:.0}", v);
        let mut out = String::new();
        for (i, c) in digits.chars().enumerate() {
            if i > 0 && (digits.len() - i).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    } else if v >= 10.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    }
}

#[cfg(test)]
mod tests;
