//! Constrained Taubin smoothing of a raw label surface.
//!
//! Taubin's λ|μ filter alternates a shrinking Laplacian step (factor λ > 0) with an inflating one
//! (μ < −λ): low frequencies (the shape) pass, high frequencies (the voxel staircase) are damped,
//! and unlike plain Laplacian smoothing the volume barely shrinks. After every step each vertex is
//! clamped into its constraint box (edge vertices stay on their voxel edge, centre vertices in
//! their polygon's box), which keeps the surface within about half a voxel of the voxel boundary
//! and each sheet on its own side of the voxels it separates.
//!
//! Neighbours: in a closed, oriented, edge-manifold mesh of triangles and quadrilaterals every
//! directed edge `a → b` occurs in exactly one polygon, so a vertex's neighbours are exactly the
//! heads of its outgoing polygon sides, without duplicates. Quadrilaterals are smoothed before
//! they are split, with both diagonals as neighbours (so the result does not depend on the split
//! and a quadrilateral is pulled flat; a diagonal joins edges of one cube on no common face, which
//! no other polygon joins).

use glam::DVec3;
use rayon::prelude::*;

use super::VoxelSurface;

/// Shrinking step factor λ.
const LAMBDA: f64 = 0.5;
/// Pass-band frequency k_pb = 1/λ + 1/μ of the filter; 0.1 as in Taubin's paper.
const PASS_BAND: f64 = 0.1;
/// λ|μ step pairs at `smoothing = 1`. The default 0.5 gives 10 pairs (20 steps, about what
/// VTK's SurfaceNets3D runs by default); more passes shrink thin structures further against their
/// constraints without removing more of the staircase.
const MAX_PAIRS: f64 = 20.0;

/// Number of λ|μ step pairs for a smoothing level in 0..=1.
pub fn pairs(smoothing: f64) -> usize {
    (smoothing * MAX_PAIRS).ceil() as usize
}

/// Smooths `surface` in place; `smoothing` 0 leaves it unchanged.
pub fn smooth(surface: &mut VoxelSurface, smoothing: f64) {
    let pairs = pairs(smoothing);
    if pairs == 0 || surface.positions.is_empty() {
        return;
    }
    let mu = 1.0 / (PASS_BAND - 1.0 / LAMBDA);
    let (offsets, neighbours) = neighbours(surface);
    let mut next = surface.positions.clone();
    for _ in 0..pairs {
        for factor in [LAMBDA, mu] {
            step(surface, &offsets, &neighbours, factor, &mut next);
            std::mem::swap(&mut surface.positions, &mut next);
        }
    }
}

/// One Laplacian step with `factor` into `next`, clamped to the constraint boxes.
fn step(
    surface: &VoxelSurface,
    offsets: &[u32],
    neighbours: &[u32],
    factor: f64,
    next: &mut [DVec3],
) {
    let p = &surface.positions;
    next.par_iter_mut()
        .with_min_len(4096)
        .enumerate()
        .for_each(|(i, out)| {
            let ring = &neighbours[offsets[i] as usize..offsets[i + 1] as usize];
            if ring.is_empty() {
                *out = p[i];
                return;
            }
            let mean = ring.iter().map(|&n| p[n as usize]).sum::<DVec3>() / ring.len() as f64;
            let moved = p[i] + (mean - p[i]) * factor;
            *out = moved.clamp(surface.lo[i], surface.hi[i]);
        });
}

/// Compressed neighbour lists: vertex `i`'s neighbours are
/// `neighbours[offsets[i]..offsets[i + 1]]`.
fn neighbours(surface: &VoxelSurface) -> (Vec<u32>, Vec<u32>) {
    let n = surface.positions.len();
    let mut offsets = vec![0u32; n + 1];
    for &v in surface.triangles.iter().flatten() {
        offsets[v as usize + 1] += 1;
    }
    for &v in surface.quads.iter().flatten() {
        offsets[v as usize + 1] += 2;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut neighbours = vec![0u32; offsets[n] as usize];
    let mut side = |from: u32, to: u32| {
        neighbours[fill[from as usize] as usize] = to;
        fill[from as usize] += 1;
    };
    for &[a, b, c] in &surface.triangles {
        side(a, b);
        side(b, c);
        side(c, a);
    }
    for &[a, b, c, d] in &surface.quads {
        for (from, to) in [(a, b), (b, c), (c, d), (d, a)] {
            side(from, to);
        }
        // Both diagonals, both ways.
        for (from, to) in [(a, c), (c, a), (b, d), (d, b)] {
            side(from, to);
        }
    }
    (offsets, neighbours)
}
