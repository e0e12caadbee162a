//! The opening kept between steps: each step recomputes only the vertices whose support
//! changed.
//!
//! [`super::dffd::open_displacements`] computes the opening of the whole incision from scratch:
//! on a long stroke that is tens of milliseconds, more than a frame. A step changes little of
//! it: the segments it cut (and the temporary tip it undid), the frames and path corrections
//! of the segments within about a width of those, the crack tips, the segments still opening
//! within the time window, the vertices it split, moved or copied. [`LiveOpening::update`]
//! compares what the opening is computed from ([`super::dffd::Inputs`], per segment) with what
//! it was computed from last time, reads the mesh's edit log ([`DynMesh::edits_since`]), and
//! recomputes the cells of the cut grid around what changed:
//! - a vertex's opening depends on the cut segments within the support `r` of it (nearest
//!   segment, frame, ramp, corrections) and on the crack tips within the taper length of its
//!   nearest cut point, so the *inner* region is the cells holding a point within `r` of a
//!   changed segment or vertex, or within `taper + r` of a tip that appeared or went (a ball of
//!   cells, [`cells_within`]: the cube of cells around a tip held three times as many);
//! - which side of the cut a vertex opens to is decided by a walk from the lips (the first
//!   lip, in seed order, fewest surface edges away), and the unfolding pulls back folded
//!   triangles together with their neighbours; the walk, the seeds and the unfolding are run
//!   over the inner cells and [`MARGIN`] cells around them (the *outer* region), and only the
//!   inner cells' vertices are taken.
//!
//! Most inner cells are there only because the segments near them opened a little further with
//! the clock (the last half second of path is still opening): the field there
//! ([`super::field::FieldAt`]: side, nearest segment, taper, path correction) is what it was.
//! So the field of every vertex is kept ([`FieldCache`]); only the *walked* cells (those around
//! a segment cut, undone, moved or given another frame or path correction, a fixed vertex or
//! an edit) are walked again, over them and the margin, and there too a vertex keeps its field
//! unless such a change reaches it. A crack tip appears or goes only where a segment was cut or
//! undone or a vertex copied, all walked; further out, up to `taper + r`, only the tapers of
//! the kept field are measured again ([`FieldCache::retaper`]): walking those cells too had
//! the walk cover half as much again. The field of the outer region is then evaluated at the
//! new clock, and the unfolding and the floors run over it as before.
//!
//! The cut grid (the segments by cell) is kept and only the changed segments are moved in it.
//! The result equals the opening computed from scratch when every seed and walk deciding an
//! inner vertex's side, and every folded patch it belongs to, lies within the margin of it
//! (the tests compare both, bit for bit, on long strokes); everything else is exact by
//! construction. Cost: the changed region, never the incision or the mesh, plus a few passes
//! over the segments: to compare them, and for their frames (taken from the last step where
//! the segments a frame reads stayed, [`super::frames::frames_reusing`]) and corrections (the
//! samples' feet on the surface those need, a search each, the smoothed strokes and the
//! corrections of the segments whose stroke and frame stayed are kept between steps,
//! [`super::kept_path`]).

use glam::DVec3;

use super::cut_grid::{Cell, CutGrid, cell_of, cells_within};
use super::dffd::{Inputs, OpenOptions, finish, floors_by_lips, taper_length};
use super::field_cache::{Changes, FieldCache};
use super::kept_path::KeptPath;
use super::side_walk::{WalkRegion, walk};
use super::sides::Sides;
use super::step::{CutSegment, Scalpel};
use super::unfold::MovedTables;
use csg::fast_hash::{FastMap, FastSet};

/// Cells of margin walked around the recomputed cells (see the module doc).
pub const MARGIN: i64 = 1;

/// What one [`LiveOpening::update`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpeningUpdate {
    /// Everything was recomputed (the first update, the options or the stroke's undo history
    /// changed).
    pub full: bool,
    /// Grid cells recomputed (0 when full or nothing changed).
    pub cells: usize,
    /// Vertices given by the recomputation.
    pub vertices: usize,
}

/// The opening of one scalpel's mesh, kept between steps (see the module doc).
#[derive(Default)]
pub struct LiveOpening {
    state: Option<State>,
    /// Every vertex the opening moves, with its display position.
    moved: FastMap<u32, DVec3>,
    /// The vertices of `moved` by the cell of their rest position (may hold stale ids).
    by_cell: FastMap<Cell, Vec<u32>>,
    /// The drawn samples' feet on the surface, the smoothed strokes and the segments' path
    /// corrections, kept for the path corrections.
    path: KeptPath,
    /// The field of every vertex within the support, apart from the clock.
    field: FieldCache,
    /// The walk's sides, kept between steps (a walk clears only what it set).
    sides: Sides,
    /// The unfolding's tables, kept between steps likewise.
    tables: MovedTables,
}

/// What the kept opening was computed from.
struct State {
    options: OpenOptions,
    inputs: Inputs,
    segments: Vec<CutSegment>,
    fixed: Vec<u32>,
    /// How many drawn samples there were.
    samples: usize,
    grid: CutGrid,
    cursor: usize,
}

impl LiveOpening {
    pub fn new() -> LiveOpening {
        LiveOpening::default()
    }

    /// The vertices the opening moves, with their display positions (in no order).
    pub fn moved(&self) -> &FastMap<u32, DVec3> {
        &self.moved
    }

    /// Whether [`LiveOpening::moved`] is the opening of `scalpel`'s mesh at `now` already.
    pub fn is_current(&self, scalpel: &Scalpel, options: &OpenOptions, now: f64) -> bool {
        // The mesh logs every edit; segments, fixed vertices and samples only grow or shrink
        // with one.
        self.state.as_ref().is_some_and(|st| {
            st.cursor == scalpel.dyn_mesh().edit_cursor()
                && st.options == *options
                && st.inputs.now == now
                && st.inputs.taper_len == taper_length(options.width, scalpel.options().depth)
                && st.segments.len() == scalpel.segments().len()
                && st.fixed.len() == scalpel.fixed.len()
                && st.samples == scalpel.drawn.len()
        })
    }

    /// Brings the opening to `scalpel`'s mesh at tool time `now`, the lips onto the drawn path
    /// (as [`super::dffd::open_displacements`]).
    pub fn update(&mut self, scalpel: &Scalpel, options: &OpenOptions, now: f64) -> OpeningUpdate {
        if self.is_current(scalpel, options, now) {
            return OpeningUpdate::default();
        }
        let mesh = scalpel.dyn_mesh();
        let cursor = mesh.edit_cursor();
        // The kept feet hold for the mesh of the last update: drop those its edits reach.
        match self
            .state
            .as_ref()
            .and_then(|st| mesh.edits_since(st.cursor))
        {
            Some(edits) => self.path.feet.forget(edits),
            None => self.path.clear(),
        }
        let before = self.state.as_ref().map(|st| (&st.segments[..], &st.inputs));
        let Some(inputs) = Inputs::new(scalpel, options, now, true, Some(&mut self.path), before)
        else {
            self.state = None;
            self.moved.clear();
            self.by_cell.clear();
            self.field.clear();
            return OpeningUpdate {
                full: true,
                ..OpeningUpdate::default()
            };
        };
        let segments = scalpel.segments();
        let nv = mesh.vertex_count() as u32;
        let edits = self.state.as_ref().and_then(|st| {
            let same = st.options == *options
                && st.inputs.taper_len == inputs.taper_len
                && st.inputs.onto_path == inputs.onto_path;
            same.then(|| mesh.edits_since(st.cursor)).flatten()
        });
        let (Some(edits), Some(mut state)) = (edits, self.state.take()) else {
            let grid = CutGrid::new(segments, nv, inputs.r);
            let size = grid.size();
            let field = walk(scalpel, &inputs, &grid, None, &mut self.sides);
            let floors = floors_by_lips(scalpel, &grid, None);
            let out = finish(
                scalpel,
                &inputs,
                field.iter(),
                floors,
                None,
                &mut self.tables,
            );
            self.field.replace(None, field, size);
            self.moved.clear();
            self.by_cell.clear();
            self.insert(scalpel, out, size);
            let vertices = self.moved.len();
            self.state = Some(State {
                options: *options,
                inputs,
                segments: segments.to_vec(),
                fixed: scalpel.fixed.clone(),
                samples: scalpel.drawn.len(),
                grid,
                cursor,
            });
            return OpeningUpdate {
                full: true,
                cells: 0,
                vertices,
            };
        };
        let size = state.grid.size();
        let (old, new) = (&state.inputs, &inputs);
        // Cells recomputed: those holding a point within the given distance of a change (see
        // the module doc). Of those, the cells where only segments' ramps changed keep their
        // field ([`FieldCache`]); the field of the others (`walked`) is walked again.
        let mut walked: FastSet<Cell> = FastSet::default();
        let mut clock_only: FastSet<Cell> = FastSet::default();
        let r = new.r;
        let mut changes = Changes {
            taper_len: new.taper_len,
            r,
            ..Changes::default()
        };
        for i in 0..state.segments.len().max(segments.len()) {
            let (before, after) = (state.segments.get(i), segments.get(i));
            // Every point within `r` of the segment is within `r` and half its length of its
            // middle.
            let around = |s: &CutSegment| (s.pa.midpoint(s.pb), r + 0.5 * s.pa.distance(s.pb));
            if let (Some(a), Some(b)) = (before, after)
                && a == b
            {
                let same_frame = old.frames[i].tangent == new.frames[i].tangent
                    && old.frames[i].lateral == new.frames[i].lateral;
                let same_corrections = old.corrections[i] == new.corrections[i];
                let (p, reach) = around(a);
                if same_frame && same_corrections {
                    if old.ramp(a.time) != new.ramp(a.time) {
                        cells_within(&mut clock_only, p, reach, size);
                    }
                    continue;
                }
                // The segment stays where it was: the nearest segments and tapers around it
                // too. Its frame decides the sides of the lips near it (walked again); the kept
                // path corrections near it are measured again when its own changed.
                cells_within(&mut walked, p, reach, size);
                if !same_corrections {
                    changes.corrections(a, r);
                }
                continue;
            }
            if let Some(a) = before {
                let (p, reach) = around(a);
                cells_within(&mut walked, p, reach, size);
                state.grid.remove(i, a);
                changes.segment(i, a, r);
            }
            if let Some(b) = after {
                let (p, reach) = around(b);
                cells_within(&mut walked, p, reach, size);
                state.grid.insert(i, b, nv);
                changes.segment(i, b, r);
            }
        }
        // A crack tip appears or goes only where segments were cut or undone, or a vertex was
        // copied (all walked above and below): around it, further out, only the tapers change.
        let mut retaper: FastSet<Cell> = FastSet::default();
        let tip_reach = new.taper_len + r;
        for t in old.tips.iter().filter(|t| !new.tips.contains(t)) {
            cells_within(&mut retaper, *t, tip_reach, size);
            changes.tips.push(*t);
        }
        for t in new.tips.iter().filter(|t| !old.tips.contains(t)) {
            cells_within(&mut retaper, *t, tip_reach, size);
            changes.tips.push(*t);
        }
        let common = state
            .fixed
            .iter()
            .zip(&scalpel.fixed)
            .take_while(|(a, b)| a == b)
            .count();
        // Only whether a vertex is fixed matters, and only to the walk, which never visits a
        // groove floor (the groove bottoms, which are nearly all the fixed vertices; a step
        // undoes its temporary tip's groove and makes it again, with new ones): the surface
        // vertices that became fixed or stopped being so.
        for &v in state.fixed[common..].iter().chain(&scalpel.fixed[common..]) {
            if v < nv && !mesh.is_floor(v) && old.fixed.contains(&v) != new.fixed.contains(&v) {
                cells_within(&mut walked, mesh.pos(v), r, size);
            }
        }
        // The log repeats a vertex for each edit of it (a step undoes its temporary tip and
        // makes it again): each once.
        let mut edited = edits.to_vec();
        edited.sort_unstable();
        edited.dedup();
        for v in edited {
            if let Some(p) = self.moved.remove(&v) {
                // Its display position: its rest one is gone; the cells around it.
                grow(&mut walked, cell_of(p, size), 1);
            }
            // The cell its field was kept in, by its rest position then.
            if let Some(c) = self.field.cell_of_vertex(v) {
                walked.insert(c);
            }
            if v < nv {
                cells_within(&mut walked, mesh.pos(v), r, size);
            }
        }
        // The field of the walked cells, walked over them and a margin around them as the whole
        // walk would (see the module doc).
        if !walked.is_empty() {
            let mut around =
                FastSet::with_capacity_and_hasher(walked.len() * 4, Default::default());
            for &c in &walked {
                grow(&mut around, c, MARGIN);
            }
            let region = WalkRegion {
                outer: &around,
                keep: &walked,
                known: &self.field,
                changes: &changes,
            };
            let field = walk(
                scalpel,
                &inputs,
                &state.grid,
                Some(&region),
                &mut self.sides,
            );
            self.field.replace(Some(&walked), field, size);
        }
        retaper.retain(|c| !walked.contains(c));
        self.field.retaper(&retaper, &inputs.tips, inputs.taper_len);
        let mut inner = walked;
        inner.extend(clock_only);
        inner.extend(retaper);
        let mut outer = FastSet::with_capacity_and_hasher(inner.len() * 4, Default::default());
        for &c in &inner {
            grow(&mut outer, c, MARGIN);
        }
        let cells = inner.len();
        if cells > 0 {
            for c in &inner {
                if let Some(list) = self.by_cell.remove(c) {
                    for v in list {
                        if self.moved.get(&v).is_some_and(|_| {
                            (v as usize) >= mesh.vertex_count() || cell_of(mesh.pos(v), size) == *c
                        }) {
                            self.moved.remove(&v);
                        }
                    }
                }
            }
        }
        state.inputs = inputs;
        state.segments.clear();
        state.segments.extend_from_slice(segments);
        state.fixed.clear();
        state.fixed.extend_from_slice(&scalpel.fixed);
        state.cursor = cursor;
        state.samples = scalpel.drawn.len();
        let mut vertices = 0;
        if cells > 0 {
            let floors = floors_by_lips(scalpel, &state.grid, Some(&outer));
            let field = self.field.in_cells(&outer);
            let out = finish(
                scalpel,
                &state.inputs,
                field,
                floors,
                Some((&inner, size)),
                &mut self.tables,
            );
            vertices = out.len();
            self.insert(scalpel, out, size);
        }
        self.state = Some(state);
        OpeningUpdate {
            full: false,
            cells,
            vertices,
        }
    }

    fn insert(&mut self, scalpel: &Scalpel, out: Vec<(u32, DVec3)>, size: f64) {
        let mesh = scalpel.dyn_mesh();
        for (v, p) in out {
            self.moved.insert(v, p);
            self.by_cell
                .entry(cell_of(mesh.pos(v), size))
                .or_default()
                .push(v);
        }
    }
}

/// Adds to `cells` the cells within `reach` cells of `c` (a cube).
fn grow(cells: &mut FastSet<Cell>, c: Cell, reach: i64) {
    for x in c.0 - reach..=c.0 + reach {
        for y in c.1 - reach..=c.1 + reach {
            for z in c.2 - reach..=c.2 + reach {
                cells.insert((x, y, z));
            }
        }
    }
}
