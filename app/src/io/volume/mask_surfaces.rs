//! A folder of masks surfaced one mask at a time, as its files are read.
//!
//! A TotalSegmentator folder holds over a hundred masks, each the full CT grid and mostly zeros.
//! Packing them into label maps first ([`super::read_volume`]) means every mask is read before
//! the first surface is made, and a full-size map is held and scanned again. Here each worker
//! inflates one mask (into its reused buffer, [`super::masks`]), keeps the mask's non-zero runs,
//! paints them into a grid of the mask's own bounding box and surfaces that grid at once: the
//! first structures are ready (written, or shown in the window) while the other files are still
//! being read, and nothing of the full grid outlives a file's inflate.
//!
//! The surfaces are those of the packed path: the same grid, the same binary mask (any non-zero
//! voxel is inside), the box only moves the voxel origin (`world_from_voxel` shifted by the box's
//! corner). Masks may overlap freely: each is its own grid. Values and names follow the packed
//! path too: mask number n (files sorted by name, from 1) is value n, named after its file, with
//! a colour table's name and colour for that value when one is given. A mask with no voxel gives
//! no structure. Every mask must share the first file's grid; a different one is an error naming
//! both files, before its surface is made.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use anyhow::Context as _;
use glam::{DAffine3, DVec3};
use rayon::prelude::*;

use super::masks::{BoxedMask, Mask, mask_files, read_mask};
use super::{LabelInfo, Structure, StructureSurface};

/// What a mask folder held, once every mask was surfaced.
#[derive(Clone, Debug)]
pub struct MaskFolder {
    pub dims: [usize; 3],
    pub world_from_voxel: DAffine3,
    /// The masks with voxels, ascending value.
    pub structures: Vec<Structure>,
}

/// Surfaces every mask of `dir`, handing each file's outcome to `each` as soon as it is known:
/// its number (files sorted by name, from 0) and its structure's surface, None for a mask with
/// no voxel. Files are taken in order by every worker, so outcomes come nearly in file order
/// (a window shows them in order as they come); `each` runs on the worker and returns false to
/// stop. `names` (a colour table) names and colours values as in [`super::read_volume`].
/// `progress` gets the fraction of files done and returns false to cancel. Errors name the file.
pub fn surfaces_each(
    dir: &Path,
    names: &[LabelInfo],
    options: &csg::labels::SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
    each: &(dyn Fn(usize, Option<StructureSurface>) -> bool + Sync),
) -> anyhow::Result<MaskFolder> {
    let files = mask_files(dir)?;
    let Some(first_file) = files.first() else {
        anyhow::bail!(
            "{}: no volume files (.nrrd, .nii, .nii.gz) in this directory",
            dir.display()
        );
    };
    let first = read_mask(first_file).with_context(|| first_file.display().to_string())?;
    let (dims, world_from_voxel) = (first.dims, first.world_from_voxel);
    let first = Mutex::new(Some(first));
    let found = Mutex::new(Vec::new());
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let one = |index: usize| -> anyhow::Result<()> {
        let file = &files[index];
        let taken = if index == 0 {
            lock(&first).take()
        } else {
            None
        };
        let mask = match taken {
            Some(mask) => mask,
            None => read_mask(file).with_context(|| file.display().to_string())?,
        };
        same_grid(&mask, dims, world_from_voxel, file, first_file)?;
        let value = index as u32 + 1;
        let surface = match mask.boxed() {
            Some(boxed) => {
                let structure = structure_of(boxed.voxels, value, file, names);
                let mesh = surface(&boxed, mask.world_from_voxel, options)
                    .with_context(|| file.display().to_string())?;
                lock(&found).push(structure.clone());
                Some(StructureSurface { structure, mesh })
            }
            None => None,
        };
        let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
        if !each(index, surface) || !progress(finished as f32 / files.len() as f32) {
            stop.store(true, Ordering::Relaxed);
        }
        Ok(())
    };
    (0..rayon::current_num_threads())
        .into_par_iter()
        .try_for_each(|_| {
            loop {
                let index = next.fetch_add(1, Ordering::Relaxed);
                if index >= files.len() || stop.load(Ordering::Relaxed) {
                    return Ok(());
                }
                if let Err(e) = one(index) {
                    stop.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
        })?;
    if stop.load(Ordering::Relaxed) {
        return Err(csg::labels::LabelSurfaceError::Cancelled)
            .with_context(|| dir.display().to_string());
    }
    let mut structures = found.into_inner().unwrap_or_else(|e| e.into_inner());
    if structures.is_empty() {
        anyhow::bail!(
            "{}: empty label map: every voxel is 0 (background)",
            dir.display()
        );
    }
    structures.sort_by_key(|s| s.value);
    Ok(MaskFolder {
        dims,
        world_from_voxel,
        structures,
    })
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

fn same_grid(
    mask: &Mask,
    dims: [usize; 3],
    world_from_voxel: DAffine3,
    file: &Path,
    first: &Path,
) -> anyhow::Result<()> {
    let a = world_from_voxel.to_cols_array();
    let b = mask.world_from_voxel.to_cols_array();
    let same_matrix = a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-3);
    if mask.dims != dims || !same_matrix {
        anyhow::bail!(
            "{}: not on the same grid as {} (dims {:?} vs {:?}, or a different voxel-to-world matrix); every mask of a folder must share one grid",
            file.display(),
            first.display(),
            mask.dims,
            dims
        );
    }
    Ok(())
}

/// The structure of mask number `value`, named and coloured as the packed path does.
fn structure_of(voxels: u64, value: u32, file: &Path, names: &[LabelInfo]) -> Structure {
    let info = names
        .iter()
        .find(|n| n.value == value && n.layer.is_none_or(|l| l == 0));
    Structure {
        layer: 0,
        value,
        name: info.map_or_else(|| super::volume_stem(file), |i| i.name.clone()),
        color: info
            .and_then(|i| i.color)
            .unwrap_or_else(|| super::default_color(value)),
        voxels,
    }
}

/// The surface of a mask's box grid.
fn surface(
    boxed: &BoxedMask,
    world_from_voxel: DAffine3,
    options: &csg::labels::SurfaceOptions,
) -> anyhow::Result<csg::Mesh> {
    let corner = DVec3::new(boxed.lo[0] as f64, boxed.lo[1] as f64, boxed.lo[2] as f64);
    let world_from_box = world_from_voxel * DAffine3::from_translation(corner);
    let grid = csg::labels::LabelGrid::new(boxed.dims, &boxed.inside, world_from_box)?;
    let options = csg::labels::SurfaceOptions {
        only: Some(vec![1]),
        ..options.clone()
    };
    let made = csg::labels::label_surfaces(&grid, &options, &|_| true)?;
    made.into_iter()
        .next()
        .map(|s| s.mesh)
        .ok_or_else(|| anyhow::anyhow!("the mask's voxels gave no surface"))
}
