//! The image a segmentation was drawn on (a CT or MR intensity volume), shown on the cut walls.
//!
//! An [`IntensityImage`] keeps its voxels **once, at their own type** (`int16` stays two bytes a
//! voxel): the bytes the reader handed over, put in little-endian order in place. Values are read
//! one voxel at a time ([`IntensityImage::value`]) and scaled by the file's slope and intercept,
//! so nothing ever holds a converted copy of a large scan. The GPU gets the same bytes as an
//! integer 3-D texture (see `crate::render::image_layer`).
//!
//! Sampling ([`IntensityImage::sample_world`]) is trilinear in voxel-index space, voxel centres
//! at integer indices (the convention of the label surfaces), after the image's own
//! voxel → world (RAS millimetre) matrix: the image and the segmentation only need to share the
//! world frame, not the grid. A point more than half a voxel outside the grid has no value.
//!
//! This module is egui- and wgpu-free: the CLI, the renderer, the glTF export and the window all
//! use it.

use std::path::PathBuf;
use std::sync::Arc;

use glam::{DAffine3, DVec3};

pub mod fit;
pub mod window;

pub use window::{Window, WindowPreset};

/// How the voxels are stored (the types kept as they are in the file; every other type is
/// converted on reading, see `crate::io::volume::intensity`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleKind {
    U8,
    I16,
    U16,
    I32,
    F32,
}

impl SampleKind {
    /// Bytes per voxel.
    pub fn size(self) -> usize {
        match self {
            SampleKind::U8 => 1,
            SampleKind::I16 | SampleKind::U16 => 2,
            SampleKind::I32 | SampleKind::F32 => 4,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            SampleKind::U8 => "uint8",
            SampleKind::I16 => "int16",
            SampleKind::U16 => "uint16",
            SampleKind::I32 => "int32",
            SampleKind::F32 => "float32",
        }
    }
}

/// An intensity volume on its grid. See the module documentation.
pub struct IntensityImage {
    pub source: PathBuf,
    pub dims: [usize; 3],
    /// Voxel index → world RAS millimetres.
    pub world_from_voxel: DAffine3,
    voxel_from_world: DAffine3,
    kind: SampleKind,
    /// Little-endian samples, x fastest, exactly `dims` product × `kind.size()` bytes.
    bytes: Vec<u8>,
    /// Stored value → real value: `value * scale.0 + scale.1`.
    scale: (f64, f64),
    /// Smallest and largest real value (NaN voxels left out).
    range: (f64, f64),
}

impl std::fmt::Debug for IntensityImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("IntensityImage")
            .field("source", &self.source)
            .field("dims", &self.dims)
            .field("kind", &self.kind)
            .field("range", &self.range)
            .finish_non_exhaustive()
    }
}

impl IntensityImage {
    /// An image from little-endian `bytes` of `kind`. Errors when the length does not match.
    pub fn new(
        source: PathBuf,
        dims: [usize; 3],
        world_from_voxel: DAffine3,
        kind: SampleKind,
        bytes: Vec<u8>,
        scale: (f64, f64),
    ) -> anyhow::Result<IntensityImage> {
        let voxels = dims.iter().product::<usize>();
        if voxels == 0 || bytes.len() != voxels * kind.size() {
            anyhow::bail!(
                "image data is {} bytes, but {} × {} × {} {} voxels need {}",
                bytes.len(),
                dims[0],
                dims[1],
                dims[2],
                kind.name(),
                voxels * kind.size()
            );
        }
        let voxel_from_world = world_from_voxel.inverse();
        let mut image = IntensityImage {
            source,
            dims,
            world_from_voxel,
            voxel_from_world,
            kind,
            bytes,
            scale,
            range: (0.0, 0.0),
        };
        image.range = image.compute_range();
        Ok(image)
    }

    /// A synthetic `float32` image whose value at voxel (i, j, k) is `f` of that voxel's world
    /// position (tests and benches).
    pub fn from_fn(
        dims: [usize; 3],
        world_from_voxel: DAffine3,
        f: impl Fn(DVec3) -> f32,
    ) -> IntensityImage {
        let mut bytes = Vec::with_capacity(dims.iter().product::<usize>() * 4);
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let p =
                        world_from_voxel.transform_point3(DVec3::new(i as f64, j as f64, k as f64));
                    bytes.extend_from_slice(&f(p).to_le_bytes());
                }
            }
        }
        IntensityImage::new(
            PathBuf::from("synthetic"),
            dims,
            world_from_voxel,
            SampleKind::F32,
            bytes,
            (1.0, 0.0),
        )
        .expect("sizes match by construction")
    }

    pub fn kind(&self) -> SampleKind {
        self.kind
    }

    /// The stored samples, little-endian (what the GPU texture is filled from).
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// Stored value → real value: `value * scale.0 + scale.1`.
    pub fn scale(&self) -> (f64, f64) {
        self.scale
    }

    /// World → voxel index (continuous; voxel centres at integers).
    pub fn voxel_from_world(&self) -> DAffine3 {
        self.voxel_from_world
    }

    /// Smallest and largest value.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }

    pub fn voxel_count(&self) -> usize {
        self.dims.iter().product()
    }

    /// The stored value at flat index `index` (x fastest), unscaled.
    pub(crate) fn raw(&self, index: usize) -> f64 {
        let b = &self.bytes;
        match self.kind {
            SampleKind::U8 => b[index] as f64,
            SampleKind::I16 => i16::from_le_bytes([b[2 * index], b[2 * index + 1]]) as f64,
            SampleKind::U16 => u16::from_le_bytes([b[2 * index], b[2 * index + 1]]) as f64,
            SampleKind::I32 => {
                let at = 4 * index;
                i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]) as f64
            }
            SampleKind::F32 => {
                let at = 4 * index;
                f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]) as f64
            }
        }
    }

    /// The value of voxel (i, j, k) (each below its dim).
    pub fn value(&self, i: usize, j: usize, k: usize) -> f64 {
        let index = i + self.dims[0] * (j + self.dims[1] * k);
        self.raw(index) * self.scale.0 + self.scale.1
    }

    /// The value at a world position, trilinear between the eight nearest voxel centres; `None`
    /// more than half a voxel outside the grid (within that half voxel the edge value holds).
    pub fn sample_world(&self, p: DVec3) -> Option<f64> {
        let q = self.voxel_from_world.transform_point3(p);
        let mut base = [0usize; 3];
        let mut next = [0usize; 3];
        let mut t = [0f64; 3];
        for a in 0..3 {
            let n = self.dims[a] as f64;
            if !(q[a] >= -0.5 && q[a] <= n - 0.5) {
                return None;
            }
            let c = q[a].clamp(0.0, n - 1.0);
            let f = c.floor();
            base[a] = f as usize;
            next[a] = (base[a] + 1).min(self.dims[a] - 1);
            t[a] = c - f;
        }
        let v = |i: usize, j: usize, k: usize| self.value(i, j, k);
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let x00 = lerp(
            v(base[0], base[1], base[2]),
            v(next[0], base[1], base[2]),
            t[0],
        );
        let x10 = lerp(
            v(base[0], next[1], base[2]),
            v(next[0], next[1], base[2]),
            t[0],
        );
        let x01 = lerp(
            v(base[0], base[1], next[2]),
            v(next[0], base[1], next[2]),
            t[0],
        );
        let x11 = lerp(
            v(base[0], next[1], next[2]),
            v(next[0], next[1], next[2]),
            t[0],
        );
        Some(lerp(lerp(x00, x10, t[1]), lerp(x01, x11, t[1]), t[2]))
    }

    /// The world box the grid covers (voxel extents, half a voxel past the outer centres).
    pub fn world_bbox(&self) -> csg::Aabb {
        let mut b = csg::Aabb::EMPTY;
        for corner in 0..8 {
            let q = DVec3::new(
                if corner & 1 == 0 {
                    -0.5
                } else {
                    self.dims[0] as f64 - 0.5
                },
                if corner & 2 == 0 {
                    -0.5
                } else {
                    self.dims[1] as f64 - 0.5
                },
                if corner & 4 == 0 {
                    -0.5
                } else {
                    self.dims[2] as f64 - 0.5
                },
            );
            b.grow(self.world_from_voxel.transform_point3(q));
        }
        b
    }

    /// Values at up to `max` voxels spread evenly over the grid (NaN left out), for percentiles.
    pub fn spread_samples(&self, max: usize) -> Vec<f64> {
        let n = self.voxel_count();
        let step = n.div_ceil(max.max(1)).max(1);
        (0..n)
            .step_by(step)
            .map(|i| self.raw(i) * self.scale.0 + self.scale.1)
            .filter(|v| !v.is_nan())
            .collect()
    }

    fn compute_range(&self) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..self.voxel_count() {
            let v = self.raw(i);
            if v < lo {
                lo = v;
            }
            if v > hi {
                hi = v;
            }
        }
        if lo > hi {
            return (0.0, 0.0);
        }
        let (a, b) = (
            lo * self.scale.0 + self.scale.1,
            hi * self.scale.0 + self.scale.1,
        );
        (a.min(b), a.max(b))
    }
}

/// Refuses an image whose world box does not meet the segmentation's: they are not in the same
/// world frame (or not of the same patient), and sampling would show nothing.
pub fn check_overlap(image: &IntensityImage, segmentation: csg::Aabb) -> anyhow::Result<()> {
    let b = image.world_bbox();
    if segmentation.is_empty() {
        return Ok(());
    }
    if !b.overlaps(&segmentation) {
        let fmt = |v: DVec3| format!("({:.1}, {:.1}, {:.1})", v.x, v.y, v.z);
        anyhow::bail!(
            "the image (world box {} to {}) and the segmentation (world box {} to {}) are disjoint: they do not share a world frame",
            fmt(b.min),
            fmt(b.max),
            fmt(segmentation.min),
            fmt(segmentation.max)
        );
    }
    Ok(())
}

/// An image shared between the scene, the renderer's upload cache and worker threads.
pub type SharedImage = Arc<IntensityImage>;

#[cfg(test)]
mod tests;
