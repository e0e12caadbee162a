//! A directory of binary masks (as TotalSegmentator writes them): one structure per volume file,
//! named after the file (`left_lung.nii.gz` → `left_lung`), every file on the same grid.
//!
//! Masks are read in parallel, a uint8 NIfTI mask (what TotalSegmentator writes) inflated a
//! chunk at a time straight into the runs of its non-zero voxels along x: a whole-body folder
//! holds over a hundred full-size masks, mostly zeros, and no full-size buffer is touched per
//! file. Other masks are decoded whole, then kept as their runs. The runs are then packed into label layers in
//! file order: mask number n (files sorted by name, counted from 1) becomes value n in the first
//! layer where it overlaps no mask packed before, so masks that do not overlap cost one label
//! map together. Any non-zero voxel is inside the mask. A different grid (dims, or a matrix
//! differing by more than 0.001 mm) is an error naming both files.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use rayon::prelude::*;

use super::samples::SampleType;
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
    let masks = files
        .par_iter()
        .map(|file| read_mask(file).with_context(|| file.display().to_string()))
        .collect::<anyhow::Result<Vec<Mask>>>()?;
    let mut packed: Option<Packed> = None;
    let mut names = Vec::with_capacity(files.len());
    for (index, (file, mask)) in files.iter().zip(&masks).enumerate() {
        let value = index as u16 + 1;
        match &mut packed {
            None => packed = Some(Packed::new(file, mask)),
            Some(p) => p.check_grid(file, mask)?,
        }
        let p = packed.as_mut().expect("set above");
        for runs in &mask.layers {
            p.add(runs, value)
                .with_context(|| format!("{}: more than 256 overlapping masks", file.display()))?;
        }
        names.push(LabelInfo {
            layer: None,
            value: value as u32,
            name: super::volume_stem(file),
            color: None,
        });
    }
    drop(masks);
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

/// One mask file: its grid and, per layer, the runs `[start, end)` of flat voxel indices that
/// are not zero.
pub(super) struct Mask {
    pub dims: [usize; 3],
    pub world_from_voxel: glam::DAffine3,
    pub layers: Vec<Vec<[usize; 2]>>,
}

/// A mask painted into a grid of its bounding box (x fastest): 1 inside, 0 outside.
pub(super) struct BoxedMask {
    /// The box's first voxel in the mask's grid.
    pub lo: [usize; 3],
    pub dims: [usize; 3],
    pub inside: Vec<u8>,
    /// Voxels inside (every layer's together).
    pub voxels: u64,
}

impl Mask {
    /// Calls `visit(x0, x1, y, z)` for each piece of a run within one row (`x0..x1`).
    fn row_pieces(&self, mut visit: impl FnMut(usize, usize, usize, usize)) {
        let [nx, ny, _] = self.dims;
        for &[start, end] in self.layers.iter().flatten() {
            let mut i = start;
            while i < end {
                let row = i / nx;
                let piece_end = end.min((row + 1) * nx);
                visit(i % nx, i % nx + (piece_end - i), row % ny, row / ny);
                i = piece_end;
            }
        }
    }

    /// The mask in a grid of its bounding box; None when it has no voxel.
    pub fn boxed(&self) -> Option<BoxedMask> {
        let (mut lo, mut hi) = ([usize::MAX; 3], [0usize; 3]);
        self.row_pieces(|x0, x1, y, z| {
            for (axis, (a, b)) in [(x0, x1 - 1), (y, y), (z, z)].into_iter().enumerate() {
                lo[axis] = lo[axis].min(a);
                hi[axis] = hi[axis].max(b);
            }
        });
        if lo[0] == usize::MAX {
            return None;
        }
        let dims = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
        let mut inside = vec![0u8; dims.iter().product()];
        self.row_pieces(|x0, x1, y, z| {
            let row = (y - lo[1] + dims[1] * (z - lo[2])) * dims[0];
            inside[row + x0 - lo[0]..row + x1 - lo[0]].fill(1);
        });
        let voxels = inside.iter().map(|&v| u64::from(v)).sum();
        Some(BoxedMask {
            lo,
            dims,
            inside,
            voxels,
        })
    }
}

/// Bytes of inflated voxel data a mask's reader holds at a time.
const CHUNK: usize = 1 << 20;

pub(super) fn read_mask(file: &Path) -> anyhow::Result<Mask> {
    read_mask_chunked(file, CHUNK)
}

/// [`read_mask`] holding `chunk` bytes of inflated voxel data at a time.
pub(super) fn read_mask_chunked(file: &Path, chunk: usize) -> anyhow::Result<Mask> {
    if super::file_format(file)? == VolumeFormat::Nifti {
        let stream = super::nifti::SampleStream::open(file)?;
        let (dims, world_from_voxel) = (stream.dims.map(|d| d as usize), stream.world_from_voxel);
        if stream.sample == SampleType::U8 {
            // The common case (TotalSegmentator writes uint8): the runs straight from the
            // inflated bytes, a chunk at a time, so no mask is ever held whole.
            let mut runs: Vec<[usize; 2]> = Vec::new();
            stream.chunks(chunk, &mut |offset, bytes| {
                for [start, end] in byte_runs(bytes) {
                    let (start, end) = (offset + start, offset + end);
                    match runs.last_mut() {
                        // A run cut by the chunk's edge continues.
                        Some(last) if last[1] == start => last[1] = end,
                        _ => runs.push([start, end]),
                    }
                }
            })?;
            return Ok(Mask {
                dims,
                world_from_voxel,
                layers: vec![runs],
            });
        }
        let raw = super::nifti::read_samples(file)?;
        let layer = super::samples::decode(&raw.bytes, raw.sample, raw.endian, raw.dims)?;
        return Ok(Mask {
            dims,
            world_from_voxel,
            layers: vec![runs_of(layer.len(), |i| layer.get(i) != 0)],
        });
    }
    let volume = super::read_file(file)?;
    Ok(Mask {
        dims: volume.dims,
        world_from_voxel: volume.world_from_voxel,
        layers: volume
            .layers
            .iter()
            .map(|layer| runs_of(layer.len(), |i| layer.get(i) != 0))
            .collect(),
    })
}

/// The runs `[start, end)` of the non-zero bytes of `bytes`. A mask is mostly zeros, so the
/// zeros are skipped eight bytes at a time: this scan reads every voxel of every mask of a folder
/// (a whole-body folder: over fifteen billion), and byte by byte it cost more than inflating them.
fn byte_runs(bytes: &[u8]) -> Vec<[usize; 2]> {
    const WORD: usize = 8;
    let zero_word = |i: usize| {
        bytes
            .get(i..i + WORD)
            .is_some_and(|w| u64::from_ne_bytes(w.try_into().expect("eight bytes")) == 0)
    };
    let mut runs = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if i % WORD == 0 && zero_word(i) {
            i += WORD;
        } else if bytes[i] == 0 {
            i += 1;
        } else {
            let start = i;
            while i < bytes.len() && bytes[i] != 0 {
                i += 1;
            }
            runs.push([start, i]);
        }
    }
    runs
}

/// The runs `[start, end)` of `0..n` where `inside` holds.
pub(super) fn runs_of(n: usize, inside: impl Fn(usize) -> bool) -> Vec<[usize; 2]> {
    let mut runs = Vec::new();
    let mut i = 0;
    while i < n {
        if inside(i) {
            let start = i;
            while i < n && inside(i) {
                i += 1;
            }
            runs.push([start, i]);
        } else {
            i += 1;
        }
    }
    runs
}

/// Masks packed so far.
struct Packed {
    first: PathBuf,
    dims: [usize; 3],
    world_from_voxel: glam::DAffine3,
    layers: Vec<Vec<u16>>,
}

impl Packed {
    fn new(file: &Path, mask: &Mask) -> Packed {
        Packed {
            first: file.to_path_buf(),
            dims: mask.dims,
            world_from_voxel: mask.world_from_voxel,
            layers: Vec::new(),
        }
    }

    fn check_grid(&self, file: &Path, mask: &Mask) -> anyhow::Result<()> {
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

    /// Puts the voxels of `runs` into the first layer they do not overlap.
    fn add(&mut self, runs: &[[usize; 2]], value: u16) -> anyhow::Result<()> {
        if runs.is_empty() {
            return Ok(());
        }
        let n = self.dims.iter().product();
        let free = self.layers.iter().position(|layer| {
            runs.iter()
                .all(|&[start, end]| layer[start..end].iter().all(|&v| v == 0))
        });
        let layer = match free {
            Some(l) => l,
            None if self.layers.len() < 256 => {
                self.layers.push(vec![0; n]);
                self.layers.len() - 1
            }
            None => anyhow::bail!("no free layer"),
        };
        let target = &mut self.layers[layer];
        for &[start, end] in runs {
            target[start..end].fill(value);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run that wraps from one row to the next lands in both rows of the box, and the box is
    /// the runs' bounds.
    #[test]
    fn boxed_mask_splits_runs_at_rows() {
        let dims = [4, 3, 2];
        // Row (y 1, z 0) from x 2 to the end, the next row up to x 1; one voxel at (3, 2, 1).
        let at = |x: usize, y: usize, z: usize| x + 4 * (y + 3 * z);
        let mask = Mask {
            dims,
            world_from_voxel: glam::DAffine3::IDENTITY,
            layers: vec![
                vec![[at(2, 1, 0), at(2, 2, 0)]],
                vec![[at(3, 2, 1), at(3, 2, 1) + 1]],
            ],
        };
        let b = mask.boxed().unwrap();
        assert_eq!((b.lo, b.dims, b.voxels), ([0, 1, 0], [4, 2, 2], 5));
        let inside = |x: usize, y: usize, z: usize| b.inside[x + 4 * (y - 1 + 2 * z)] == 1;
        let expected = [(2, 1, 0), (3, 1, 0), (0, 2, 0), (1, 2, 0), (3, 2, 1)];
        for z in 0..2 {
            for y in 1..3 {
                for x in 0..4 {
                    assert_eq!(
                        inside(x, y, z),
                        expected.contains(&(x, y, z)),
                        "{x} {y} {z}"
                    );
                }
            }
        }
        let empty = Mask {
            layers: vec![Vec::new()],
            ..mask
        };
        assert!(empty.boxed().is_none());
    }

    /// The word-skipping scan finds the runs of the plain one, at every alignment and length.
    #[test]
    fn byte_runs_are_the_plain_runs() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for len in [0usize, 1, 7, 8, 9, 15, 16, 17, 63, 64, 65, 1000] {
            for density in [0u64, 1, 8, 64, 200, 256] {
                let bytes: Vec<u8> = (0..len)
                    .map(|_| {
                        state ^= state << 13;
                        state ^= state >> 7;
                        state ^= state << 17;
                        u8::from(state % 256 < density) * (1 + (state >> 8) as u8 % 3)
                    })
                    .collect();
                let plain = runs_of(bytes.len(), |i| bytes[i] != 0);
                assert_eq!(byte_runs(&bytes), plain, "length {len}, density {density}");
            }
        }
    }
}
