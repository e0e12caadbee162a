//! The default scene: **real anatomy**, the SPL head/neck atlas label map (3D Slicer licence;
//! provenance and attribution in `assets/README.md`), compiled into the binary so that `cutaway`
//! opens on a head to cut into, face forward, with the deep structures (ventricles, basal ganglia,
//! hippocampus and amygdala, brainstem, eyes and optic nerves) inside.
//!
//! The structures come from the atlas's label map (`hncma-atlas.nrrd`, 256³, 1 mm) and its
//! colour table, embedded byte for byte and read by the same NRRD reader and label-surface
//! pipeline (`io::volume`, `csg::labels`) as any volume the user opens: names and colours from
//! the table, one model per label, grouped by anatomical system ([`groups`]). The default shows
//! the deep structures a user expects inside a head ([`selection`]: about sixty of the atlas's
//! three hundred labels, light enough to surface and draw at once); [`ALL_NAME`] is the same
//! atlas with every named structure. The atlas has no skin label, so the occluder is the atlas's
//! skin surface, decimated once offline (`assets/spl_head/decimate_skin.py`); it is first in the
//! list and the cutter's natural target.
//!
//! Earlier defaults embedded the atlas's model files (`Model_<label>_<name>.vtk`) instead of the
//! label map; sessions saved from them name those files, and [`load_missing`] serves each as the
//! surface of its label, so such sessions still open.
//!
//! The skin reads in milliseconds, the label surfaces take longer: the window shows the skin at
//! once ([`load_skin`]) and lets the structures arrive from a background job
//! ([`load_structures`]); the CLI, benches and tests take both at once ([`load`]). The atlas is in
//! RAS millimetres, so its front (anterior) is +Y: [`FRONT`] says where the camera looks from.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::DVec3;

use crate::io::volume::{LabelVolume, Structure};
use crate::io::{Format, Model};

pub mod groups;
pub mod selection;

/// The folder under `assets/` (and in the models' virtual paths).
pub const FOLDER: &str = "spl_head";

/// Menu name of the scene.
pub const NAME: &str = "head atlas";

/// Menu name of the same atlas with every structure its table names.
pub const ALL_NAME: &str = "head atlas (all structures)";

/// Direction from the head toward a viewer who faces it (RAS: anterior is +Y).
pub const FRONT: DVec3 = DVec3::Y;

/// The label map's file name under `assets/spl_head/`.
pub const ATLAS_FILE: &str = "hncma-atlas.nrrd";

/// The skin surface's file name under `assets/spl_head/`.
pub const SKIN_FILE: &str = "skin.ply";

static ATLAS: &[u8] = include_bytes!("../../../assets/spl_head/hncma-atlas.nrrd");
static TABLE: &str = include_str!("../../../assets/spl_head/hncma-atlas-lut.ctbl");
static SKIN: &[u8] = include_bytes!("../../../assets/spl_head/skin.ply");

/// Smoothing of the label surfaces: the reader's default, so the default scene is what opening
/// `hncma-atlas.nrrd` gives.
pub const SMOOTHING: f64 = 0.5;

/// Fraction of each label surface's triangles kept; `None` keeps the surfaces as extracted.
pub const DECIMATE: Option<f64> = None;

/// The virtual path of an embedded file, as if loaded from the repository's `assets/` folder.
pub fn virtual_path(file: &str) -> PathBuf {
    PathBuf::from(format!("assets/{FOLDER}/{file}"))
}

/// The whole scene: the skin, then the default's labels ([`load_skin`] + [`load_structures`]).
pub fn load() -> anyhow::Result<Vec<Model>> {
    let mut models = load_skin()?;
    models.extend(load_structures(&|_| true)?);
    Ok(models)
}

/// The skin and every structure the atlas's table names ([`ALL_NAME`]), grouped and listed as
/// [`load_structures`] lists its own. `progress` gets 0..=1 and returns false to cancel.
pub fn load_all(progress: &(dyn Fn(f32) -> bool + Sync)) -> anyhow::Result<Vec<Model>> {
    let named = table_values()?;
    let mut structures = atlas_models(|_, s| named.contains(&s.value), progress)?;
    structures.sort_by_key(|m| (groups::rank(&m.group), m.index));
    let mut models = load_skin()?;
    models.extend(structures);
    Ok(models)
}

/// The skin, one closed surface named `skin`, outside any group, with no colour of its own (the
/// anatomy colour table gives it).
pub fn load_skin() -> anyhow::Result<Vec<Model>> {
    let path = virtual_path(SKIN_FILE);
    let format = Format::from_path(&path)
        .ok_or_else(|| anyhow::anyhow!("{}: not a mesh file name", path.display()))?;
    let parts = crate::io::parse_bytes(format, SKIN, &crate::io::file_stem(&path))
        .with_context(|| path.display().to_string())?;
    Ok(crate::io::structures_of_parts(&path, parts, ""))
}

/// The embedded label map with the names and colours of its table.
pub fn atlas_volume() -> anyhow::Result<LabelVolume> {
    crate::io::volume::embedded::read_embedded(&virtual_path(ATLAS_FILE), ATLAS, TABLE)
}

/// The surface options of the default scene's labels.
pub fn surface_options() -> csg::labels::SurfaceOptions {
    csg::labels::SurfaceOptions {
        smoothing: SMOOTHING,
        decimate: DECIMATE,
        only: None,
    }
}

/// The default scene's structures ([`selection::DEFAULT_SYSTEMS`]) as models: named from the
/// table (`left hippocampus`), coloured by it, grouped by anatomical system, listed group by
/// group (deep structures first) and by label value within a group. A model's `index` is its
/// label's position in the volume's ascending label list, as when the file is opened, so
/// sessions find it again. `progress` gets 0..=1 and returns false to cancel.
pub fn load_structures(progress: &(dyn Fn(f32) -> bool + Sync)) -> anyhow::Result<Vec<Model>> {
    let mut models = atlas_models(|_, s| selection::in_default(s.value), progress)?;
    models.sort_by_key(|m| (groups::rank(&m.group), m.index));
    Ok(models)
}

/// The surfaces of the atlas's labels that `keep` accepts (given the label's position in the
/// volume's ascending label list), in label order, grouped.
fn atlas_models(
    keep: impl Fn(usize, &Structure) -> bool,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<Vec<Model>> {
    let mut volume = atlas_volume()?;
    let all = std::mem::take(&mut volume.structures);
    volume.structures = all
        .iter()
        .enumerate()
        .filter(|(k, s)| keep(*k, s))
        .map(|(_, s)| s.clone())
        .collect();
    let surfaces = crate::io::volume::surfaces_with(&volume, surface_options(), progress)
        .with_context(|| volume.source.display().to_string())?;
    Ok(surfaces
        .into_iter()
        .map(|s| {
            let label = &s.structure;
            let color = label.color.map(|c| c as f32 / 255.0);
            Model {
                source: volume.source.clone(),
                index: all
                    .iter()
                    .position(|v| (v.value, v.layer) == (label.value, label.layer))
                    .unwrap_or(0),
                group: groups::group_of(label.value, &label.name).to_owned(),
                ..Model::part(crate::io::structure_name(&label.name), Some(color), s.mesh)
            }
        })
        .collect())
}

/// The label values the atlas's colour table names.
pub fn table_values() -> anyhow::Result<Vec<u32>> {
    let table = crate::io::volume::color_table::parse(TABLE)
        .with_context(|| virtual_path("hncma-atlas-lut.ctbl").display().to_string())?;
    Ok(table.into_iter().map(|entry| entry.value).collect())
}

/// The embedded file a path names when the path does not exist on disk and ends in
/// `assets/spl_head/<file>` (as sessions saved from the default scene do): its structures, in the
/// volume's label order for the atlas (a session picks them by that index); for a model file of
/// an earlier default (`Model_<label>_<name>.vtk`) the one surface of its label, as the file held
/// it. `None` for any other path.
pub fn load_missing(path: &Path) -> Option<anyhow::Result<Vec<Model>>> {
    load_missing_picking(path, None)
}

/// [`load_missing`] for a reader that needs only the structures at positions `only` of the
/// file's list (a session's picks): the atlas then surfaces just those labels (a saved default
/// scene picks 59 of 312), each model keeping its position as `index`. Every label is surfaced,
/// as [`load_missing`] does, when `only` is `None` or names a position the atlas does not have
/// (the session's reader then says which).
pub fn load_missing_picking(
    path: &Path,
    only: Option<&[usize]>,
) -> Option<anyhow::Result<Vec<Model>>> {
    if path.exists() {
        return None;
    }
    let components: Vec<&str> = path.iter().filter_map(|c| c.to_str()).collect();
    let [.., assets, folder, file] = components.as_slice() else {
        return None;
    };
    if *assets != "assets" || *folder != FOLDER {
        return None;
    }
    // A session names the file, not the list's group: the group comes back with the entry.
    match *file {
        SKIN_FILE => Some(load_skin()),
        // Every label, as opening the file gives them: a session picks by position.
        ATLAS_FILE => Some(atlas_picking(only)),
        _ => {
            let value = old_model_label(file)?;
            Some(old_model(file, value))
        }
    }
}

/// The atlas's labels at positions `only` (all of them when `None` or out of range).
fn atlas_picking(only: Option<&[usize]>) -> anyhow::Result<Vec<Model>> {
    let labels = atlas_volume()?.structures.len();
    match only {
        Some(only) if only.iter().all(|&k| k < labels) => {
            atlas_models(|k, _| only.contains(&k), &|_| true)
        }
        _ => atlas_models(|_, _| true, &|_| true),
    }
}

/// The label value an earlier default's model file is named after: `Model_17_left_hippocampus.vtk`
/// → 17. `None` for any other name.
pub fn old_model_label(file: &str) -> Option<u32> {
    let rest = file.strip_prefix("Model_")?.strip_suffix(".vtk")?;
    let (value, name) = rest.split_once('_')?;
    (!name.is_empty()).then_some(())?;
    value.parse().ok()
}

/// The surface of label `value`, as the one structure of the model file `file` (its virtual path
/// is the model's source, so saving the session again names the same file). An error when the
/// atlas has no such label.
fn old_model(file: &str, value: u32) -> anyhow::Result<Vec<Model>> {
    let path = virtual_path(file);
    let mut models = atlas_models(|_, s| s.value == value, &|_| true)?;
    anyhow::ensure!(
        models.len() == 1,
        "{}: the head atlas has no label {value}",
        path.display()
    );
    for model in &mut models {
        model.source = path.clone();
        model.index = 0;
        model.group.clear();
    }
    Ok(models)
}

/// True when every model comes from this scene (its virtual paths or the source tree's copies).
pub fn is_default_scene(models: &[Model]) -> bool {
    !models.is_empty()
        && models.iter().all(|m| {
            let mut parts = m.source.iter().rev().skip(1);
            parts.next().is_some_and(|f| f == FOLDER) && parts.next().is_some_and(|a| a == "assets")
        })
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod old_sessions_tests;
