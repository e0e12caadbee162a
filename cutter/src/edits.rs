//! Editing a cutter (thesis 3.3.3): moving a plane's edge, changing depth with self-intersection
//! resolution, rotating a plane about its front edge, removing the last box.
//!
//! Depth changes come in two rules (see [`crate::editor::Rules`]): [`change_depth`] adds
//! [`DEPTH_STEP`]·δ a wheel notch (the first rules), [`scale_depth`] multiplies by
//! [`DEPTH_FACTOR`] a notch, so a notch is the same share of any depth and of any target's size,
//! and [`set_depth`] gives planes one depth (the cutter panel's field).
//!
//! Every function here either returns the edited cutter, valid by [`Cutter::sanity_check`], or
//! refuses (returns None) and leaves the input untouched: the editor never holds an invalid cutter.

use glam::DVec3;

use crate::cutter::{CutKind, Cutter};
use crate::geom;
use crate::plane::BoundedPlane;

/// Depth change per wheel notch, as a multiple of δ.
pub const DEPTH_STEP: f64 = 2.0;
/// Rotation per Ctrl+wheel notch, in degrees.
pub const ROTATE_STEP_DEG: f64 = 5.0;
/// Smallest depth a plane may get, as a multiple of δ.
pub const MIN_DEPTH: f64 = 1.0;
/// Depth factor of one wheel notch under [`crate::editor::Rules::Reach`] (5 % deeper a notch up,
/// the same back a notch down).
pub const DEPTH_FACTOR: f64 = 1.05;
/// Most rounds of the self-intersection resolution before the edit is refused.
const MAX_RESOLVE_ROUNDS: usize = 400;

/// Which planes a depth change applies to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthTarget {
    /// Every plane (the pointer is off the cutter).
    All,
    /// One plane (the selected one).
    Plane(usize),
}

/// Changes depth by `notches · DEPTH_STEP · δ` (negative = shallower), one notch at a time with
/// self-intersection resolution after each (thesis: "after every incremental increase in depth").
/// Wedge cutters always change as a whole (their planes share the back axis point).
pub fn change_depth(
    cutter: &Cutter,
    target: DepthTarget,
    notches: f64,
    delta: f64,
) -> Option<Cutter> {
    let per = notches_split(notches)?.1 * DEPTH_STEP * delta;
    in_steps(cutter, target, notches, delta, |depth| depth + per)
}

/// Multiplies depth by `DEPTH_FACTOR^notches` (negative = shallower), one notch at a time with
/// self-intersection resolution after each, as [`change_depth`] steps.
pub fn scale_depth(
    cutter: &Cutter,
    target: DepthTarget,
    notches: f64,
    delta: f64,
) -> Option<Cutter> {
    let factor = DEPTH_FACTOR.powf(notches_split(notches)?.1);
    in_steps(cutter, target, notches, delta, |depth| depth * factor)
}

/// Gives the target planes the depth `depth` (at least [`MIN_DEPTH`]·δ), reached in steps of
/// at most a tenth of the change with self-intersection resolution after each. None when nothing
/// changes or the result is invalid.
pub fn set_depth(cutter: &Cutter, target: DepthTarget, depth: f64, delta: f64) -> Option<Cutter> {
    if !(depth.is_finite() && depth > 0.0) {
        return None;
    }
    let depth = depth.max(MIN_DEPTH * delta);
    let mut c = cutter.clone();
    let range = plane_range(&c, target)?;
    let start: Vec<f64> = c.planes[range.clone()].iter().map(|p| p.depth()).collect();
    const STEPS: usize = 10;
    for k in 1..=STEPS {
        let t = k as f64 / STEPS as f64;
        if c.kind == CutKind::Wedge {
            set_wedge_depth(&mut c, |_| start[0] + (depth - start[0]) * t, delta)?;
            continue;
        }
        for (p, &from) in c.planes[range.clone()].iter_mut().zip(&start) {
            *p = p.with_depth(from + (depth - from) * t);
        }
        if !resolve_self_intersections(&mut c.planes, delta) {
            return None;
        }
    }
    c.sanity_check().ok()?;
    (c != *cutter).then_some(c)
}

/// The notch count and the signed share of one step, for a finite, non-zero `notches`.
fn notches_split(notches: f64) -> Option<(usize, f64)> {
    if notches == 0.0 || !notches.is_finite() {
        return None;
    }
    let count = notches.abs().ceil() as usize;
    Some((count, notches / count as f64))
}

/// The planes a depth change applies to.
fn plane_range(c: &Cutter, target: DepthTarget) -> Option<std::ops::Range<usize>> {
    match target {
        DepthTarget::All => Some(0..c.planes.len()),
        DepthTarget::Plane(i) if i < c.planes.len() => Some(i..i + 1),
        DepthTarget::Plane(_) => None,
    }
}

/// Moves a wedge's shared back axis point along the axis to the depth `next(depth)` (at least
/// [`MIN_DEPTH`]·δ).
fn set_wedge_depth(c: &mut Cutter, next: impl Fn(f64) -> f64, delta: f64) -> Option<()> {
    let axis = (c.planes[0].back_top - c.planes[0].front_top).try_normalize()?;
    let depth =
        next((c.planes[0].back_top - c.planes[0].front_top).length()).max(MIN_DEPTH * delta);
    let bt = c.planes[0].front_top + axis * depth;
    for p in &mut c.planes {
        p.back_top = bt;
        p.back_bottom = p.front_bottom + axis * depth;
    }
    Some(())
}

/// One notch at a time: each target plane's depth becomes `next(depth)` (at least
/// [`MIN_DEPTH`]·δ), then crossing planes are resolved. Wedges change as a whole.
fn in_steps(
    cutter: &Cutter,
    target: DepthTarget,
    notches: f64,
    delta: f64,
    next: impl Fn(f64) -> f64,
) -> Option<Cutter> {
    let (count, _) = notches_split(notches)?;
    let mut c = cutter.clone();
    for _ in 0..count {
        if c.kind == CutKind::Wedge {
            set_wedge_depth(&mut c, &next, delta)?;
        } else {
            let range = plane_range(&c, target)?;
            for p in &mut c.planes[range] {
                *p = p.with_depth(next(p.depth()).max(MIN_DEPTH * delta));
            }
            if !resolve_self_intersections(&mut c.planes, delta) {
                return None;
            }
        }
    }
    c.sanity_check().ok()?;
    (c != *cutter).then_some(c)
}

/// Groups of planes that intersect each other, as inclusive index ranges (thesis 3.3.3: a group
/// spans from its lowest to its highest plane, so `[4, 5, 7]` colliding gives `4..=7`).
pub fn intersecting_groups(planes: &[BoundedPlane]) -> Vec<(usize, usize)> {
    let n = planes.len();
    let quads: Vec<[DVec3; 4]> = planes.iter().map(|p| p.corners()).collect();
    let boxes: Vec<csg::Aabb> = quads
        .iter()
        .map(|q| csg::Aabb::from_points(q.iter()))
        .collect();
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if boxes[i].overlaps(&boxes[j]) && geom::quad_quad_intersect(&quads[i], &quads[j]) {
                ranges.push((i, j));
            }
        }
    }
    ranges.sort_unstable();
    let mut merged: Vec<(usize, usize)> = Vec::new();
    for (lo, hi) in ranges {
        match merged.last_mut() {
            Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
            _ => merged.push((lo, hi)),
        }
    }
    merged
}

/// The thesis's iterative resolution: while some planes intersect, rotate each plane of each group
/// one increment about its front edge, backward (against the path) below the group's median and
/// forward above it. Returns false when planes still intersect after the round limit.
pub fn resolve_self_intersections(planes: &mut [BoundedPlane], delta: f64) -> bool {
    for _ in 0..MAX_RESOLVE_ROUNDS {
        let groups = intersecting_groups(planes);
        if groups.is_empty() {
            return true;
        }
        let path: Vec<DVec3> = planes.iter().map(|p| p.front_mid()).collect();
        for (lo, hi) in groups {
            let median = (lo + hi) as f64 * 0.5;
            for i in lo..=hi {
                let idx = i as f64;
                if idx == median {
                    continue;
                }
                let along = path_direction(&path, i);
                let p = planes[i];
                let angle =
                    (delta / p.depth().max(1e-300)).clamp(0.2f64.to_radians(), 5f64.to_radians());
                // Pick the rotation sense that moves the back edge the wanted way along the path.
                let plus = p.rotated_about_front_edge(angle);
                let moves_forward = (plus.back_mid() - p.back_mid()).dot(along) > 0.0;
                let want_forward = idx > median;
                planes[i] = if moves_forward == want_forward {
                    plus
                } else {
                    p.rotated_about_front_edge(-angle)
                };
            }
        }
    }
    intersecting_groups(planes).is_empty()
}

/// Unit direction of the path at plane `i` (central difference of front-edge midpoints).
fn path_direction(path: &[DVec3], i: usize) -> DVec3 {
    let lo = i.saturating_sub(1);
    let hi = (i + 1).min(path.len() - 1);
    (path[hi] - path[lo]).normalize_or_zero()
}

/// Rotates plane `index` about its front edge by `notches · ROTATE_STEP_DEG` (positive tilts its
/// back edge forward along the path). Refused for wedges and when the result is invalid.
pub fn rotate_plane(cutter: &Cutter, index: usize, notches: f64) -> Option<Cutter> {
    if cutter.kind == CutKind::Wedge || index >= cutter.planes.len() || notches == 0.0 {
        return None;
    }
    let path = cutter.path();
    let along = path_direction(&path, index);
    let p = cutter.planes[index];
    let angle = (notches * ROTATE_STEP_DEG).to_radians();
    let plus = p.rotated_about_front_edge(angle);
    let forward = (plus.back_mid() - p.back_mid()).dot(along) > 0.0;
    let rotated = if forward {
        plus
    } else {
        p.rotated_about_front_edge(-angle)
    };
    let mut c = cutter.clone();
    c.planes[index] = rotated;
    c.sanity_check().ok()?;
    Some(c)
}

/// Moves the edge of plane `index` through its front-top (`top`) or front-bottom vertex so that
/// the front vertex lands on `target` projected onto the plane through it normal to the edge
/// (thesis figure 37); the back vertex follows. Refused for a wedge's shared axis vertex and when
/// the result is invalid.
pub fn move_edge(cutter: &Cutter, index: usize, top: bool, target: DVec3) -> Option<Cutter> {
    let p = *cutter.planes.get(index)?;
    if cutter.kind == CutKind::Wedge && top {
        return None;
    }
    let (front, back) = if top {
        (p.front_top, p.back_top)
    } else {
        (p.front_bottom, p.back_bottom)
    };
    let normal = (front - back).try_normalize()?;
    let offset = (target - front) - normal * (target - front).dot(normal);
    if !offset.is_finite() {
        return None;
    }
    let mut q = p;
    if top {
        q.front_top += offset;
        q.back_top += offset;
    } else {
        q.front_bottom += offset;
        q.back_bottom += offset;
    }
    let mut c = cutter.clone();
    c.planes[index] = q;
    c.sanity_check().ok()?;
    Some(c)
}

/// Removes the last box (down to one box).
pub fn remove_last_box(cutter: &Cutter) -> Option<Cutter> {
    if cutter.planes.len() <= 2 {
        return None;
    }
    let mut c = cutter.clone();
    c.planes.pop();
    c.sanity_check().ok()?;
    Some(c)
}
