//! Multi-layer cutting: the blade cuts every surface it passes through down to its depth.
//!
//! Segmented anatomy stacks closed surfaces (skin over fat over muscle). A tool stroke is drawn
//! on the surface it touches; below each sample the blade reaches `depth` along the inward normal.
//! [`layer_strokes`] casts that blade segment from the touched point into the *uncut* mesh and
//! turns every other region it meets into a stroke of its own (the consecutive samples whose
//! blade reaches that region), with the depth left below the hit. Cutting those strokes after
//! the top one gives each stacked surface its own groove. Computed once, before any cut, so the
//! rays never meet the new groove walls.
//!
//! The blade leaving the touched structure through its far side (depth larger than the
//! structure's thickness) is not a layer: the stroke on the touched structure itself cuts
//! through it ([`super::through`]); such hits are ignored here.

use glam::DVec3;

/// A stroke on one surface under the blade.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerStroke {
    /// The region (connected component of the input) the stroke is on.
    pub region: u32,
    /// Samples on that surface, in stroke order (at least 2).
    pub samples: Vec<DVec3>,
    /// Blade depth left below this surface (mean over the samples; > 0).
    pub depth: f64,
}

/// The strokes the blade makes on the surfaces below the one it touches (see the module doc).
/// `index` must be built from `mesh`; `regions` labels `mesh`'s triangles.
pub fn layer_strokes(
    mesh: &csg::Mesh,
    index: &csg::SpatialIndex,
    regions: &csg::regions::Regions,
    samples: &[DVec3],
    depth: f64,
) -> Vec<LayerStroke> {
    if depth <= 0.0 || samples.is_empty() || mesh.triangles.is_empty() {
        return Vec::new();
    }
    let eps = 1e-7 * mesh.bbox().diagonal().max(f64::MIN_POSITIVE);
    // Per sample: the regions the blade meets below the touched surface, with the depth left.
    let mut hits: Vec<Vec<(u32, DVec3, f64)>> = Vec::with_capacity(samples.len());
    for &q in samples {
        let mut below = Vec::new();
        if let Some(cp) = index.closest_point(mesh, q) {
            let top = regions.region_of_triangle[cp.face as usize];
            let n = mesh
                .face_normal_scaled(cp.face as usize)
                .normalize_or_zero();
            let mut origin = cp.point - n * eps;
            let mut left = depth;
            for _ in 0..16 {
                if n == DVec3::ZERO || left <= 0.0 {
                    break;
                }
                let Some(hit) = index.ray_cast(mesh, origin, -n, left) else {
                    break;
                };
                let region = regions.region_of_triangle[hit.face as usize];
                left -= hit.t + eps;
                if region != top
                    && left > 0.0
                    && !below.iter().any(|b: &(u32, DVec3, f64)| b.0 == region)
                {
                    below.push((region, hit.point, left));
                }
                origin = hit.point - n * eps;
            }
        }
        hits.push(below);
    }
    runs(hits)
}

/// Strokes from per-sample hits: `hits[i]` lists the surfaces (`id`, hit point, blade depth left)
/// the blade of sample `i` meets; the consecutive samples meeting one surface become a stroke on
/// it (at least 2 samples; depth = mean depth left). An empty list (the blade met nothing, or the
/// sample was off the surface) ends every run. Shared with the window, where the surfaces are
/// other models.
pub fn runs(hits: impl IntoIterator<Item = Vec<(u32, DVec3, f64)>>) -> Vec<LayerStroke> {
    // Runs of consecutive samples per region.
    let mut out: Vec<LayerStroke> = Vec::new();
    let mut open: Vec<(u32, Vec<DVec3>, f64)> = Vec::new();
    let flush = |run: (u32, Vec<DVec3>, f64), out: &mut Vec<LayerStroke>| {
        if run.1.len() >= 2 {
            let n = run.1.len() as f64;
            out.push(LayerStroke {
                region: run.0,
                samples: run.1,
                depth: run.2 / n,
            });
        }
    };
    for below in hits {
        let mut still = Vec::new();
        for run in open.drain(..) {
            if below.iter().any(|b| b.0 == run.0) {
                still.push(run);
            } else {
                flush(run, &mut out);
            }
        }
        open = still;
        for (region, p, left) in below {
            if let Some(run) = open.iter_mut().find(|r| r.0 == region) {
                run.1.push(p);
                run.2 += left;
            } else {
                open.push((region, vec![p], left));
            }
        }
    }
    for run in open {
        flush(run, &mut out);
    }
    out
}
