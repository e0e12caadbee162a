//! # Label grid → one closed, smooth surface per label
//!
//! A segmentation volume is a 3-D grid of label values (0 = background). Cutaway cuts surfaces,
//! so every label present becomes one closed, edge-manifold, outward-oriented triangle mesh that
//! the exact boolean accepts as a target with no repair. This module sees no file format: the
//! volume readers hand it a [`LabelGrid`] (a borrowed slice, its dimensions and the
//! voxel → world transform).
//!
//! ## Construction (why it is closed and manifold)
//! Per label, the binary mask "voxel == value" is contoured by marching cubes over the cubes
//! whose corners are voxel centres, with two choices that make the result a closed 2-manifold by
//! construction:
//! - every ambiguous cube face (inside corners on a diagonal) separates the inside corners, on
//!   both cubes sharing the face, so the face segments of neighbouring cubes agree;
//! - a cube's only polygon, when it has 3 or 4 sides (most cubes of a smooth boundary), is one
//!   triangle or two split along a diagonal through the cube's interior; every other polygon is
//!   closed by a fan from its own centre vertex. So every mesh edge is either a face segment
//!   (shared by exactly the two cubes of that face) or lies inside one cube and is used only by
//!   that cube's polygon.
//!
//! Two voxels that touch only along an edge or at a corner therefore get two separate sheets
//! (the mask is read with 6-connectivity), never a pinched edge or vertex. Voxels outside the
//! grid count as outside, so a label touching the border is closed there.
//!
//! ## Smoothing (why it stays free of self-intersection)
//! [`smooth`] relaxes the vertices with Taubin's λ|μ filter (shrink-free low pass) under a
//! constraint: an edge vertex stays on its voxel edge (away from its ends), a centre vertex in its
//! cube (in its own part of the cube when the cube cuts several polygons). The topology never
//! changes, and the constraint keeps every sheet near the voxel
//! boundary it came from; the tests check the result with the boolean's exact self-intersection
//! check.
//!
//! ## Decimation (optional)
//! [`SurfaceOptions::decimate`] keeps a fraction of each surface's triangles by quadric edge
//! collapse (`decimate.rs`); every collapse keeps the surface closed and edge-manifold, and the
//! result passes the boolean's exact cutter check or is decimated less (see that file).
//!
//! ## Cost
//! One pass over the grid finds each label's voxel count and bounding box ([`scan`]); each label
//! is then extracted inside its box padded by one voxel, two voxel slices at a time, visiting only
//! the cubes between each row's first and last inside voxel, so no buffer of the full grid is
//! allocated per label. Labels run in parallel, largest first. Smoothing is the dominant cost: it
//! runs over as few vertices as the surface needs (no centre vertex where a cube holds one
//! triangle or quadrilateral), as few passes as remove the staircase, and reads one coordinate per
//! neighbour for the edge vertices. [`label_surfaces_timed`] says where the time went.
//!
//! Where the time goes on a real atlas (256³, 312 labels, 3.9 million triangles): reading and
//! inflating the file about a tenth of the wall time, the scan a fiftieth, and of the per-label
//! work about a quarter extraction and seven tenths smoothing. A smoothing step is bound by each vertex's chain of
//! additions, not by its reads: fixed-size neighbour slots (no variable loop), constant
//! neighbour coordinates summed once, neighbour rings written during extraction, buffers reused
//! across labels and a division moved off the chain each measured within noise of this plain
//! form, so it stays. What is left to win is the duplicated work: each boundary between two
//! labels is extracted and smoothed once per label, so about half the vertices are made twice.
//! Sharing them needs one topology for both labels on every inter-label face, which the per-mask
//! face rule here does not give (on an ambiguous face each label separates its own corners).
//! A one-pass variant that shares only the vertices (each label keeps its own polygons from the
//! same case table, a voxel edge between two labels carries one vertex smoothed once over the
//! lower label's surface) was built and measured against this path on the SPL head atlas: it
//! makes 1.48 million vertices instead of 1.95 million (surfaces against background, most of the
//! area, are not shared) and costs more CPU time (about 0.67 s against 0.46 s in the same run),
//! because a whole-grid pass over label values is slower than per-label passes over bit masks and
//! one large vertex array loses the per-label arrays' cache locality. It kept volumes closer
//! (median error 1.4 % against 1.9 %) and left no gap between touching labels. To beat this path
//! it would need cube configurations from bit masks, its ring and stitch passes per slab in
//! parallel, and smoothing in slab order with each slab's boundary neighbours copied in.

mod cases;
mod decimate;
mod extract;
mod scan;
mod smooth;
#[cfg(test)]
mod tests;

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

use glam::{DAffine3, DVec3};
use rayon::prelude::*;

use crate::mesh::Mesh;

pub use scan::{LabelStats, label_stats};

/// A label value type a grid may hold; implemented for `u8`, `u16` and `u32`.
pub trait LabelValue: Copy + Eq + Send + Sync + 'static {
    /// The value as `u32` (label values are compared and reported as `u32`).
    fn to_u32(self) -> u32;
}

impl LabelValue for u8 {
    fn to_u32(self) -> u32 {
        self as u32
    }
}

impl LabelValue for u16 {
    fn to_u32(self) -> u32 {
        self as u32
    }
}

impl LabelValue for u32 {
    fn to_u32(self) -> u32 {
        self
    }
}

/// A 3-D label grid, x fastest: the value at `(i, j, k)` is
/// `data[i + dims[0] * (j + dims[1] * k)]`.
#[derive(Clone, Copy, Debug)]
pub struct LabelGrid<'a, T: LabelValue> {
    /// Voxels along x, y and z.
    pub dims: [usize; 3],
    /// The voxel values. Must hold exactly `dims[0] * dims[1] * dims[2]` entries
    /// ([`LabelGrid::new`] checks it).
    pub data: &'a [T],
    /// Voxel index `(i, j, k)` (voxel centres at integers) → world RAS millimetres. Must be
    /// finite and invertible ([`LabelGrid::new`] checks it).
    pub world_from_voxel: DAffine3,
}

impl<'a, T: LabelValue> LabelGrid<'a, T> {
    /// A grid after checking that `data` holds one value per voxel and that the transform is
    /// finite and invertible.
    pub fn new(
        dims: [usize; 3],
        data: &'a [T],
        world_from_voxel: DAffine3,
    ) -> Result<LabelGrid<'a, T>, LabelSurfaceError> {
        let grid = LabelGrid {
            dims,
            data,
            world_from_voxel,
        };
        grid.sanity_check()?;
        Ok(grid)
    }

    /// Checks the invariants written on the fields.
    pub fn sanity_check(&self) -> Result<(), LabelSurfaceError> {
        let LabelGrid {
            dims,
            data,
            world_from_voxel,
        } = self;
        let expected = dims
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(d))
            .ok_or(LabelSurfaceError::DimsOverflow { dims: *dims })?;
        if data.len() != expected {
            return Err(LabelSurfaceError::DataLength {
                dims: *dims,
                expected,
                actual: data.len(),
            });
        }
        let det = world_from_voxel.matrix3.determinant();
        if !world_from_voxel.is_finite() || det == 0.0 || !det.is_finite() {
            return Err(LabelSurfaceError::BadTransform {
                world_from_voxel: world_from_voxel.to_cols_array(),
            });
        }
        Ok(())
    }

    /// Volume of one voxel in world units (|det| of the linear part).
    pub fn voxel_volume(&self) -> f64 {
        self.world_from_voxel.matrix3.determinant().abs()
    }

    /// The value at voxel `(i, j, k)`.
    pub fn value(&self, i: usize, j: usize, k: usize) -> u32 {
        self.data[i + self.dims[0] * (j + self.dims[1] * k)].to_u32()
    }
}

/// What to extract and how smooth. `Default`: smoothing 0.5, no decimation, every label.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceOptions {
    /// 0 = raw marching-cubes surface of the voxels, 1 = strongest smoothing; default 0.5.
    /// Values outside 0..=1 are an error.
    pub smoothing: f64,
    /// Fraction of each surface's triangles kept by quadric edge-collapse decimation
    /// (0 < fraction ≤ 1; `None` = no decimation, the default). Each decimated surface is checked
    /// with the boolean's exact cutter check (closed, oriented, free of self-intersection) and
    /// refused with [`LabelSurfaceError::DecimateRefused`] when it fails.
    pub decimate: Option<f64>,
    /// Extract only these label values (`None` = every non-zero label present; values not
    /// present, and 0, are skipped). Default `None`.
    pub only: Option<Vec<u32>>,
}

impl Default for SurfaceOptions {
    fn default() -> SurfaceOptions {
        SurfaceOptions {
            smoothing: 0.5,
            decimate: None,
            only: None,
        }
    }
}

impl SurfaceOptions {
    /// The same options with `smoothing` set.
    pub fn with_smoothing(mut self, smoothing: f64) -> SurfaceOptions {
        self.smoothing = smoothing;
        self
    }

    /// The same options extracting only `values`.
    pub fn with_only(mut self, values: Vec<u32>) -> SurfaceOptions {
        self.only = Some(values);
        self
    }
}

/// The surface of one label.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelSurface {
    /// The label value.
    pub value: u32,
    /// Number of voxels holding the value.
    pub voxels: u64,
    /// Closed, edge-manifold, outward-oriented surface in world coordinates.
    pub mesh: Mesh,
}

/// Why no surfaces could be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LabelSurfaceError {
    /// The dimensions multiply to more than `usize` holds. Fix the volume header.
    #[error("volume dimensions {dims:?} are too large to address")]
    DimsOverflow { dims: [usize; 3] },
    /// The data does not hold one value per voxel. Fix the volume header or data.
    #[error("volume dimensions {dims:?} need {expected} voxels, but the data holds {actual}")]
    DataLength {
        dims: [usize; 3],
        expected: usize,
        actual: usize,
    },
    /// The voxel → world transform is not finite or not invertible. Fix the volume's spacing /
    /// direction fields.
    #[error("voxel-to-world transform {world_from_voxel:?} is not finite and invertible")]
    BadTransform { world_from_voxel: [f64; 12] },
    /// `smoothing` is outside 0..=1.
    #[error("smoothing {smoothing} is outside 0..=1")]
    BadSmoothing { smoothing: f64 },
    /// The decimation fraction is not in 0 < fraction ≤ 1.
    #[error("decimation fraction {fraction} is outside 0 < fraction <= 1")]
    BadDecimate { fraction: f64 },
    /// A decimated surface failed the exact cutter check; ask for a larger fraction.
    #[error(
        "label {value}: the decimated surface is not a valid closed surface ({reason}); keep a larger fraction"
    )]
    DecimateRefused { value: u32, reason: String },
    /// One label's surface would need more vertices than a `u32` index can name.
    #[error("the surface of label {value} needs more than u32::MAX vertices")]
    TooManyVertices { value: u32 },
    /// The progress callback asked to stop.
    #[error("surface extraction cancelled")]
    Cancelled,
}

/// One closed, edge-manifold, outward-oriented, self-intersection-free surface per label present
/// (ascending value; label 0 is background). `progress` gets 0..=1 (fraction of the labels' voxels
/// done) and returns false to cancel.
pub fn label_surfaces<T: LabelValue>(
    grid: &LabelGrid<T>,
    options: &SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> Result<Vec<LabelSurface>, LabelSurfaceError> {
    label_surfaces_timed(grid, options, progress).map(|(surfaces, _)| surfaces)
}

/// Where [`label_surfaces`] spent its time (seconds). `scan_s` is wall time; the per-label phases
/// are summed over the labels, which run in parallel, so they add up to CPU time, not wall time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// The pass over the grid that finds each label's voxel count and box.
    pub scan_s: f64,
    /// Marching cubes over each label's box.
    pub extract_s: f64,
    /// Constrained Taubin smoothing.
    pub smooth_s: f64,
    /// Decimation (0 when not asked for).
    pub decimate_s: f64,
    /// Quadrilateral splitting and the transform to world coordinates.
    pub world_s: f64,
}

impl PhaseTimes {
    fn add(&mut self, o: &PhaseTimes) {
        self.scan_s += o.scan_s;
        self.extract_s += o.extract_s;
        self.smooth_s += o.smooth_s;
        self.decimate_s += o.decimate_s;
        self.world_s += o.world_s;
    }
}

/// [`label_surfaces`], also saying where the time went (for benches and `--json` reports).
pub fn label_surfaces_timed<T: LabelValue>(
    grid: &LabelGrid<T>,
    options: &SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> Result<(Vec<LabelSurface>, PhaseTimes), LabelSurfaceError> {
    let made = std::sync::Mutex::new(Vec::new());
    let times = label_surfaces_each(grid, options, progress, &|surface| {
        made.lock().unwrap_or_else(|e| e.into_inner()).push(surface);
        true
    })?;
    let mut surfaces = made.into_inner().unwrap_or_else(|e| e.into_inner());
    surfaces.sort_by_key(|s| s.value);
    Ok((surfaces, times))
}

/// [`label_surfaces_timed`] handing each surface to `each` as soon as it is made, on the worker
/// that made it and in whatever order the workers finish, instead of collecting them: a caller
/// writes or shows the first surfaces while the others are made, and keeps only what it needs
/// of each. `each` returns false to stop (the call then ends in
/// [`LabelSurfaceError::Cancelled`]). Largest boxes are made first.
pub fn label_surfaces_each<T: LabelValue>(
    grid: &LabelGrid<T>,
    options: &SurfaceOptions,
    progress: &(dyn Fn(f32) -> bool + Sync),
    each: &(dyn Fn(LabelSurface) -> bool + Sync),
) -> Result<PhaseTimes, LabelSurfaceError> {
    grid.sanity_check()?;
    if !(0.0..=1.0).contains(&options.smoothing) {
        return Err(LabelSurfaceError::BadSmoothing {
            smoothing: options.smoothing,
        });
    }
    if let Some(fraction) = options.decimate
        && !(fraction > 0.0 && fraction <= 1.0)
    {
        return Err(LabelSurfaceError::BadDecimate { fraction });
    }
    let scan_start = Instant::now();
    let mut labels = label_stats(grid);
    let mut times = PhaseTimes {
        scan_s: scan_start.elapsed().as_secs_f64(),
        ..PhaseTimes::default()
    };
    if let Some(only) = &options.only {
        labels.retain(|s| only.contains(&s.value));
    }
    // Largest box first, so the longest jobs start early and the pool stays busy at the end.
    labels.sort_by_key(|s| std::cmp::Reverse(s.box_voxels()));
    let total: u64 = labels.iter().map(|s| s.box_voxels()).sum::<u64>().max(1);
    let done = AtomicU64::new(0);
    let cancelled = AtomicBool::new(false);
    if !progress(0.0) {
        return Err(LabelSurfaceError::Cancelled);
    }
    let flip = grid.world_from_voxel.matrix3.determinant() < 0.0;
    let results = labels
        .par_iter()
        .map(|stats| {
            if cancelled.load(Ordering::Relaxed) {
                return Err(LabelSurfaceError::Cancelled);
            }
            let mut t = PhaseTimes::default();
            let mut clock = Instant::now();
            let mut lap = |into: &mut f64| {
                let now = Instant::now();
                *into += (now - clock).as_secs_f64();
                clock = now;
            };
            let mut surface = extract::extract_label(grid, stats)
                .ok_or(LabelSurfaceError::TooManyVertices { value: stats.value })?;
            lap(&mut t.extract_s);
            smooth::smooth(&mut surface, options.smoothing);
            lap(&mut t.smooth_s);
            let mut mesh = surface.into_world(&grid.world_from_voxel, flip);
            lap(&mut t.world_s);
            if let Some(fraction) = options.decimate
                && fraction < 1.0
            {
                mesh = decimate::decimate_checked(&mesh, fraction).map_err(|reason| {
                    LabelSurfaceError::DecimateRefused {
                        value: stats.value,
                        reason,
                    }
                })?;
                lap(&mut t.decimate_s);
            }
            // The construction's guarantee (module doc), checked wherever assertions are on:
            // every test that makes a label surface checks it.
            debug_assert!(mesh.is_closed_oriented(), "label {}", stats.value);
            let kept = each(LabelSurface {
                value: stats.value,
                voxels: stats.voxels,
                mesh,
            });
            let finished =
                done.fetch_add(stats.box_voxels(), Ordering::Relaxed) + stats.box_voxels();
            if !kept || !progress(finished as f32 / total as f32) {
                cancelled.store(true, Ordering::Relaxed);
            }
            Ok(t)
        })
        .collect::<Result<Vec<_>, _>>()?;
    if cancelled.load(Ordering::Relaxed) {
        return Err(LabelSurfaceError::Cancelled);
    }
    for t in &results {
        times.add(t);
    }
    // The workers report in whatever order they finish; the last word is "done".
    progress(1.0);
    Ok(times)
}

/// Voxel count per label value in one pass (for `info`): ascending `(value, count)`, 0 excluded.
pub fn label_counts<T: LabelValue>(grid: &LabelGrid<T>) -> Vec<(u32, u64)> {
    label_stats(grid)
        .into_iter()
        .map(|s| (s.value, s.voxels))
        .collect()
}

/// A surface under construction, in the label box's voxel coordinates, with each vertex's
/// constraint. `f64` like the rest of `csg`: with `f32` the roundings of a grid and of the
/// same grid with an axis flipped differ by about 10⁻⁵ voxel, and the surfaces must be the same.
#[derive(Clone, Debug, Default)]
pub(crate) struct VoxelSurface {
    /// Voxel index of the box's local origin: local `p` is voxel `origin + p`.
    pub origin: DVec3,
    /// Vertex positions in local voxel coordinates.
    pub positions: Vec<DVec3>,
    /// Per vertex, where it may move (same length as `positions`): [`Constraint::edge`] for a
    /// vertex on a voxel edge along that axis (it moves along the edge only, away from its
    /// ends), [`Constraint::centre`] for a centre vertex (it stays in `centre_boxes[c]`).
    /// Edge vertices need no stored bounds (their edge is the unit segment around them), which
    /// keeps the smoothing's memory traffic down.
    pub constraint: Vec<Constraint>,
    /// Lowest and highest corner of each centre vertex's box.
    pub centre_boxes: Vec<[DVec3; 2]>,
    /// Triangles, counter-clockwise seen from outside in voxel index space.
    pub triangles: Vec<[u32; 3]>,
    /// Quadrilaterals (a cube's only polygon with four sides), counter-clockwise seen from
    /// outside; each becomes two triangles in [`VoxelSurface::into_world`].
    pub quads: Vec<[u32; 4]>,
}

/// Where one vertex may move during smoothing: `0..3` = along that axis on its voxel edge,
/// `3 + c` = inside centre box `c`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Constraint(pub u32);

impl Constraint {
    /// On a voxel edge along `axis`.
    pub fn edge(axis: usize) -> Constraint {
        Constraint(axis as u32)
    }

    /// Inside centre box `index`.
    pub fn centre(index: usize) -> Constraint {
        Constraint(3 + index as u32)
    }
}

impl VoxelSurface {
    /// The mesh in world coordinates; each quadrilateral is split along its shorter diagonal in
    /// world space (so the split is the same for any order or direction of the grid's axes);
    /// `flip` reverses every triangle (for a transform with negative determinant, which mirrors
    /// and so turns outward into inward).
    fn into_world(self, world_from_voxel: &DAffine3, flip: bool) -> Mesh {
        // In place: the voxel positions are not needed after this, and a fresh buffer would be
        // touched (page-faulted) anew.
        let mut positions = self.positions;
        for p in &mut positions {
            *p = world_from_voxel.transform_point3(self.origin + *p);
        }
        let mut triangles = self.triangles;
        triangles.reserve(2 * self.quads.len());
        for [a, b, c, d] in self.quads {
            let at = |v: u32| positions[v as usize];
            if at(a).distance_squared(at(c)) <= at(b).distance_squared(at(d)) {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[b, c, d], [b, d, a]]);
            }
        }
        if flip {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        Mesh {
            positions,
            triangles,
        }
    }
}
