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

use std::collections::VecDeque;

use glam::DVec3;

use super::cut_grid::{Cell, CutGrid, InCells};
use super::dyn_mesh::{DynMesh, prev};
use super::field::{FieldAt, taper_at};
use super::field_cache::{Changes, FieldCache, Kept};
pub use super::frames::{Frame, frames};
use super::kept_path::KeptPath;
use super::nearest_cut::{self, Balls};
use super::sides::Sides;
use super::step::Scalpel;
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
    let Some(inputs) = Inputs::new(scalpel, options, now, onto_path, None) else {
        return Vec::new();
    };
    let mesh = scalpel.dyn_mesh();
    let mut grid = CutGrid::new(scalpel.segments(), mesh.vertex_count() as u32, inputs.r);
    compute(scalpel, &inputs, &mut grid)
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
    /// feet valid for this mesh ([`KeptPath`]).
    pub fn new(
        scalpel: &Scalpel,
        options: &OpenOptions,
        now: f64,
        onto_path: bool,
        kept: Option<&mut KeptPath>,
    ) -> Option<Inputs> {
        let mesh = scalpel.dyn_mesh();
        let w = options.width;
        let segments = scalpel.segments();
        if w.is_nan() || w <= 0.0 || segments.is_empty() {
            return None;
        }
        let nv = mesh.vertex_count() as u32;
        let frames = frames(segments, w);
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
fn compute(scalpel: &Scalpel, inputs: &Inputs, grid: &mut CutGrid) -> Vec<(u32, DVec3)> {
    let field = walk(scalpel, inputs, grid, None, &mut Sides::default());
    let floors = floors_by_lips(scalpel, grid, None);
    let mut tables = MovedTables::default();
    finish(scalpel, inputs, field.iter(), floors, None, &mut tables)
}

/// Where a partial walk works: the cells it walks over (and seeds at the lips of), those whose
/// vertices' field it gives, and the field kept from before with what changed since (a
/// vertex's kept field is given when no change reaches it, [`FieldCache::kept`]).
pub(crate) struct WalkRegion<'a> {
    pub outer: &'a FastSet<Cell>,
    pub keep: &'a FastSet<Cell>,
    pub known: &'a FieldCache,
    pub changes: &'a Changes,
}

/// The field of every vertex the walk of the module doc reaches within the support, in the
/// order it reaches them, apart from the clock ([`FieldAt`]); fixed vertices are walked over,
/// not given. With a region, the walk stays in its outer cells and seeds only at lips there,
/// and gives the vertices of its kept cells only.
pub(crate) fn walk(
    scalpel: &Scalpel,
    inputs: &Inputs,
    grid: &mut CutGrid,
    region: Option<&WalkRegion>,
    side: &mut Sides,
) -> Vec<FieldAt> {
    let outer = region.map(|g| g.outer);
    let mesh = scalpel.dyn_mesh();
    let segments = scalpel.segments();
    let mut field = Vec::new();
    let r = inputs.r;
    let nv = mesh.vertex_count() as u32;
    let (frames, corrections, tips) = (&inputs.frames, &inputs.corrections, &inputs.tips);
    let onto_path = inputs.onto_path;
    let size = grid.size();
    let mut in_outer = InCells::new(outer, size);
    let mut in_keep = InCells::new(region.map(|g| g.keep), size);
    // Nearest point on the cut among the segments `near`: (distance, point, segment index).
    // `last` is the previous answer's segment, measured first (see [`nearest_cut`]).
    let balls = Balls::new(segments);
    let mut last: Option<usize> = None;
    let mut nearest = |p: DVec3, near: &[usize]| -> Option<(f64, DVec3, usize)> {
        let found = nearest_cut::nearest(segments, &balls, p, near, last);
        last = found.map(|f| f.2).or(last);
        found
    };
    // The correction at a point: the corrections at the ends of the segments `near` within
    // the support, weighted by inverse squared distance (exact at a lip vertex; smooth around
    // the zigzag's corners, where the nearest segment changes from one vertex to the next and a
    // correction taken from it alone would squash the small triangles there).
    let correction_at = |p: DVec3, near: &[usize]| -> DVec3 {
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for &i in near.iter().filter(|&&i| balls.may_reach(i, p, r)) {
            let s = &segments[i];
            for (end, c) in [(s.pa, corrections[i][0]), (s.pb, corrections[i][1])] {
                let d2 = end.distance_squared(p);
                if d2 == 0.0 {
                    return c;
                }
                if d2 < r * r {
                    let k = d2.recip();
                    sum += c * k;
                    weight += k;
                }
            }
        }
        if weight > 0.0 {
            sum / weight
        } else {
            DVec3::ZERO
        }
    };
    // Breadth-first over surface vertices from the lip copies (seeds with their side), within
    // the support; every other vertex takes the side of the vertex it was reached from. (So a
    // vertex takes the side of the first seed, in seed order, among those fewest surface edges
    // away: a region's vertices take the sides the whole walk gives them when its margin holds
    // those seeds and paths.)
    side.start(mesh.vertex_count());
    let mut queue: VecDeque<u32> = VecDeque::new();
    let mut fan = Vec::new();
    let seed_segments: Vec<usize> = match outer {
        None => (0..segments.len()).collect(),
        Some(o) => grid.segments_in(o),
    };
    for s in seed_segments.iter().map(|&i| &segments[i]) {
        for v in [s.a, s.b] {
            if v >= nv || !mesh.has_copies(v) || !in_outer.contains(mesh.pos(v)) {
                continue;
            }
            for c in std::iter::once(v).chain(mesh.copies(v)) {
                if side.contains(c) {
                    continue;
                }
                let p = mesh.pos(c);
                let Some((_, _, i)) = nearest(p, grid.near(p)) else {
                    continue;
                };
                let sigma = lip_side(mesh, c, &frames[i], &mut fan);
                if sigma != 0.0 {
                    side.insert(c, sigma);
                    queue.push_back(c);
                }
            }
        }
    }
    while let Some(v) = queue.pop_front() {
        let p = mesh.pos(v);
        // Neighbours are queued without asking where they lie (several per vertex, most
        // already queued); one outside the region is dropped here, given nothing and walked
        // from nowhere, as if never queued.
        if !in_outer.contains(p) {
            continue;
        }
        let Some(sigma) = side.get(v) else {
            continue;
        };
        // A kept field says the vertex is within the support, as before. Outside the kept
        // cells (the margin) no change reaches (they would be kept cells otherwise), and only
        // that is asked of it.
        let wanted = in_keep.contains(p);
        let kept = region.and_then(|g| g.known.kept(v, p, sigma, wanted.then_some(g.changes)));
        let (dist, c, i) = match kept {
            Some(k) => (0.0, k.field_at.nearest, k.field_at.segment as usize),
            None => {
                let Some(found) = nearest(p, grid.near(p)) else {
                    continue;
                };
                found
            }
        };
        if dist >= r {
            continue;
        }
        mesh.surface_fan_into(v, &mut fan);
        for &h in &fan {
            for n in [mesh.dest(h), mesh.origin(prev(h))] {
                if !mesh.is_floor(n) && !side.contains(n) {
                    side.insert(n, sigma);
                    queue.push_back(n);
                }
            }
        }
        if !wanted || (!inputs.fixed.is_empty() && inputs.fixed.contains(&v)) {
            continue;
        }
        if let Some(Kept {
            mut field_at,
            taper,
            correction,
        }) = kept
        {
            if taper {
                field_at.taper = taper_at(tips, field_at.nearest, inputs.taper_len);
            }
            if correction && onto_path {
                field_at.correction = correction_at(p, grid.near(p));
            }
            field.push(field_at);
            continue;
        }
        let taper = taper_at(tips, c, inputs.taper_len);
        let falloff = {
            let s2 = (dist / r) * (dist / r);
            (1.0 - s2) * (1.0 - s2)
        };
        let correction = if onto_path {
            correction_at(p, grid.near(p))
        } else {
            DVec3::ZERO
        };
        field.push(FieldAt {
            vertex: v,
            segment: i as u32,
            rest: p,
            nearest: c,
            dist,
            sigma,
            taper,
            falloff,
            correction,
        });
    }
    field
}

/// The floor vertices next to the lip copies (groove bottoms), those of the lips in `outer`
/// when given: the opening moves them by the lips' correction. Sorted, each once.
pub(crate) fn floors_by_lips(
    scalpel: &Scalpel,
    grid: &mut CutGrid,
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
    let mut floors = Vec::new();
    let mut fan = Vec::new();
    for s in lip_segments.iter().map(|&i| &segments[i]) {
        for v in [s.a, s.b] {
            if v >= nv || !mesh.has_copies(v) || !in_outer.contains(mesh.pos(v)) {
                continue;
            }
            for c in std::iter::once(v).chain(mesh.copies(v)) {
                // A lip copy with no cut segment near it seeds nothing (see `walk`).
                if grid.near(mesh.pos(c)).is_empty() {
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
        }
    }
    floors.sort_unstable();
    floors.dedup();
    floors
}

/// The opening from the field of the vertices within the support ([`walk`]) and the floors
/// next to the lips ([`floors_by_lips`]): each field evaluated at this clock, the path
/// corrections and then the displacements unfolded, the floors moved by the lips' corrections.
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
    super::unfold::unfold_correction(mesh, &mut out, &mut corrected, &mut around);
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
    super::unfold::unfold(mesh, &mut out, &mut around);
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

/// The side (`±1` along the frame's lateral) lip copy `v` opens to, from its own surface
/// triangles: they lie left of the lip `y → v → x` (the first and last edges of its surface
/// fan), so the side is `+1` when that lip runs along the path. `0` when `v` is no lip (a
/// closed surface fan) or the lip runs across the path.
fn lip_side(mesh: &DynMesh, v: u32, frame: &Frame, fan: &mut Vec<u32>) -> f64 {
    let closed = mesh.fan_into(v, fan);
    if closed && !fan.iter().any(|&h| mesh.is_wall(h / 3)) {
        return 0.0;
    }
    if !mesh.surface_fan_into(v, fan) {
        return 0.0;
    }
    let (Some(&first), Some(&last)) = (fan.first(), fan.last()) else {
        return 0.0;
    };
    let along = mesh.pos(mesh.dest(first)) - mesh.pos(mesh.origin(prev(last)));
    let d = along.dot(frame.tangent);
    if d.abs() <= 1e-6 * along.length() {
        0.0
    } else {
        d.signum()
    }
}
