//! The local exact boolean: cut a closed cutter out of a cached target.
//!
//! # Robustness contract
//!
//! **Input.** The target is any [`Mesh`] that passed [`Mesh::sanity_check`], indexed once with
//! [`TargetIndex::build`]: closed or open, manifold or not, several regions, degenerate faces
//! allowed. The cutter must be closed, edge-manifold, consistently oriented outward (positive
//! volume), free of self-intersections (sub-cutters of [`subtract_many`] must also be disjoint
//! and not nested), finite, and span together with the target at most [`MAX_REACH`] target
//! sizes (a cutter beyond the cached lattice is cut on a wider one, see `far.rs`). Anything else
//! is a typed [`CutError`]; a cut never panics and never modifies the target.
//!
//! **Decisions.** Coordinates are quantized once to an integer lattice (steps of about
//! 2⁻²⁷ × the target's size, see [`crate::lattice`]); every topological decision is an exact
//! integer predicate of [`crate::exact`], with one tie-break rule for all degeneracies: the
//! cutter is symbolically translated by δ = (ε, ε², ε³) (Simulation of Simplicity). No epsilon
//! enters anywhere. So a target point exactly on a cutter face plane lies on the side −δ points
//! to, and coplanar faces separate by the sign of their normal's first non-zero component (x,
//! then y, then z); collinearities that survive the perturbation are handled exactly by the
//! triangulation ([`crate::split`]).
//!
//! **Output** ([`CutResult`]):
//! - **kept** (target outside the cutter, as a delta against the target: `removed_faces` plus
//!   `kept_new_faces`), **removed** (target inside the cutter), **walls** (cutter inside the
//!   target, facing out of kept), **contours**, and the provenance of every output face.
//! - Every vertex the cut did not create keeps its exact input coordinates (same bits); the new
//!   contour vertices are rounded once from their exact lattice value. Each contour vertex has
//!   one id, shared by kept, removed, walls and contours, so they weld bit for bit.
//! - **Regions.** Every region of the target is cut as its own solid. A region is a connected
//!   component together with its cavities: a closed component oriented inward (negative
//!   volume) that lies inside another closed component is a cavity of the innermost such
//!   component; every other component is its own region (decided exactly when the index is
//!   built, [`crate::cavities`]). The walls of a closed region are the cutter inside that
//!   region's solid (non-zero winding: inside its outer shell, outside its cavities), split by
//!   that region's contour only; nested regions (a brain inside the skin, a cube inside a cube)
//!   each get their own walls, which overlap where the solids do. [`CutResult::walls_solid`]
//!   names each wall triangle's region and [`CutResult::region_parts`] splits a result by
//!   region.
//! - For a closed, edge-manifold target, per region: kept + walls and removed + reversed walls
//!   are each closed, edge-manifold and consistently oriented, without T-junctions, and the
//!   volumes add up to the region's up to the rounding of the new vertices; kept and removed
//!   together are exactly the target's faces, split along the contour (so their areas add up to
//!   the target's area); contours are closed loops.
//! - Self-intersecting targets (regions that interpenetrate, a region crossing itself): kept and
//!   removed are exact as above. Where the contour curves of two target sheets cross inside one
//!   cutter face, the three-plane crossing point is not constructed: that face is split by the
//!   topology-only fallback, its wall pieces may overlap or take the wrong side, and kept +
//!   walls has T-junctions there. Such faces usually show in [`crate::output::CutStats`]
//!   (`triangulation_fallbacks`, `status_fallbacks`; both 0 for every target that does not
//!   intersect itself), and [`crate::cutcheck::crossing_cutter_faces`] names them exactly.
//! - Open or non-manifold targets: kept and removed are exact as above (they are classified
//!   relative to the closed cutter). Walls are split along the contour wherever it runs through
//!   a cutter face as a simple path or loop; contour pieces that end or branch inside a cutter
//!   face (target boundary or non-manifold edge) do not split it. The seed status of each cutter
//!   component comes from the target's generalized winding number (≥ ½ is inside), which is a
//!   classifier, not an exact test; a fast winding-number tree ([`crate::winding`], built with
//!   the index of an open target) makes it about O(log N) per cutter component.
//! - A cutter identical to the target (or sharing faces with it) is decided by the same δ rule
//!   as every coplanar case: the target faces whose normal's first non-zero component (x, then
//!   y, then z) is negative lie outside the translated cutter and are kept, the others are
//!   removed, and the walls are the cutter's faces against the kept ones. So kept + walls is a
//!   double layer of zero volume (its two sides may be triangulated differently), and removed +
//!   reversed walls is the whole solid, closed.
//! - Target faces with a repeated vertex index have no area and no edges of their own: they are
//!   never split; if one is crossed it is dropped from both kept and removed.
//! - Geometry after rounding: new vertices move by at most half a lattice step plus one `f64`
//!   rounding, so tiny inversions of slivers next to the contour are possible, never topological
//!   defects. A new vertex is the exact intersection of the *quantized* inputs: it can differ
//!   from the intersection of the `f64` inputs by about a lattice step (more where an edge
//!   grazes a plane).
//!
//! [`crate::cutcheck`] checks this contract on a result; the property, differential (against
//! Manifold) and fuzz tests of `csg/tests/` run it on random and degenerate cuts.
//!
//! **Cost.** Only faces whose boxes overlap cutter faces, in BVH subtrees that straddle the
//! cutter face's plane, are examined; untouched faces are classified by flood fill from the
//! contour (inside the cutter only, so output-sensitive: the face-to-face neighbours and a
//! per-face bitmap are cached with the index) and at most one exact inside test per untouched
//! region whose box overlaps the cutter. No per-cut allocation, clear or first touch is
//! proportional to the target size. The kept part and the removed piece are returned as deltas
//! against the target (the removed piece is built into a mesh when first read, see
//! [`Removed`](crate::output::Removed)). The broad phase, the exact pair tests, the splitting of faces and the placing
//! of new vertices run in parallel (rayon); the flood fill runs beside the assembly of the
//! output. Everything a thread decides is a pure function of its inputs and results are merged
//! in a fixed order, so a cut's output does not depend on the thread count or scheduling.
//!
//! # Stages
//! 1. Validate and quantize the cutter (`prepare`). Early-out: boxes disjoint.
//! 2. Exact intersection ([`crate::intersect`]).
//! 3. Cutter vertex statuses (the set of region solids each lies in, [`crate::solids`]): one
//!    inside test per cutter component, then crossings toggle their face's solid
//!    (`vertex_solids`).
//! 4. Split touched target faces, and touched cutter faces once per solid they meet
//!    (`faces`, with [`crate::split`]); statuses of the pieces.
//! 5. Flood fill of untouched target faces inside the cutter; untouched regions (`flood`).
//! 6. Assemble the output and the contours (`assemble`, with [`crate::contour`]); 5 and 6
//!    run side by side.

mod assemble;
mod error;
mod faces;
mod far;
mod flood;
mod inputs;
mod prepare;
mod vertex_solids;

pub use error::CutError;
pub use far::MAX_REACH;
pub(crate) use prepare::prepare_cutter;
pub use prepare::{check_cutter, cutter_self_intersections};

use crate::phases::{Phases, timed};
use inputs::CutInputs;

use crate::intersect::{self, PreparedCutter};
use crate::mesh::Mesh;
use crate::output::{CutOptions, CutResult, CutStats};
use crate::target::TargetIndex;

/// Cuts `cutter` out of the target (see the robustness contract in the module doc): exact
/// topology for any sane target, closed and manifold kept + walls for closed targets that do not
/// intersect themselves, degeneracies resolved by translating the cutter by δ = (ε, ε², ε³), a
/// typed [`CutError`] for an invalid cutter, never a panic.
///
/// Each region of the target is cut as its own solid (non-zero winding). A region is a
/// connected component together with its cavities: a closed component oriented inward
/// (negative volume) that lies inside another closed component (decided exactly) is a cavity of
/// the innermost such one; every other component is its own region. So a cube of side 10 with
/// an inward cube of side 4 inside is one hollow solid (walls skip the cavity), while the same
/// inner cube oriented outward is a second solid, with walls of its own inside the first's. For
/// every closed region, kept + walls and removed + reversed walls are closed and the volume
/// identity holds; [`CutResult::region_parts`] gives each region's kept, walls and removed.
///
/// A cutter identical to the target keeps the faces whose normal's first non-zero component is
/// negative, with walls against them: a zero-volume double layer (module doc).
pub fn subtract(target: &TargetIndex, cutter: &Mesh) -> Result<CutResult, CutError> {
    subtract_many(target, &[cutter])
}

/// Cuts several disjoint sub-cutters (ribbons, slices) at once. Every output face carries the
/// id of its sub-cutter (`sub_cutter` of [`Part`](crate::Part) and [`crate::output::Contour`]); use
/// [`Part::of_sub_cutter`](crate::Part::of_sub_cutter) for one sub-cutter's removed piece or walls.
pub fn subtract_many(target: &TargetIndex, cutters: &[&Mesh]) -> Result<CutResult, CutError> {
    subtract_with(target, cutters, &CutOptions::default())
}

/// [`subtract_many`] with options.
pub fn subtract_with(
    target: &TargetIndex,
    cutters: &[&Mesh],
    options: &CutOptions,
) -> Result<CutResult, CutError> {
    let mut phases = Phases::new(options.time_phases);
    // A cutter reaching beyond the target's lattice is cut on a wider lattice (`far`).
    let wider;
    let (target, cutter) = match prepare_cutter(target, cutters) {
        Err(far @ CutError::OutOfRange { .. }) => {
            wider = far::index_with_room(target, cutters).ok_or(far)?;
            phases.mark("index with room for the cutter");
            (&wider, prepare_cutter(&wider, cutters)?)
        }
        prepared => (target, prepared?),
    };
    phases.mark("prepare");
    // On a rayon worker: the parallel stages inside then hand work to the other workers through
    // their local queues, instead of each waking the pool from outside (which costs a scheduler
    // round trip per stage on a busy machine).
    let mut result = rayon::scope(|_| run(target, &cutter, options, &mut phases))?;
    result.phases = phases.into_marks();
    Ok(result)
}
/// Stages 2–6 on a validated cutter.
pub(crate) fn run(
    target: &TargetIndex,
    cutter: &PreparedCutter,
    options: &CutOptions,
    phases: &mut Phases,
) -> Result<CutResult, CutError> {
    let mut stats = CutStats::default();
    let mut result = CutResult {
        target_vertex_count: target.mesh.positions.len(),
        ..Default::default()
    };
    // Stage 1b: early-out when the boxes are disjoint.
    if !cutter.bounds.overlaps(&target.bounds) {
        result.stats = stats;
        return Ok(result);
    }
    // Stage 2: intersections.
    let isect = intersect::intersect_timed(target, cutter, phases).map_err(CutError::Internal)?;
    stats.candidate_pairs = isect.candidate_pairs;
    let cut = CutInputs {
        target,
        cutter,
        isect: &isect,
    };
    // Stage 3: cutter vertex statuses.
    let (cutter_in, sets) = vertex_solids::cutter_vertex_solids(&cut, &mut stats)?;
    phases.mark("cutter status");
    // Stage 4: split faces, then the statuses of their pieces.
    let (mut faces, split_cutter) = faces::split_faces(&cut, &cutter_in, &sets)?;
    for face in &faces {
        stats.triangulation_fallbacks += face.fallbacks;
    }
    stats.touched_target_faces = faces.len();
    phases.mark("split faces");
    faces::resolve_piece_statuses(&cut, &mut faces, &mut stats)?;
    phases.mark("piece status");
    // Stage 5 on this thread while stage 6 runs on the others.
    let on = phases.on;
    let ((flood, flood_ms), (output, output_ms)) = rayon::join(
        || timed(on, || flood::flood(&cut, &faces)),
        || {
            // When the other thread took this branch (0 when at once; the flood fill's time
            // when no other thread was free and this one ran it after the flood fill).
            let start = if on {
                phases.last.elapsed().as_secs_f64() * 1e3
            } else {
                0.0
            };
            let (r, ms) = timed(on, || {
                assemble::assemble(&cut, &faces, split_cutter, options)
            });
            (r, (start, ms))
        },
    );
    let output = output?;
    phases.record("(flood)", flood_ms);
    phases.record("(output starts)", output_ms.0);
    phases.record("(output)", output_ms.1);
    phases.append(&output.phases);
    phases.mark("flood+output");
    stats.inside_tests += flood.inside_tests;
    stats.touched_cutter_faces += output.stats.touched_cutter_faces;
    stats.triangulation_fallbacks += output.stats.triangulation_fallbacks;
    stats.status_fallbacks += output.stats.status_fallbacks;
    let mut removed = output.removed;
    removed.whole_faces = flood.whole_faces;
    removed.whole_sub_cutter = flood.whole_sub_cutter;
    result.removed_faces = flood.removed_faces;
    result.removed = removed;
    result.new_positions = output.new_positions;
    result.kept_new_faces = output.kept_new_faces;
    result.kept_new_provenance = output.kept_new_provenance;
    result.walls = output.walls;
    result.walls_solid = output.walls_solid;
    result.contours = output.contours;
    result.stats = stats;
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::inputs::PARALLEL_MIN;
    use super::*;
    use crate::output::{PositionBits, position_bits};
    use crate::testkit;
    use glam::DVec3;

    /// Everything a cut returns, with positions as bits, for exact comparison.
    fn fingerprint(r: &CutResult) -> String {
        let bits =
            |p: &[DVec3]| -> Vec<PositionBits> { p.iter().map(|&q| position_bits(q)).collect() };
        format!(
            "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
            r.removed_faces,
            bits(&r.new_positions),
            r.kept_new_faces,
            r.kept_new_provenance,
            r.walls.mesh.triangles,
            bits(&r.walls.mesh.positions),
            r.walls.provenance,
            r.removed.whole_faces,
            r.removed.piece_faces,
            r.removed.mesh.triangles,
            r.contours
                .iter()
                .map(|c| (bits(&c.points), c.closed, c.sub_cutter))
                .collect::<Vec<_>>(),
            r.removed.sub_cutter,
            r.stats,
        )
    }

    /// The parallel stages merge their results in a fixed order: one thread and four threads
    /// give the same cut, bit for bit (one cutter and two sub-cutters, each large enough for
    /// every stage to run in parallel).
    #[test]
    fn cut_does_not_depend_on_the_thread_count() {
        let index = TargetIndex::build(testkit::geodesic_sphere(40, 10.0)).unwrap();
        let slab = testkit::cube(DVec3::new(-12.0, -3.1, 2.05), DVec3::new(12.0, 3.3, 12.0));
        let a = testkit::cube(DVec3::new(-12.0, -12.0, -4.0), DVec3::new(12.0, 12.0, -3.0));
        let b = testkit::cube(DVec3::new(-2.0, -12.0, -1.0), DVec3::new(2.5, 12.0, 1.5));
        let cut = |threads: usize, cutters: &[&Mesh]| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| subtract_many(&index, cutters).unwrap())
        };
        for cutters in [vec![&slab], vec![&a, &b]] {
            let one = cut(1, &cutters);
            assert!(one.stats.touched_target_faces >= 2 * PARALLEL_MIN);
            assert!(one.removed.whole_faces.len() > 1000);
            assert_eq!(fingerprint(&one), fingerprint(&cut(4, &cutters)));
        }
    }

    /// Stage times are returned only when asked for, starting with the total, and a cut with
    /// them is the same cut.
    #[test]
    fn phase_times_only_when_asked() {
        let index = TargetIndex::build(testkit::geodesic_sphere(8, 10.0)).unwrap();
        let slab = testkit::cube(DVec3::new(-12.0, -3.1, 2.05), DVec3::new(12.0, 3.3, 12.0));
        let plain = subtract(&index, &slab).unwrap();
        assert!(plain.phases.is_empty());
        let options = CutOptions::default().with_phase_times(true);
        let timed = subtract_with(&index, &[&slab], &options).unwrap();
        let names: Vec<&str> = timed.phases.iter().map(|(n, _)| *n).collect();
        assert_eq!(names.first(), Some(&"total"));
        for stage in ["prepare", "cutter status", "split faces", "flood+output"] {
            assert!(names.contains(&stage), "{stage} missing from {names:?}");
        }
        assert!(
            timed
                .phases
                .iter()
                .all(|(_, ms)| ms.is_finite() && *ms >= 0.0)
        );
        assert_eq!(fingerprint(&plain), fingerprint(&timed));
    }
}
