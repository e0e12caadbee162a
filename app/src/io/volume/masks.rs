//! A directory of binary masks (as TotalSegmentator writes them): one structure per volume file,
//! named after the file (`left_lung.nii.gz` → `left_lung`), every file on the same grid.
//!
//! Masks are read one after another (a whole-body folder holds over a hundred full-size masks,
//! so they are never all in memory at once) and packed into label layers: mask number n (files
//! sorted by name, counted from 1) becomes value n in the first layer where it overlaps no mask
//! packed before, so masks that do not overlap cost one label map together. Any non-zero voxel
//! is inside the mask. A different grid (dims, or a matrix differing by more than 0.001 mm) is
//! an error naming both files.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use super::{LabelData, LabelInfo, RawVolume, VolumeFormat};

/// The volume files directly inside `dir`, sorted (sub-folders are not searched: a mask folder
/// is flat).
pub fn mask_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let context = || format!("{}: cannot list directory", dir.display());
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(context)? {
        let entry = entry.with_context(context)?;
        let path = entry.path();
        let hidden = entry.file_name().to_string_lossy().starts_with('.');
        if !hidden && path.is_file() && VolumeFormat::from_path(&path).is_some() {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

pub(crate) fn read(dir: &Path) -> anyhow::Result<RawVolume> {
    let files = mask_files(dir)?;
    if files.is_empty() {
        anyhow::bail!(
            "{}: no volume files (.nrrd, .nii, .nii.gz) in this directory",
            dir.display()
        );
    }
    if files.len() > u16::MAX as usize {
        anyhow::bail!(
            "{}: {} masks is more than {}",
            dir.display(),
            files.len(),
            u16::MAX
        );
    }
    let mut packed: Option<Packed> = None;
    let mut names = Vec::with_capacity(files.len());
    for (index, file) in files.iter().enumerate() {
        let mask = super::read_file(file).with_context(|| file.display().to_string())?;
        let value = index as u16 + 1;
        match &mut packed {
            None => packed = Some(Packed::new(file, &mask)),
            Some(p) => p.check_grid(file, &mask)?,
        }
        let p = packed.as_mut().expect("set above");
        for layer in &mask.layers {
            p.add(layer, value)
                .with_context(|| format!("{}: more than 256 overlapping masks", file.display()))?;
        }
        names.push(LabelInfo {
            layer: None,
            value: value as u32,
            name: super::volume_stem(file),
            color: None,
        });
    }
    let p = packed.expect("at least one file");
    let narrow = files.len() <= u8::MAX as usize;
    Ok(RawVolume {
        dims: p.dims,
        world_from_voxel: p.world_from_voxel,
        layers: p
            .layers
            .into_iter()
            .map(|l| {
                if narrow {
                    LabelData::U8(l.into_iter().map(|v| v as u8).collect())
                } else {
                    LabelData::U16(l)
                }
            })
            .collect(),
        names,
    })
}

/// Masks packed so far.
struct Packed {
    first: PathBuf,
    dims: [usize; 3],
    world_from_voxel: glam::DAffine3,
    layers: Vec<Vec<u16>>,
}

impl Packed {
    fn new(file: &Path, mask: &RawVolume) -> Packed {
        Packed {
            first: file.to_path_buf(),
            dims: mask.dims,
            world_from_voxel: mask.world_from_voxel,
            layers: Vec::new(),
        }
    }

    fn check_grid(&self, file: &Path, mask: &RawVolume) -> anyhow::Result<()> {
        let a = self.world_from_voxel.to_cols_array();
        let b = mask.world_from_voxel.to_cols_array();
        let same_matrix = a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-3);
        if mask.dims != self.dims || !same_matrix {
            anyhow::bail!(
                "{}: not on the same grid as {} (dims {:?} vs {:?}, or a different voxel-to-world matrix); every mask of a folder must share one grid",
                file.display(),
                self.first.display(),
                mask.dims,
                self.dims
            );
        }
        Ok(())
    }

    /// Puts the non-zero voxels of `mask` into the first layer they do not overlap.
    fn add(&mut self, mask: &LabelData, value: u16) -> anyhow::Result<()> {
        let inside = |i: usize| mask.get(i) != 0;
        let n = mask.len();
        if !(0..n).any(inside) {
            return Ok(());
        }
        let free = self
            .layers
            .iter()
            .position(|layer| (0..n).all(|i| !inside(i) || layer[i] == 0));
        let layer = match free {
            Some(l) => l,
            None if self.layers.len() < 256 => {
                self.layers.push(vec![0; n]);
                self.layers.len() - 1
            }
            None => anyhow::bail!("no free layer"),
        };
        let target = &mut self.layers[layer];
        for (i, v) in target.iter_mut().enumerate() {
            if inside(i) {
                *v = value;
            }
        }
        Ok(())
    }
}
