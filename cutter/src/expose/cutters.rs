//! An occluder's cutters: paint-roller cutters whose planes stand on rays from the eye.
//!
//! The cells where the occluder hides the focus, grown by the margin (a round margin: the cells
//! within that distance, `distance.rs`), are what must be opened
//! (the occluder's **window**). The grid's columns are grouped into boxes of a few columns; a run
//! of consecutive boxes that hold window cells becomes one cutter, with a bounded plane on every
//! box boundary. Plane `k` is the part of the plane through the eye at that boundary (a line in
//! `(u, v)`, see `frame.rs`) that covers the window rows of the boxes on both sides of it, from a
//! front depth to a back depth:
//! - back: the largest reach (`occlusion.rs`) of the cells of those boxes, plus the clearance;
//!   so wherever the cutter's back face lies in front of a point of the focus it lies outside the
//!   occluder (no wall there), and elsewhere it stands behind the focus;
//! - front: the nearest crossing of the occluder in those boxes before that back, less the
//!   clearance; so the front face lies outside the occluder and the cutter removes everything of
//!   it along the window's rays up to the back.
//!
//! Taking both sides of a plane makes each box's faces, which interpolate between its two
//! planes, cover what the box holds: the window rows of a box lie within both of its planes' rows,
//! and its depths within both planes' front..back. The side faces run along rays, so they are seen
//! edge-on from the eye and hide nothing. A cutter the exact check refuses is replaced by the same
//! cutter with one front and one back depth for all planes (a slice of a cone, which is always
//! valid), and dropped with a note if that fails too.

use crate::cutter::{CutKind, Cutter};
use crate::expose::abuffer::ABuffer;
use crate::expose::distance::squared_distances;
use crate::expose::frame::ViewFrame;
use crate::expose::occlusion::Occluder;
use crate::plane::BoundedPlane;

/// How an occluder's cutters are shaped.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    /// The margin around the hidden cells, in cells (a cell is within it when its centre is
    /// this near a hidden cell's centre).
    pub margin_cells: f64,
    /// Grid columns per box.
    pub box_columns: usize,
    /// Gap between a cutter's faces and what they must clear, in model units (a cell's width at
    /// that depth is added, for what lies between the sampled rays).
    pub clearance: f64,
    /// No cutter face comes nearer the eye than this depth.
    pub near: f64,
}

/// One cutter through an occluder.
#[derive(Clone, Debug)]
pub struct OccluderCutter {
    pub cutter: Cutter,
    /// The cells of the focus it opens (where the occluder hid the focus).
    pub opened_cells: usize,
    /// Depth of its nearest front corner (cutters are listed nearest first).
    pub front_depth: f64,
    /// Set when the shaped cutter was refused and the one-depth cutter was used instead.
    pub simplified: bool,
}

/// The window rows, the largest reach and the hidden cells of one box.
#[derive(Clone, Copy, Debug)]
struct BoxWindow {
    /// First and last window row; `None` when the box holds no window cell.
    rows: Option<(usize, usize)>,
    reach: f64,
    hidden: usize,
}

/// The cutters through `occluder`, and notes for the runs no valid cutter could open.
pub fn occluder_cutters(
    frame: &ViewFrame,
    buffer: &ABuffer,
    occluder: &Occluder,
    shape: &Shape,
) -> (Vec<OccluderCutter>, Vec<String>) {
    let boxes = box_windows(frame, occluder, shape);
    let mut cutters = Vec::new();
    let mut notes = Vec::new();
    let mut b = 0;
    while b < boxes.len() {
        if boxes[b].rows.is_none() {
            b += 1;
            continue;
        }
        let start = b;
        while b < boxes.len() && boxes[b].rows.is_some() {
            b += 1;
        }
        match run_cutter(frame, buffer, occluder.mesh, &boxes[start..b], start, shape) {
            Ok(cutter) => cutters.push(cutter),
            Err(why) => notes.push(why),
        }
    }
    (cutters, notes)
}

/// Every box's window: the hidden cells grown by the margin.
fn box_windows(frame: &ViewFrame, occluder: &Occluder, shape: &Shape) -> Vec<BoxWindow> {
    let (columns, rows) = (frame.columns, frame.rows);
    let mut hidden = vec![false; frame.cells()];
    let mut reach = vec![f64::NEG_INFINITY; frame.cells()];
    for &(cell, r) in &occluder.hidden {
        hidden[cell] = true;
        reach[cell] = r;
    }
    // Grown by the margin: every cell within that distance of a hidden one.
    let radius2 = shape.margin_cells * shape.margin_cells;
    let window: Vec<bool> = squared_distances(&hidden, columns, rows)
        .into_iter()
        .map(|d| d <= radius2)
        .collect();
    let k = shape.box_columns.max(1);
    (0..columns.div_ceil(k))
        .map(|b| {
            let mut w = BoxWindow {
                rows: None,
                reach: f64::NEG_INFINITY,
                hidden: 0,
            };
            for i in b * k..((b + 1) * k).min(columns) {
                for j in 0..rows {
                    let c = frame.index(i, j);
                    if window[c] {
                        w.rows = Some(w.rows.map_or((j, j), |(lo, hi)| (lo.min(j), hi.max(j))));
                    }
                    if hidden[c] {
                        w.hidden += 1;
                        w.reach = w.reach.max(reach[c]);
                    }
                }
            }
            w
        })
        .collect()
}

/// Fills the `NaN` entries of `values` from the nearest set entry (the larger of the two when
/// both sides are equally near); false when none is set.
fn fill_from_neighbours(values: &mut [f64], larger: bool) -> bool {
    let set: Vec<usize> = (0..values.len()).filter(|&k| !values[k].is_nan()).collect();
    if set.is_empty() {
        return false;
    }
    let original = values.to_vec();
    for k in 0..values.len() {
        if !original[k].is_nan() {
            continue;
        }
        let nearest = set.iter().map(|&s| s.abs_diff(k)).min().unwrap_or(0);
        let candidates = set
            .iter()
            .filter(|&&s| s.abs_diff(k) == nearest)
            .map(|&s| original[s]);
        values[k] = if larger {
            candidates.fold(f64::NEG_INFINITY, f64::max)
        } else {
            candidates.fold(f64::INFINITY, f64::min)
        };
    }
    true
}

/// The cutter of one run of boxes (`boxes`, the first being box `first` of the grid).
fn run_cutter(
    frame: &ViewFrame,
    buffer: &ABuffer,
    mesh: u32,
    boxes: &[BoxWindow],
    first: usize,
    shape: &Shape,
) -> Result<OccluderCutter, String> {
    let k = shape.box_columns.max(1);
    let planes = boxes.len() + 1;
    // The boxes on both sides of plane p are p - 1 and p (within the run).
    let sides = |p: usize| (p.saturating_sub(1)..(p + 1).min(boxes.len())).map(|b| &boxes[b]);
    let rows: Vec<(usize, usize)> = (0..planes)
        .map(|p| {
            sides(p)
                .filter_map(|b| b.rows)
                .fold((usize::MAX, 0), |(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
        })
        .collect();
    let clear = |z: f64| shape.clearance + 1.5 * frame.cell * z.abs();
    let mut back: Vec<f64> = (0..planes)
        .map(|p| {
            let r = sides(p).map(|b| b.reach).fold(f64::NEG_INFINITY, f64::max);
            if r.is_finite() { r } else { f64::NAN }
        })
        .collect();
    if !fill_from_neighbours(&mut back, true) {
        return Err("a run of the window hides nothing".to_string());
    }
    for z in &mut back {
        *z += clear(*z);
    }
    // The nearest crossing of the occluder in each box, among those the cutter would cut.
    let box_front: Vec<f64> = (0..boxes.len())
        .map(|b| {
            let (lo, hi) = (rows[b].0.min(rows[b + 1].0), rows[b].1.max(rows[b + 1].1));
            let limit = back[b].max(back[b + 1]);
            let column_start = (first + b) * k;
            let mut nearest = f64::INFINITY;
            for i in column_start..(column_start + k).min(frame.columns) {
                for j in lo..=hi {
                    let crossings = buffer.at(frame.index(i, j));
                    if let Some(c) = crossings.iter().find(|c| c.mesh == mesh && c.z < limit) {
                        nearest = nearest.min(c.z);
                    }
                }
            }
            nearest
        })
        .collect();
    let mut front: Vec<f64> = (0..planes)
        .map(|p| {
            let z = (p.saturating_sub(1)..(p + 1).min(boxes.len()))
                .map(|b| box_front[b])
                .fold(f64::INFINITY, f64::min);
            if z.is_finite() { z } else { f64::NAN }
        })
        .collect();
    if !fill_from_neighbours(&mut front, false) {
        return Err("the occluder is not crossed in its window".to_string());
    }
    for (f, &b) in front.iter_mut().zip(&back) {
        *f = (*f - clear(*f)).min(b - clear(b)).max(shape.near);
        if *f >= b {
            return Err("the occluder lies too close to the eye to cut in front of it".to_string());
        }
    }
    let u: Vec<f64> = (0..planes)
        .map(|p| frame.column_edge(((first + p) * k).min(frame.columns)))
        .collect();
    // Built from the view: rolled further, its planes keep going the way the eye looks.
    let build = |front: &[f64], back: &[f64]| Cutter {
        kind: CutKind::Curving,
        direction: crate::CutDirection::View,
        smooth: false,
        levels: crate::subdivision::DEFAULT_LEVELS,
        planes: (0..planes)
            .map(|p| {
                let (v_lo, v_hi) = (frame.row_edge(rows[p].0), frame.row_edge(rows[p].1 + 1));
                BoundedPlane {
                    front_top: frame.point(u[p], v_hi, front[p]),
                    back_top: frame.point(u[p], v_hi, back[p]),
                    back_bottom: frame.point(u[p], v_lo, back[p]),
                    front_bottom: frame.point(u[p], v_lo, front[p]),
                }
            })
            .collect(),
    };
    let opened_cells = boxes.iter().map(|b| b.hidden).sum();
    let front_depth = front.iter().copied().fold(f64::INFINITY, f64::min);
    let shaped = build(&front, &back);
    let refused = match shaped.validate() {
        Ok(()) => {
            return Ok(OccluderCutter {
                cutter: shaped,
                opened_cells,
                front_depth,
                simplified: false,
            });
        }
        Err(e) => e,
    };
    let deepest = back.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let one_depth = build(&vec![front_depth; planes], &vec![deepest; planes]);
    match one_depth.validate() {
        Ok(()) => Ok(OccluderCutter {
            cutter: one_depth,
            opened_cells,
            front_depth,
            simplified: true,
        }),
        Err(e) => Err(format!("no valid cutter ({refused}; with one depth: {e})")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_fill_from_the_nearest_set_value() {
        let mut v = [f64::NAN, 2.0, f64::NAN, f64::NAN, 5.0, f64::NAN];
        assert!(fill_from_neighbours(&mut v, true));
        assert_eq!(v, [2.0, 2.0, 2.0, 5.0, 5.0, 5.0]);
        let mut none = [f64::NAN; 3];
        assert!(!fill_from_neighbours(&mut none, true));
    }
}
