//! Opening the incision: a discontinuous free-form deformation (Sela, Schein, Elber 2004).
//!
//! The DFFD paper inserts a C⁻¹ knot along the incision so that a smooth displacement field
//! jumps across it. Here the field is evaluated directly at the vertices: a vertex at distance
//! `dist < r` from the cut (nearest point `c` on a cut segment) moves by
//! `ramp · φ(dist / r) · (δ + σ · (w / 2) · taper · l)`, where
//! - `l = n × t` is the lateral direction of the *path*, not of the one mesh edge nearest the
//!   vertex: the cut runs along mesh edges that zigzag around the drawn path (snapping), so the
//!   tangent `t` and normal `n` are averaged over the cut segments within about one width on
//!   either side ([`frames`]). With per-edge directions neighbouring vertices moved in directions
//!   up to the zigzag's angle apart, and the lips looked torn;
//! - `σ = ±1` is the side of the cut the vertex is on (the discontinuity). It is decided by the
//!   mesh, not by coordinates: each lip copy knows its side from the orientation of its own
//!   surface triangles (the surface lies left of the lip it walks along, and left is `+l` when
//!   the lip runs along `t`), and every other vertex takes the side of the lip it is reached from
//!   over surface triangles (a breadth-first walk that never crosses the cut, since the lips are
//!   split and groove walls are not walked). A vertex's own position says nothing reliable: next
//!   to a zigzagging lip it can lie across the nearest edge's line, and a groove lip's fan holds
//!   long wall triangles reaching to a floor vertex far along the path, which used to put both
//!   lips of a groove on one side, so they moved together and the groove did not open;
//! - `ramp = clamp((now - t_cut) / window, 0, 1)`: the trailing time window over which a freshly
//!   cut segment opens to its full width;
//! - `taper` goes from 0 at a crack tip to 1 one width away (or, for a groove, where its depth
//!   stops tapering, [`super::groove::TAPER_DEPTHS`] blade depths away, when that is farther), so
//!   the lips meet at the tips and a groove never opens wider than it is deep near them;
//! - `φ(s) = (1 - s²)²` and `r = 3 w` (the support);
//! - `δ` moves the lips onto the drawn path: the rest-pose cut zigzags around the path along
//!   mesh edges (by up to a fraction of an edge, more than a width on a coarse skin), and
//!   shifted sideways as it is the lips showed its spikes and notches. [`super::drawn`] gives
//!   each cut segment's ends their lateral offset to the drawn path (smoothed over about a
//!   width); `δ` at a vertex is the inverse-squared-distance mean of those near it, so a lip
//!   vertex gets its own exactly (both copies alike: the gap is kept) and the surface around the
//!   lips follows smoothly. A groove's floor vertices move by the mean `δ` of the lips their
//!   walls reach (no opening), so the floor stays under the drawn path and the walls are alike.
//!
//! Where that field would turn a surface triangle over (sharp bends, corners framed by
//! different segments), [`super::unfold`] shrinks first the path corrections `δ` of its corners
//! (where `δ` is larger than the triangles around it allow), then the displacements.
//!
//! Vertices outside the support are never written: their display position is their rest
//! position bit for bit. The rest pose itself is never changed (cutting continues
//! in the rest pose).

use glam::DVec3;

use super::cut_grid::{Cell, CutGrid, InCells, Near};
use super::dyn_mesh::prev;
use super::field::FieldAt;
use super::frames::frames_reusing;
pub use super::frames::{Frame, frames};
use super::kept_path::KeptPath;
use super::side_walk::walk;
use super::sides::Sides;
use super::step::{CutSegment, Scalpel};
use super::unfold::{Moved, MovedTables};
use csg::fast_hash::FastSet;

/// How the incision opens.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenOptions {
    /// Final gap between the lips (model units). Default `0` (closed).
    pub width: f64,
    /// Seconds over which a freshly cut segment opens to full width. Default `0.5`.
    pub window: f64,
}

impl Default for OpenOptions {
    fn default() -> Self {
        OpenOptions {
            width: 0.0,
            window: 0.5,
        }
    }
}

/// Support radius as a multiple of the width.
const SUPPORT: f64 = 3.0;

/// Display positions of `scalpel`'s mesh opened at tool time `now` (seconds): the rest
/// positions with [`open_displacements`] applied.
pub fn open_positions(scalpel: &Scalpel, options: &OpenOptions, now: f64) -> Vec<DVec3> {
    let mut out = scalpel.dyn_mesh().positions().to_vec();
    for (v, p) in open_displacements(scalpel, options, now) {
        out[v as usize] = p;
    }
    out
}

/// The vertices the opening moves at tool time `now`, with their display positions (sparse:
/// only vertices inside the support; cost proportional to them, not to the mesh).
pub fn open_displacements(scalpel: &Scalpel, options: &OpenOptions, now: f64) -> Vec<(u32, DVec3)> {
    displacements(scalpel, options, now, true)
}

/// [`open_displacements`] without moving the lips onto the drawn path: the rest-pose cut
/// (its zigzag along the mesh edges) shifted sideways, as the opening was before. For
/// comparisons (tests, benches); the window and the command line show [`open_displacements`].
pub fn open_displacements_along_cut(
    scalpel: &Scalpel,
    options: &OpenOptions,
    now: f64,
) -> Vec<(u32, DVec3)> {
    displacements(scalpel, options, now, false)
}

fn displacements(
    scalpel: &Scalpel,
    options: &OpenOptions,
    now: f64,
    onto_path: bool,
) -> Vec<(u32, DVec3)> {
    let Some(inputs) = Inputs::new(scalpel, options, now, onto_path, None, None) else {
        return Vec::new();
    };
    let mesh = scalpel.dyn_mesh();
    let grid = CutGrid::new(scalpel.segments(), mesh.vertex_count() as u32, inputs.r);
    compute(scalpel, &inputs, &grid)
}

/// What the opening of every vertex is computed from, besides the mesh: per cut segment its
/// frame and its ends' path corrections, the crack tips, the vertices never moved, the clock.
/// The live opening ([`super::live_opening`]) compares two of these to find what a step changed.
#[derive(Clone, Debug)]
pub(crate) struct Inputs {
    pub width: f64,
    /// The support radius.
    pub r: f64,
    pub window: f64,
    pub now: f64,
    pub onto_path: bool,
    pub taper_len: f64,
    pub frames: Vec<Frame>,
    pub corrections: Vec<[DVec3; 2]>,
    /// Crack tips: segment ends whose vertex was never copied.
    pub tips: Vec<DVec3>,
    pub fixed: FastSet<u32>,
}

impl Inputs {
    /// `None` when nothing opens (no width, no cut).
    /// `kept`: the path corrections' feet, smoothed strokes and measures kept from before, the
    /// feet valid for this mesh ([`KeptPath`]). `before`: the segments and inputs of the last
    /// step, whose frames are taken where they read the same segments ([`frames_reusing`]).
    pub fn new(
        scalpel: &Scalpel,
        options: &OpenOptions,
        now: f64,
        onto_path: bool,
        kept: Option<&mut KeptPath>,
        before: Option<(&[CutSegment], &Inputs)>,
    ) -> Option<Inputs> {
        let mesh = scalpel.dyn_mesh();
        let w = options.width;
        let segments = scalpel.segments();
        if w.is_nan() || w <= 0.0 || segments.is_empty() {
            return None;
        }
        let nv = mesh.vertex_count() as u32;
        let frames = match before {
            Some((old, last)) if last.width.to_bits() == w.to_bits() => {
                frames_reusing(segments, w, (old, &last.frames))
            }
            _ => frames(segments, w),
        };
        let mut tips: Vec<DVec3> = Vec::new();
        for s in segments {
            for (v, p) in [(s.a, s.pa), (s.b, s.pb)] {
                if v < nv && !mesh.has_copies(v) && !tips.contains(&p) {
                    tips.push(p);
                }
            }
        }
        // A groove's depth tapers toward its tips over `TAPER_DEPTHS` blade depths: opening it
        // wider than it is deep there would tilt its walls over the lips (folded triangles).
        let taper_len = taper_length(w, scalpel.options().depth);
        // Per segment end, the lateral move onto the drawn path (see the module doc).
        let corrections = if onto_path {
            super::drawn::corrections(mesh, &scalpel.drawn, segments, &frames, w, kept)
        } else {
            vec![[DVec3::ZERO; 2]; segments.len()]
        };
        Some(Inputs {
            width: w,
            r: SUPPORT * w,
            window: options.window,
            now,
            onto_path,
            taper_len,
            frames,
            corrections,
            tips,
            fixed: scalpel.fixed.iter().copied().collect(),
        })
    }

    /// How far a segment cut at `time` has opened at this clock (0 to 1).
    pub fn ramp(&self, time: f64) -> f64 {
        if self.window > 0.0 {
            ((self.now - time) / self.window).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }
}

/// The opening of every vertex: the field of the module doc, the unfolding and the groove
/// floors.
fn compute(scalpel: &Scalpel, inputs: &Inputs, grid: &CutGrid) -> Vec<(u32, DVec3)> {
    let field = walk(scalpel, inputs, grid, None, &mut Sides::default());
    let floors = floors_by_lips(scalpel, grid, None);
    let mut tables = MovedTables::default();
    finish(scalpel, inputs, field.iter(), floors, None, &mut tables)
}

/// The floor vertices next to the lip copies (groove bottoms), those of the lips in `outer`
/// when given: the opening moves them by the lips' correction. Sorted, each once.
pub(crate) fn floors_by_lips(
    scalpel: &Scalpel,
    grid: &CutGrid,
    outer: Option<&FastSet<Cell>>,
) -> Vec<u32> {
    let mesh = scalpel.dyn_mesh();
    let segments = scalpel.segments();
    let nv = mesh.vertex_count() as u32;
    let size = grid.size();
    let mut in_outer = InCells::new(outer, size);
    let lip_segments: Vec<usize> = match outer {
        None => (0..segments.len()).collect(),
        Some(o) => grid.segments_in(o),
    };
    // The lip copies, each once (a path vertex ends two segments, and its copies are the
    // other lip's).
    let mut lips: Vec<u32> = Vec::new();
    for s in lip_segments.iter().map(|&i| &segments[i]) {
        for v in [s.a, s.b] {
            if v < nv && mesh.has_copies(v) && in_outer.contains(mesh.pos(v)) {
                lips.push(v);
                lips.extend(mesh.copies(v));
            }
        }
    }
    lips.sort_unstable();
    lips.dedup();
    let mut floors = Vec::new();
    let mut fan = Vec::new();
    let mut near = Near::default();
    for c in lips {
        // A lip copy with no cut segment near it seeds nothing (see `walk`).
        if near.near(grid, mesh.pos(c)).is_empty() {
            continue;
        }
        mesh.fan_into(c, &mut fan);
        for &h in &fan {
            floors.extend(
                mesh.triangles()[(h / 3) as usize]
                    .iter()
                    .filter(|&&f| mesh.is_floor(f)),
            );
        }
    }
    floors.sort_unstable();
    floors.dedup();
    floors
}

/// The opening from the field of the vertices within the support ([`super::side_walk::walk`])
/// and the floors next to the lips ([`floors_by_lips`]): each field evaluated at this clock,
/// the path corrections and then the displacements unfolded, the floors moved by the lips'
/// corrections.
/// With `keep` (cells, their size), only the vertices of those cells are given. `tables`: the
/// unfolding's tables, cleared ([`MovedTables`]), cleared again after.
pub(crate) fn finish<'a>(
    scalpel: &Scalpel,
    inputs: &Inputs,
    field: impl Iterator<Item = &'a FieldAt>,
    floors: Vec<u32>,
    keep: Option<(&FastSet<Cell>, f64)>,
    tables: &mut MovedTables,
) -> Vec<(u32, DVec3)> {
    let mesh = scalpel.dyn_mesh();
    let segments = scalpel.segments();
    let mut out = Vec::new();
    let mut corrected: Vec<DVec3> = Vec::new();
    for f in field {
        if let Some((p, c)) = f.opened(inputs, segments) {
            out.push((f.vertex, p));
            corrected.push(c);
        }
    }
    // Both unfoldings look at the triangles around the same moved vertices.
    let mut around = Some(Moved::with_tables(mesh, &out, std::mem::take(tables)));
    let folding = super::unfold::unfold_correction(mesh, &mut out, &mut corrected, &mut around);
    // Floor vertices under the lips: the mean correction of the surface vertices their walls
    // reach (both lips of a groove have the same), so that the floor stays under the drawn path
    // and the two walls are alike.
    let index = around.as_ref().expect("made above");
    let mut floor_moves = Vec::new();
    let mut fan = Vec::new();
    for f in floors {
        mesh.fan_into(f, &mut fan);
        let (mut sum, mut count) = (DVec3::ZERO, 0.0);
        for &h in &fan {
            for n in [mesh.dest(h), mesh.origin(prev(h))] {
                if !mesh.is_floor(n) {
                    sum += index.slot(n).map_or(DVec3::ZERO, |k| corrected[k]);
                    count += 1.0;
                }
            }
        }
        if count > 0.0 && sum != DVec3::ZERO {
            floor_moves.push((f, mesh.pos(f) + sum / count));
        }
    }
    super::unfold::unfold(mesh, &mut out, &mut around, folding);
    if let Some(m) = around {
        *tables = m.into_tables();
    }
    out.extend(floor_moves);
    if let Some((cells, size)) = keep {
        let mut in_cells = InCells::new(Some(cells), size);
        out.retain(|&(v, _)| in_cells.contains(mesh.pos(v)));
    }
    out
}

/// How far from a crack tip the opening of `width` tapers, for a blade `depth` deep.
pub fn taper_length(width: f64, depth: f64) -> f64 {
    width.max(super::groove::TAPER_DEPTHS * depth)
}
