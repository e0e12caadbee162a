//! Expose: the cutters that open the view onto a focus structure, built for the user.
//!
//! Given the focus, the structures that may hide it and the eye, [`expose`] returns ordinary
//! paint-roller [`Cutter`]s, one (or, for an occluder that hides separate parts of the focus,
//! a few) per occluder that hides it, each to be aimed at that occluder: after cutting them, every
//! point of the focus the eye would see with the occluders gone is seen (up to the sampling
//! below), and the occluders lose only what lies on the rays to the focus's silhouette plus a
//! margin, in front of the focus. The focus itself is never cut.
//!
//! The idea follows importance-driven cutaways (Viola et al. 2004: what hides an important
//! object is cleared along the view) and cutaways of a selected target (Li et al. 2007: the
//! cut follows the target's silhouette plus a margin, from the view), with the cut exact: each
//! cutter is a valid input of the exact boolean ([`Cutter::validate`] passes), shaped so that
//! the boolean's result is what the user is shown.
//!
//! Why one cutter per occluder: a scene cutter cuts the one structure it is aimed at, so each
//! occluder needs its own, and a cutter per occluder can also be sized to it: its front rests
//! just in front of that occluder's surface and its back goes only as deep as that occluder
//! requires (past its own far side, or past the focus where the focus lies inside it, as a brain
//! structure lies inside the skin). Each is editable on its own like a painted cutter.
//!
//! Stages, in order ([`frame`], [`abuffer`], [`occlusion`], [`cutters`]):
//! 1. the view frame: view coordinates turned to the long axis of the focus's image, and a grid
//!    of rays over that image plus the margin;
//! 2. every crossing of every ray with the focus and the occluders (a watertight rasterization);
//! 3. per ray, which occluders cross it before the focus, and how deep a cutter must reach;
//! 4. per occluder, its window (the hidden rays grown by the margin) and the cutters whose
//!    planes stand on rays through the window's edge.
//!
//! Sampling: the rays are `resolution` cells apart across the image; the faces keep a clearance
//! of a cell's width (plus [`ExposeOptions::clearance`]) from what they clear, so what falls
//! between rays is covered unless it is thinner than a cell.

pub mod abuffer;
pub mod cutters;
pub mod distance;
pub mod frame;
pub mod occlusion;

use csg::Mesh;
use glam::DVec3;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::cutter::Cutter;
use crate::expose::abuffer::ABuffer;
use crate::expose::cutters::{Shape, occluder_cutters};
use crate::expose::frame::ViewFrame;
use crate::expose::occlusion::{Occluder, Occlusion};

/// How the cutters are sized. Lengths are in model units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExposeOptions {
    /// Margin around the focus's silhouette, measured across the view at the focus's nearest
    /// point. Default 3 (3 mm in a scene in millimetres).
    pub margin: f64,
    /// Gap between a cutter's faces and what they clear (the occluder's surface in front, the
    /// focus or the occluder's far side behind), on top of a cell's width. Default 0.5.
    pub clearance: f64,
    /// Rays across the longer side of the focus's image plus margin. Default 256.
    pub resolution: usize,
    /// Most boxes of one cutter. Default 40.
    pub max_boxes: usize,
    /// The occluders that hide the least of the focus are left uncut while together they hide
    /// at most this share of its image. Default 0.003: neighbours that touch the focus hide
    /// slivers of its rim from most views, and a cutter for each would add dozens of cutters
    /// for little of the view. Kept small because a rim is seen at a grazing angle: a sliver of
    /// the image can be ten times its share of the focus's visible surface (at 0.01 the pons
    /// from the front kept 11 % of its visible surface hidden behind the brainstem's other
    /// parts).
    pub leave_share: f64,
}

impl Default for ExposeOptions {
    fn default() -> ExposeOptions {
        ExposeOptions {
            margin: 3.0,
            clearance: 0.5,
            resolution: 256,
            max_boxes: 40,
            leave_share: 0.003,
        }
    }
}

impl ExposeOptions {
    /// The options with `margin` (model units).
    pub fn with_margin(self, margin: f64) -> ExposeOptions {
        ExposeOptions { margin, ..self }
    }

    /// The options with `clearance` (model units).
    pub fn with_clearance(self, clearance: f64) -> ExposeOptions {
        ExposeOptions { clearance, ..self }
    }
}

/// A cutter through one occluder.
#[derive(Clone, Debug)]
pub struct ExposedCutter {
    /// Index of the occluder (in the slice given to [`expose`]) the cutter is to cut.
    pub occluder: usize,
    pub cutter: Cutter,
    /// Share (0..=1) of the focus's image this cutter opens (where its occluder hid the focus).
    pub opens: f64,
    /// True when the shaped cutter was refused by the exact check and one with a single front
    /// and back depth was used instead (it removes more).
    pub simplified: bool,
}

/// What [`expose`] built.
#[derive(Clone, Debug, Default)]
pub struct Exposure {
    /// The cutters, nearest occluder first.
    pub cutters: Vec<ExposedCutter>,
    /// Share (0..=1) of the focus's image that something hid.
    pub hidden: f64,
    /// The occluders left uncut (see [`ExposeOptions::leave_share`]).
    pub left: Vec<usize>,
    /// Runs of an occluder no valid cutter could open, one line each.
    pub notes: Vec<String>,
}

/// Why no cutters were built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExposeError {
    /// The focus has no triangles.
    #[error("the structure has no surface")]
    EmptyFocus,
    /// Part of the focus lies at or behind the eye's plane: turn or move the camera back.
    #[error("part of the structure lies behind the camera (vertex {vertex})")]
    BehindEye { vertex: usize },
    /// The caller asked to stop.
    #[error("cancelled")]
    Cancelled,
}

/// The eye and the axes of the view the cutters open.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExposeView {
    pub eye: DVec3,
    /// Unit viewing direction.
    pub forward: DVec3,
    /// Unit directions across the view, orthogonal to `forward` and to each other.
    pub right: DVec3,
    pub up: DVec3,
}

impl ExposeView {
    /// The view of `camera`.
    pub fn of_camera(camera: &Camera) -> ExposeView {
        let (right, up, forward) = camera.basis();
        ExposeView {
            eye: camera.eye,
            forward,
            right,
            up,
        }
    }
}

/// The cutters that open `view` onto `focus` through `occluders` (see the module docs).
/// `keep_going` is asked between stages; when it says no, [`ExposeError::Cancelled`].
pub fn expose(
    focus: &Mesh,
    occluders: &[&Mesh],
    view: &ExposeView,
    options: &ExposeOptions,
    keep_going: &dyn Fn() -> bool,
) -> Result<Exposure, ExposeError> {
    if focus.triangles.is_empty() {
        return Err(ExposeError::EmptyFocus);
    }
    // 1. The frame: the focus's image, its long axis, the grid over it plus the margin.
    let mut image = Vec::with_capacity(focus.positions.len());
    for (k, &p) in focus.positions.iter().enumerate() {
        let q = p - view.eye;
        let z = q.dot(view.forward);
        if z.is_nan() || z <= 0.0 {
            return Err(ExposeError::BehindEye { vertex: k });
        }
        image.push([q.dot(view.right) / z, q.dot(view.up) / z]);
    }
    let frame = ViewFrame::oriented(view.eye, view.forward, view.right, view.up, &image);
    let (mut u, mut v, mut nearest) = (
        [f64::INFINITY, f64::NEG_INFINITY],
        [f64::INFINITY, f64::NEG_INFINITY],
        f64::INFINITY,
    );
    for &p in &focus.positions {
        let [pu, pv, pz] = frame.project(p);
        u = [u[0].min(pu), u[1].max(pu)];
        v = [v[0].min(pv), v[1].max(pv)];
        nearest = nearest.min(pz);
    }
    let margin = options.margin.max(0.0) / nearest;
    let resolution = options.resolution.max(8);
    let longer = (u[1] - u[0]).max(v[1] - v[0]) + 2.0 * margin;
    // Two cells beyond the margin on every side, so the window's edge is inside the grid.
    let pad = margin + 2.0 * longer / resolution as f64;
    let frame = frame.with_grid(
        [u[0] - pad, u[1] + pad],
        [v[0] - pad, v[1] + pad],
        resolution,
    );
    let near = nearest * 1e-6;

    // 2. Every crossing of every ray.
    let mut meshes = Vec::with_capacity(occluders.len() + 1);
    meshes.push(focus);
    meshes.extend_from_slice(occluders);
    let buffer = ABuffer::build(&frame, &meshes, near);
    if !keep_going() {
        return Err(ExposeError::Cancelled);
    }

    // 3. What hides the focus where.
    let occlusion = Occlusion::of(&buffer, frame.cells());
    let focus_cells = occlusion.focus_cells().max(1) as f64;
    let hidden_cells = occlusion
        .focus_depth
        .iter()
        .enumerate()
        .filter(|&(c, d)| {
            d.is_finite()
                && occlusion
                    .occluders
                    .iter()
                    .any(|o| o.hidden.binary_search_by_key(&c, |h| h.0).is_ok())
        })
        .count();

    // 4. Each occluder's cutters.
    let shape = Shape {
        margin_cells: margin / frame.cell + 1.0,
        box_columns: frame.columns.div_ceil(options.max_boxes.max(1)),
        clearance: options.clearance.max(0.0),
        near: nearest * 1e-3,
    };
    let mut by_share: Vec<&Occluder> = occlusion.occluders.iter().collect();
    by_share.sort_by_key(|o| o.hidden.len());
    let mut hidden_by_left = 0.0;
    let (left, opened): (Vec<&Occluder>, Vec<&Occluder>) = by_share.into_iter().partition(|o| {
        hidden_by_left += o.hidden.len() as f64 / focus_cells;
        hidden_by_left <= options.leave_share
    });
    let mut left: Vec<usize> = left.iter().map(|o| o.mesh as usize - 1).collect();
    left.sort_unstable();
    if !keep_going() {
        return Err(ExposeError::Cancelled);
    }
    // Each occluder's cutters are shaped and checked independently (the exact check is most of
    // the work), in parallel.
    let per_occluder: Vec<_> = opened
        .par_iter()
        .map(|o| {
            (
                o.mesh as usize - 1,
                occluder_cutters(&frame, &buffer, o, &shape),
            )
        })
        .collect();
    let mut built: Vec<(f64, ExposedCutter)> = Vec::new();
    let mut notes = Vec::new();
    for (index, (cutters, why)) in per_occluder {
        for c in cutters {
            built.push((
                c.front_depth,
                ExposedCutter {
                    occluder: index,
                    cutter: c.cutter,
                    opens: c.opened_cells as f64 / focus_cells,
                    simplified: c.simplified,
                },
            ));
        }
        notes.extend(why.into_iter().map(|w| format!("occluder {index}: {w}")));
    }
    built.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(Exposure {
        cutters: built.into_iter().map(|(_, c)| c).collect(),
        hidden: hidden_cells as f64 / focus_cells,
        left,
        notes,
    })
}

#[cfg(test)]
mod tests;
