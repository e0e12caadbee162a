//! Multi-layer cutting: the blade cuts every surface it passes through down to its depth.
//!
//! Segmented anatomy stacks closed surfaces (skin over fat over muscle), each a mesh of its own
//! (a model in the window, a connected region of the file for `cutaway scalpel`). A stroke is
//! drawn on the surface it touches; below each of its samples the blade is the segment from the
//! touched point down the inward normal, `depth` long. [`strokes_below`] casts it against every
//! other surface *as it was before the stroke* (so the rays never meet the new groove walls) and
//! turns the consecutive samples whose blade meets one surface into a stroke on it, at the hit
//! points, with the mean depth left below them. [`cut_layer`] cuts those strokes on a scalpel of
//! its own, all or none. The window and the command line both go through these two functions,
//! so a stroke gives the same meshes in both, bit for bit.
//!
//! The blade leaving the touched structure through its far side (depth larger than the
//! structure's thickness) is not a layer: the stroke on the touched structure itself cuts
//! through it ([`super::through`]).

use glam::DVec3;

/// A stroke on one surface under the blade.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerStroke {
    /// The surface the stroke is on (its [`Surface::id`]).
    pub region: u32,
    /// Samples on that surface, in stroke order (at least 2).
    pub samples: Vec<DVec3>,
    /// Blade depth left below this surface (mean over the samples; > 0).
    pub depth: f64,
}

/// A surface the blade may reach below the touched one, with its spatial index.
#[derive(Clone, Copy)]
pub struct Surface<'a> {
    /// The caller's name for it (a model index, a region number).
    pub id: u32,
    pub mesh: &'a csg::Mesh,
    pub index: &'a csg::SpatialIndex,
}

/// The box the blade of a stroke can reach: its on-surface samples' box grown by the depth.
/// `None` when fewer than two samples are on the surface or the depth is 0 (no layers then).
/// Surfaces whose box misses it need no index.
pub fn reach(samples: &[Option<DVec3>], depth: f64) -> Option<csg::Aabb> {
    let points: Vec<DVec3> = samples.iter().flatten().copied().collect();
    (depth > 0.0 && points.len() >= 2)
        .then(|| csg::Aabb::from_points(&points).expanded(depth * 1.01 + 1e-9))
}

/// The strokes the blade makes on the surfaces `below` (see the module doc). `top` and
/// `top_index` are the touched surface before the stroke; `samples` are the stroke's samples,
/// `None` where the blade was off the surface (that ends every run).
pub fn strokes_below(
    top: &csg::Mesh,
    top_index: &csg::SpatialIndex,
    samples: &[Option<DVec3>],
    depth: f64,
    below: &[Surface],
) -> Vec<LayerStroke> {
    if depth <= 0.0 || below.is_empty() || top.triangles.is_empty() {
        return Vec::new();
    }
    // Start the rays just below the touched surface so they never hit it where they start.
    let eps = 1e-7 * top.bbox().diagonal().max(f64::MIN_POSITIVE);
    let hits = samples.iter().map(|sample| {
        let mut hits: Vec<(u32, DVec3, f64)> = Vec::new();
        if let Some(q) = sample
            && let Some(cp) = top_index.closest_point(top, *q)
        {
            let n = top.face_normal_scaled(cp.face as usize).normalize_or_zero();
            if n != DVec3::ZERO {
                let origin = cp.point - n * eps;
                for s in below {
                    if let Some(hit) = s.index.ray_cast(s.mesh, origin, -n, depth) {
                        let left = depth - hit.t - eps;
                        if left > 0.0 {
                            hits.push((s.id, hit.point, left));
                        }
                    }
                }
            }
        }
        hits
    });
    runs(hits)
}

/// Cuts `strokes` (all on `mesh`) with the blade `options` at each stroke's depth, on a scalpel
/// of its own, and opens them with `open` after its whole window. All or none: the first
/// refused stroke is the error. `Ok(None)`: they changed nothing.
pub fn cut_layer(
    mesh: &csg::Mesh,
    strokes: &[&LayerStroke],
    options: super::ScalpelOptions,
    open: &super::OpenOptions,
) -> Result<Option<(csg::Mesh, super::StrokeReport)>, super::ScalpelError> {
    cut_layer_walls(mesh, &[], strokes, options, open).map(|c| c.map(|(m, _, r)| (m, r)))
}

/// [`cut_layer`] on a mesh whose triangles `walls` are walls already (see
/// [`super::Scalpel::mark_walls`]); also returns the cut mesh's walls, ascending.
pub fn cut_layer_walls(
    mesh: &csg::Mesh,
    walls: &[u32],
    strokes: &[&LayerStroke],
    options: super::ScalpelOptions,
    open: &super::OpenOptions,
) -> Result<Option<(csg::Mesh, Vec<u32>, super::StrokeReport)>, super::ScalpelError> {
    let mut scalpel = super::Scalpel::new(mesh, options)?;
    scalpel.mark_walls(walls);
    let mut total = super::StrokeReport::default();
    for stroke in strokes {
        scalpel.set_options(options.with_depth(stroke.depth));
        let report = scalpel.cut_stroke(&stroke.samples)?;
        total.triangles_cut += report.triangles_cut;
        total.triangles_created += report.triangles_created;
    }
    let mut cut = scalpel.mesh();
    if open.width > 0.0 {
        scalpel.advance_clock(open.window);
        for (v, p) in super::dffd::open_displacements(&scalpel, open, scalpel.clock()) {
            cut.positions[v as usize] = p;
        }
    }
    if cut.triangles == mesh.triangles && cut.positions == mesh.positions {
        return Ok(None);
    }
    Ok(Some((cut, scalpel.wall_faces(), total)))
}

/// Strokes from per-sample hits: `hits[i]` lists the surfaces (`id`, hit point, blade depth left)
/// the blade of sample `i` meets; the consecutive samples meeting one surface become a stroke on
/// it (at least 2 samples; depth = mean depth left). An empty list (the blade met nothing, or the
/// sample was off the surface) ends every run.
fn runs(hits: impl IntoIterator<Item = Vec<(u32, DVec3, f64)>>) -> Vec<LayerStroke> {
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
