//! Segmentation label volumes: NRRD (`.nrrd`, `.nhdr` + data file, Slicer `.seg.nrrd`), NIfTI-1/2
//! (`.nii`, `.nii.gz`) and directories of binary masks, read into one [`LabelVolume`] whose
//! structures (one per label value present, with name and colour) become meshes through
//! [`csg::labels::label_surfaces`].
//!
//! # Geometry
//! `world_from_voxel` maps a voxel index (i, j, k) to **RAS millimetres** (+x toward the
//! patient's right, +y anterior, +z superior, as in 3D Slicer). NRRD files in LPS (`space:
//! left-posterior-superior`, and `scanner-xyz`, which is DICOM's LPS patient frame) are converted
//! by negating x and y; NIfTI sform/qform is RAS by definition. A flipped or permuted axis is just
//! another matrix: the surface code fixes the winding once from the determinant's sign, so the
//! same anatomy stored with different axis orders gives the same surfaces. Meshes are never
//! converted: they keep their own coordinates (3D Slicer exports models in LPS by default).
//!
//! # Names and colours
//! A structure's name and colour come, in this order of preference, from a colour table given
//! with `--labels`, the file's own segment metadata (Slicer `SegmentN_Name/_Color/_LabelValue/
//! _Layer`), a colour table beside the volume ([`color_table::find_beside`]), the mask file's
//! name; else `label 17` and a stable colour of its own ([`default_color`]).
//!
//! # Layers
//! Overlapping Slicer segmentations store one label map per layer (a 4-D file whose first axis
//! is the layer list); a structure is then a (layer, value) pair. Mask directories use the same
//! model: masks that do not overlap share a layer, so a TotalSegmentator folder costs one label
//! map, not one per structure.
//!
//! # Bad input
//! Sizes are checked against [`MAX_AXIS`] and [`MAX_VOXELS`] and against the bytes actually
//! present before any buffer of that size is allocated; gzip streams are inflated with a limit
//! one byte past the expected size, so a lying header or a decompression bomb ends in an error.
//! Every error is one line and names the file.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::{DAffine3, DMat3, DVec3};

pub mod array;
pub mod color_table;
pub mod content;
mod content_rule;
pub mod embedded;
mod gzip;
pub mod intensity;
pub mod mask_surfaces;
mod masks;
mod nifti;
mod nrrd;
pub mod samples;
mod segments;

/// Largest size of one axis.
pub const MAX_AXIS: usize = 2048;
/// Largest number of voxels (all layers together).
pub const MAX_VOXELS: u64 = 4_000_000_000;

/// One label map, x fastest: value at (i, j, k) is `data[i + dims[0] * (j + dims[1] * k)]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LabelData {
    U8(Vec<u8>),
    U16(Vec<u16>),
    U32(Vec<u32>),
}

impl LabelData {
    pub fn len(&self) -> usize {
        match self {
            LabelData::U8(v) => v.len(),
            LabelData::U16(v) => v.len(),
            LabelData::U32(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        match self {
            LabelData::U8(v) => v.len(),
            LabelData::U16(v) => v.len() * 2,
            LabelData::U32(v) => v.len() * 4,
        }
    }

    /// Voxel count per non-zero value, ascending.
    pub fn counts(&self, dims: [usize; 3]) -> anyhow::Result<Vec<(u32, u64)>> {
        Ok(match self {
            LabelData::U8(v) => csg::labels::label_counts(&grid(dims, v)?),
            LabelData::U16(v) => csg::labels::label_counts(&grid(dims, v)?),
            LabelData::U32(v) => csg::labels::label_counts(&grid(dims, v)?),
        })
    }

    /// The value at flat index `index`.
    pub fn get(&self, index: usize) -> u32 {
        match self {
            LabelData::U8(v) => v[index] as u32,
            LabelData::U16(v) => v[index] as u32,
            LabelData::U32(v) => v[index],
        }
    }
}

fn grid<T: csg::labels::LabelValue>(
    dims: [usize; 3],
    data: &[T],
) -> anyhow::Result<csg::labels::LabelGrid<'_, T>> {
    csg::labels::LabelGrid::new(dims, data, DAffine3::IDENTITY).map_err(anyhow::Error::from)
}

/// One structure of a volume: a label value present in one layer.
#[derive(Clone, Debug, PartialEq)]
pub struct Structure {
    pub layer: usize,
    pub value: u32,
    pub name: String,
    /// sRGB, 0..=255.
    pub color: [u8; 3],
    pub voxels: u64,
}

/// A label volume read from a file or a mask directory.
#[derive(Clone, Debug)]
pub struct LabelVolume {
    pub source: PathBuf,
    pub dims: [usize; 3],
    /// Voxel index → world RAS millimetres.
    pub world_from_voxel: DAffine3,
    /// One label map per layer, each `dims` product long.
    pub layers: Vec<LabelData>,
    /// The labels present (voxels > 0), ascending value, then layer.
    pub structures: Vec<Structure>,
}

impl LabelVolume {
    /// Voxel size along i, j, k in millimetres (the lengths of the matrix columns).
    pub fn spacing(&self) -> [f64; 3] {
        let m = self.world_from_voxel.matrix3;
        [m.x_axis.length(), m.y_axis.length(), m.z_axis.length()]
    }
}

/// A name and/or colour for a label value, from a file's metadata or a colour table.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelInfo {
    /// `None`: every layer (colour tables); `Some(l)`: this layer only (Slicer segments).
    pub layer: Option<usize>,
    pub value: u32,
    pub name: String,
    pub color: Option<[u8; 3]>,
}

/// What a reader hands over: the grid and whatever names the file itself carries.
#[derive(Debug)]
pub(crate) struct RawVolume {
    pub dims: [usize; 3],
    pub world_from_voxel: DAffine3,
    pub layers: Vec<LabelData>,
    pub names: Vec<LabelInfo>,
}

/// What a reader hands over for an intensity image: the grid and its samples at their own type,
/// decompressed but not decoded (the file's byte order), one layer after another.
#[derive(Debug)]
pub(crate) struct RawSamples {
    pub dims: [usize; 3],
    pub world_from_voxel: DAffine3,
    pub layers: usize,
    pub sample: samples::SampleType,
    pub endian: samples::Endian,
    pub bytes: Vec<u8>,
    /// Stored value → real value: `value * scale.0 + scale.1` (NIfTI `scl_slope`/`scl_inter`).
    pub scale: (f64, f64),
}

/// The volume formats, by how the file is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeFormat {
    Nrrd,
    Nifti,
}

impl VolumeFormat {
    /// The format a file name's extension names (case-insensitive): `.nrrd`, `.nhdr`
    /// (`.seg.nrrd` included), `.nii`, `.nii.gz`.
    pub fn from_path(path: &Path) -> Option<VolumeFormat> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        if name.ends_with(".nrrd") || name.ends_with(".nhdr") {
            Some(VolumeFormat::Nrrd)
        } else if name.ends_with(".nii") || name.ends_with(".nii.gz") {
            Some(VolumeFormat::Nifti)
        } else {
            None
        }
    }

    /// Recognises a volume by its first bytes: the NRRD magic `NRRD000`, or a NIfTI-1/2
    /// header size (348 or 540, either byte order) with its magic. A gzip stream is not looked
    /// into (`.nii.gz` is recognised by its name).
    pub fn sniff(bytes: &[u8]) -> Option<VolumeFormat> {
        if bytes.starts_with(b"NRRD000") {
            return Some(VolumeFormat::Nrrd);
        }
        nifti::sniff(bytes).then_some(VolumeFormat::Nifti)
    }

    pub fn name(self) -> &'static str {
        match self {
            VolumeFormat::Nrrd => "NRRD",
            VolumeFormat::Nifti => "NIfTI",
        }
    }
}

/// Whether `path` is read as a label volume: a file with a volume extension (or, without a mesh
/// extension, whose content starts like a volume), or a directory holding volume files and no
/// mesh files (a mask directory; otherwise it is a mesh directory, whose volume files are not
/// read as masks).
pub fn is_volume(path: &Path) -> bool {
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => {
            masks::mask_files(path).is_ok_and(|files| !files.is_empty())
                && super::mesh_files(path).is_ok_and(|files| files.is_empty())
        }
        Ok(m) if m.is_file() => {
            VolumeFormat::from_path(path).is_some()
                || (super::Format::from_path(path).is_none() && sniff_file(path).is_some())
        }
        _ => false,
    }
}

fn sniff_file(path: &Path) -> Option<VolumeFormat> {
    use std::io::Read as _;
    // Only regular files: opening a FIFO would block.
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return None;
    }
    let mut head = [0u8; 348];
    let mut file = std::fs::File::open(path).ok()?;
    let mut filled = 0;
    while filled < head.len() {
        match file.read(&mut head[filled..]) {
            Ok(0) | Err(_) => break,
            Ok(n) => filled += n,
        }
    }
    VolumeFormat::sniff(&head[..filled])
}

/// Reads a volume file or mask directory with its names and colours (`labels`: a colour table
/// that overrides all other sources). Errors name the file.
/// A file that holds an intensity image rather than labels ([`content`]) is an error that says so.
pub fn read_volume(path: &Path, labels: Option<&Path>) -> anyhow::Result<LabelVolume> {
    match content::read_content(path, labels)? {
        content::VolumeContent::Labels(volume) => Ok(volume),
        content::VolumeContent::Image { reason, .. } => anyhow::bail!(
            "{}: an intensity image ({reason}), not a segmentation: open it as the image (--image, or Open Image… in the File menu)",
            path.display()
        ),
    }
}

/// [`read_volume`] of a label map, from the reader's `raw` volume when the caller has read it
/// already (files), else read here (mask folders).
fn read_volume_labels(
    path: &Path,
    labels: Option<&Path>,
    raw: Option<RawVolume>,
) -> anyhow::Result<LabelVolume> {
    let table = match labels {
        Some(table) => color_table::read(table)?,
        None => Vec::new(),
    };
    let metadata = std::fs::metadata(path).with_context(|| path.display().to_string())?;
    let (raw, beside) = if metadata.is_dir() {
        (masks::read(path)?, Vec::new())
    } else {
        let raw = match raw {
            Some(raw) => raw,
            None => read_file(path).with_context(|| path.display().to_string())?,
        };
        // A file that names its own structures needs no table from the folder.
        let beside = if raw.names.is_empty() && labels.is_none() {
            color_table::find_beside(path)?
        } else {
            Vec::new()
        };
        (raw, beside)
    };
    finish(path, raw, &[table, beside].concat()).with_context(|| path.display().to_string())
}

fn read_file(path: &Path) -> anyhow::Result<RawVolume> {
    match file_format(path)? {
        VolumeFormat::Nrrd => nrrd::read(path),
        VolumeFormat::Nifti => nifti::read(path),
    }
}

/// The format of a volume file, by its name or else its first bytes.
fn file_format(path: &Path) -> anyhow::Result<VolumeFormat> {
    match VolumeFormat::from_path(path) {
        Some(format) => Ok(format),
        None => sniff_file(path).ok_or_else(|| {
            anyhow::anyhow!("not a volume (expected .nrrd, .nhdr, .seg.nrrd, .nii or .nii.gz)")
        }),
    }
}

/// Counts voxels, resolves names and colours (`names` first, then the file's own), and refuses
/// an empty label map.
fn finish(source: &Path, raw: RawVolume, names: &[LabelInfo]) -> anyhow::Result<LabelVolume> {
    let mut structures = Vec::new();
    for (layer, data) in raw.layers.iter().enumerate() {
        for (value, voxels) in data.counts(raw.dims)? {
            let find = |infos: &[LabelInfo]| {
                infos
                    .iter()
                    .find(|n| n.value == value && n.layer.is_none_or(|l| l == layer))
                    .cloned()
            };
            let info = find(names).or_else(|| find(&raw.names));
            let name = info
                .as_ref()
                .map(|i| i.name.clone())
                .unwrap_or_else(|| format!("label {value}"));
            let color = info
                .and_then(|i| i.color)
                .unwrap_or_else(|| default_color(value));
            structures.push(Structure {
                layer,
                value,
                name,
                color,
                voxels,
            });
        }
    }
    if structures.is_empty() {
        anyhow::bail!("empty label map: every voxel is 0 (background)");
    }
    structures.sort_by_key(|s| (s.value, s.layer));
    Ok(LabelVolume {
        source: source.to_path_buf(),
        dims: raw.dims,
        world_from_voxel: raw.world_from_voxel,
        layers: raw.layers,
        structures,
    })
}

/// A stable colour for a label without one: hues a golden angle apart, so neighbouring values
/// differ clearly; the same value always gets the same colour.
pub fn default_color(value: u32) -> [u8; 3] {
    let hue = (value as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let (saturation, brightness) = (0.55, 0.85);
    let chroma = brightness * saturation;
    let x = chroma * (1.0 - (hue % 2.0 - 1.0).abs());
    let (r, g, b) = match hue as u32 {
        0 => (chroma, x, 0.0),
        1 => (x, chroma, 0.0),
        2 => (0.0, chroma, x),
        3 => (0.0, x, chroma),
        4 => (x, 0.0, chroma),
        _ => (chroma, 0.0, x),
    };
    let m = brightness - chroma;
    [r, g, b].map(|c| ((c + m) * 255.0).round() as u8)
}

/// Checks a reader's dims (each in 1..=[`MAX_AXIS`], total with `layers` at most
/// [`MAX_VOXELS`]) and returns the voxel count of one layer.
pub(crate) fn check_dims(dims: [u64; 3], layers: u64) -> anyhow::Result<usize> {
    for (axis, &n) in dims.iter().enumerate() {
        if n == 0 || n > MAX_AXIS as u64 {
            anyhow::bail!(
                "size {n} of axis {axis} is outside 1..={MAX_AXIS} (sizes {} {} {})",
                dims[0],
                dims[1],
                dims[2]
            );
        }
    }
    let voxels = dims[0] * dims[1] * dims[2];
    if voxels.saturating_mul(layers) > MAX_VOXELS {
        anyhow::bail!(
            "{} voxels ({} {} {}{}) is more than the limit of {MAX_VOXELS}",
            voxels.saturating_mul(layers),
            dims[0],
            dims[1],
            dims[2],
            if layers > 1 {
                format!(" × {layers} layers")
            } else {
                String::new()
            }
        );
    }
    Ok(voxels as usize)
}

/// Builds and checks a voxel-to-world matrix: finite, not singular.
pub(crate) fn affine(columns: [DVec3; 3], origin: DVec3) -> anyhow::Result<DAffine3> {
    let m = DMat3::from_cols(columns[0], columns[1], columns[2]);
    if !columns.iter().chain([&origin]).all(|c| c.is_finite()) {
        anyhow::bail!(
            "the voxel-to-world matrix is not finite (directions {:?} {:?} {:?}, origin {:?})",
            columns[0].to_array(),
            columns[1].to_array(),
            columns[2].to_array(),
            origin.to_array()
        );
    }
    let scale = columns.iter().map(|c| c.length()).product::<f64>();
    if scale == 0.0 || m.determinant().abs() <= 1e-9 * scale {
        anyhow::bail!(
            "singular direction matrix (directions {:?} {:?} {:?}): the axes do not span 3-D space",
            columns[0].to_array(),
            columns[1].to_array(),
            columns[2].to_array()
        );
    }
    Ok(DAffine3::from_mat3_translation(m, origin))
}

/// The stem of a volume file name without its volume extensions: `a.seg.nrrd` → `a`,
/// `b.nii.gz` → `b`, `c.nhdr` → `c`.
pub fn volume_stem(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let lower = name.to_ascii_lowercase();
    for ext in [".seg.nrrd", ".nii.gz", ".nrrd", ".nhdr", ".nii"] {
        if lower.ends_with(ext) {
            return name[..name.len() - ext.len()].to_owned();
        }
    }
    match name.rsplit_once('.') {
        Some((stem, _)) if !stem.is_empty() => stem.to_owned(),
        _ => name,
    }
}

/// One structure's surface.
#[derive(Clone, Debug)]
pub struct StructureSurface {
    pub structure: Structure,
    pub mesh: csg::Mesh,
}

/// One closed surface per structure, in structure order (ascending value, then layer).
/// `progress` gets 0..=1 over the whole volume and returns false to cancel.
pub fn surfaces(
    volume: &LabelVolume,
    smoothing: Option<f64>,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<Vec<StructureSurface>> {
    let mut options = csg::labels::SurfaceOptions::default();
    if let Some(smoothing) = smoothing {
        options.smoothing = smoothing;
    }
    surfaces_with(volume, options, progress)
}

/// [`surfaces`] with every option of `csg::labels` (smoothing, decimation); `options.only` is
/// replaced by each layer's structures.
pub fn surfaces_with(
    volume: &LabelVolume,
    options: csg::labels::SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<Vec<StructureSurface>> {
    let made = std::sync::Mutex::new(Vec::with_capacity(volume.structures.len()));
    surfaces_each(volume, options, progress, &|surface| {
        made.lock().unwrap_or_else(|e| e.into_inner()).push(surface);
        true
    })?;
    let mut out = made.into_inner().unwrap_or_else(|e| e.into_inner());
    out.sort_by_key(|s| (s.structure.value, s.structure.layer));
    Ok(out)
}

/// [`surfaces_with`] handing each structure's surface to `each` as soon as it is made (on the
/// worker that made it, in no particular order), so a caller writes or shows the first
/// structures while the others are made and keeps only what it needs. `each` returns false to
/// stop; the call then ends in the cancelled error.
pub fn surfaces_each(
    volume: &LabelVolume,
    mut options: csg::labels::SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
    each: &(dyn Fn(StructureSurface) -> bool + Sync),
) -> anyhow::Result<()> {
    let layers = volume.layers.len();
    for (layer, data) in volume.layers.iter().enumerate() {
        let wanted: Vec<&Structure> = volume
            .structures
            .iter()
            .filter(|s| s.layer == layer)
            .collect();
        if wanted.is_empty() {
            continue;
        }
        options.only = Some(wanted.iter().map(|s| s.value).collect());
        let layer_progress = |f: f32| progress((layer as f32 + f) / layers as f32);
        let layer_each = |surface: csg::labels::LabelSurface| match wanted
            .iter()
            .find(|s| s.value == surface.value)
        {
            Some(structure) => each(StructureSurface {
                structure: (*structure).clone(),
                mesh: surface.mesh,
            }),
            None => true,
        };
        match data {
            LabelData::U8(v) => layer_surfaces(volume, v, &options, &layer_progress, &layer_each)?,
            LabelData::U16(v) => layer_surfaces(volume, v, &options, &layer_progress, &layer_each)?,
            LabelData::U32(v) => layer_surfaces(volume, v, &options, &layer_progress, &layer_each)?,
        }
    }
    Ok(())
}

fn layer_surfaces<T: csg::labels::LabelValue>(
    volume: &LabelVolume,
    data: &[T],
    options: &csg::labels::SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
    each: &(dyn Fn(csg::labels::LabelSurface) -> bool + Sync),
) -> anyhow::Result<()> {
    let grid = csg::labels::LabelGrid::new(volume.dims, data, volume.world_from_voxel)?;
    csg::labels::label_surfaces_each(&grid, options, progress, each)?;
    Ok(())
}

/// A volume as mesh parts: one per structure, named and coloured (what
/// [`super::read_parts`] returns for a volume).
/// A folder of masks is surfaced mask by mask as its files are read ([`mask_surfaces`]), never
/// packed into a full-size label map.
pub fn read_parts(path: &Path) -> anyhow::Result<Vec<super::Model>> {
    if path.is_dir() {
        let made = std::sync::Mutex::new(Vec::new());
        let options = csg::labels::SurfaceOptions::default();
        mask_surfaces::surfaces_each(path, &[], &options, &|_| true, &|_, surface| {
            made.lock()
                .unwrap_or_else(|e| e.into_inner())
                .extend(surface);
            true
        })?;
        let mut made = made.into_inner().unwrap_or_else(|e| e.into_inner());
        made.sort_by_key(|s| s.structure.value);
        return Ok(made.into_iter().map(part_of).collect());
    }
    parts_of(&read_volume(path, None)?)
}

/// A structure's surface as a mesh part, named and coloured.
pub fn part_of(s: StructureSurface) -> super::Model {
    let color = s.structure.color.map(|c| c as f32 / 255.0);
    super::Model::part(s.structure.name, Some(color), s.mesh)
}

/// A label volume's structures as mesh parts (see [`read_parts`]).
pub fn parts_of(volume: &LabelVolume) -> anyhow::Result<Vec<super::Model>> {
    parts_of_with(volume, &|_| true)
}

/// [`parts_of`] reporting the fraction done (0..=1) to `progress`, which returns false to cancel.
pub fn parts_of_with(
    volume: &LabelVolume,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<Vec<super::Model>> {
    let path = &volume.source;
    let surfaces = surfaces(volume, None, progress).with_context(|| path.display().to_string())?;
    Ok(surfaces.into_iter().map(part_of).collect())
}

#[cfg(test)]
mod tests;
