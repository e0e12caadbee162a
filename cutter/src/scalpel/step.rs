//! The scalpel session: strokes, steps and the surface walk.
//!
//! Notation: `v` the current cut vertex, `q` the tool sample, `n` the normal at `v`, `d = q - v`.
//! The walking plane passes through `v`, `q` and `v + |d| n`; the exact side of each fan vertex
//! against it decides where the cut leaves `v`'s fan:
//! - through a vertex `b` on the plane (cut along edge `v b`),
//! - through the edge `b c` opposite `v` at parameter `t` (split it; near its ends go through the
//!   end vertex instead),
//! - nowhere (the fan ends at a boundary ahead: cross to the other lip of a slit or stop).
//!
//! Stages of a step: (1) undo the previous temporary tip; (2) walk permanently from the anchor
//! (the last permanent cut vertex) while the next crossing lies before the foot of `q`;
//! (3) place the tip (the foot of `q`, snapped) temporarily, with the groove walls that close
//! it. On any error the mesh is rolled back to the state before (1) and the old tip is redone.
//!
//! This file holds the session and the stroke life cycle; the walk (`step/walk.rs`), the tips
//! (`step/tips.rs`) and the mesh edits of a cut (`step/edits.rs`) are further `impl` blocks of
//! [`Scalpel`] in child modules.

use glam::DVec3;

use super::cut_point::{CutPoint, classify, classify_on_edges, closest_face_near, side};
use super::dyn_mesh::{DynMesh, Mark, NO_TWIN, NONMANIFOLD, is_real, next, prev};
use super::groove::{Groove, GrooveBackup};
use super::locate::Locator;
use super::{ScalpelError, ScalpelOptions, Tool};

mod edits;
mod tips;
mod walk;

/// Seconds between two tool samples (the tool clock the opening's time window runs on).
pub const SAMPLE_PERIOD: f64 = 1.0 / 60.0;

/// Tip snapping radius of both slits of a through-cut (see `Scalpel::end_snap`).
const THROUGH_SNAP_END: f64 = 0.02;

pub use super::cut_point::RESTART_SEARCH;

/// Triangles reserved for cuts when a scalpel is made (at least; more on large meshes).
const RESERVED_TRIANGLES: usize = 65_536;

/// A cut that cannot leave its anchor is stuck (see `Scalpel::stuck`) once the blade is this
/// many of the anchor's longest surface edges away.
const STUCK_REACH: f64 = 2.0;

/// At most this many triangles examined when a through-cut looks for its far side under a
/// sample (see `Scalpel::place_tips`).
const FAR_SEARCH: usize = 512;

/// Why a slot's step was refused when it reached another cut or a boundary (see `step`).
const SLOT_BLOCKED: &str = "through-cut blocked by a cut or boundary";

/// At most this many fan crossings in one step (a guard against a walk that cannot progress).
const MAX_CROSSINGS: usize = 100_000;

/// What a step did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepReport {
    /// Triangles the step's walk crossed (permanent part plus the tip's triangle).
    pub triangles_crossed: usize,
    /// Whether the blade is on the mesh after the step.
    pub on_mesh: bool,
}

/// What a finished stroke did.
#[derive(Clone, Debug, Default)]
pub struct StrokeReport {
    /// Triangles crossed by the stroke's cuts.
    pub triangles_cut: usize,
    /// Net triangles added by the stroke.
    pub triangles_created: usize,
    /// Pieces a loop detached (compacted, rest pose).
    pub detached: Vec<csg::Mesh>,
}

/// One segment of a cut in the rest pose, for the opening deformation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutSegment {
    pub a: u32,
    pub b: u32,
    pub pa: DVec3,
    pub pb: DVec3,
    /// Surface normal where the segment was cut.
    pub normal: DVec3,
    /// Tool clock (seconds) when the segment was cut.
    pub time: f64,
}

#[cfg(test)]
impl CutSegment {
    /// A segment from `pa` to `pb` between vertices 0 and 1, cut at time 0 on a +Z surface
    /// (the unit tests' segment).
    pub(crate) fn between(pa: DVec3, pb: DVec3) -> CutSegment {
        CutSegment {
            a: 0,
            b: 1,
            pa,
            pb,
            normal: DVec3::Z,
            time: 0.0,
        }
    }
}

/// One connected run of a stroke on the surface.
#[derive(Clone, Debug)]
pub(crate) struct Cut {
    pub start: u32,
    /// Last permanent cut vertex.
    pub anchor: u32,
    /// Permanent path vertices (ids when reached; cuts may give them copies later).
    pub path: Vec<u32>,
    pub groove: Option<Groove>,
    /// One side of a through-cut: never doubles back along its own open slit.
    pub through: bool,
    /// The two ends of the edge the cut split to make its anchor (`None` when the anchor is a
    /// vertex it went through). A groove never goes on along that edge (see `walk`).
    pub split_edge: Option<(u32, u32)>,
}

/// Where the walk toward a sample ends, relative to the anchor.
#[derive(Clone, Copy, Debug)]
enum End {
    AtVertex,
    OnVertex(u32),
    OnEdge { h: u32, p: DVec3 },
    InFace { t: u32, p: DVec3 },
}

enum WalkEnd {
    Reached(End),
    Blocked { merged: bool },
    Closed,
}

enum Exit {
    Blocked,
    Degenerate,
    /// Along the edge of half-edge `e` (between `v` and `b`).
    Vertex {
        e: u32,
        b: u32,
    },
    /// Across the edge `next(h0)` of the triangle of outgoing half-edge `h0`, at `t` from `dest(h0)`.
    Edge {
        h0: u32,
        t: f64,
        y: DVec3,
    },
}

#[derive(Clone, Debug)]
struct Tip {
    mark: Mark,
    groove: Option<GrooveBackup>,
    segments: usize,
    crossed: usize,
}

#[derive(Clone, Debug)]
struct Stroke {
    mark: Mark,
    /// `segments.len()` and `fixed.len()` before the stroke.
    records: (usize, usize),
    triangles_before: usize,
    cut: Option<Cut>,
    tip: Option<Tip>,
    /// The sample the current tip was placed for.
    tip_q: Option<DVec3>,
    touched: bool,
    merged: bool,
    crossed: usize,
    /// The stroke's first cut start (for closing a loop).
    first_start: Option<u32>,
    /// The stroke cuts grooves into a closed surface: every step must leave it closed.
    closed: bool,
    /// Cutting through ([`super::through`]): the slit on the far side, under the current cut.
    far: Option<Cut>,
    /// Thickness of the structure where the through-cut started.
    thickness: f64,
    /// Where the stroke's last cut ended inside the stroke (a merge into another cut): a cut
    /// restarting in this stroke searches for its start from there, not over the whole mesh.
    last_end: Option<u32>,
    /// Whether the surface where the stroke first touched the mesh is closed (the one global
    /// scan of a stroke; a restart in the stroke is on the same surface and reuses it).
    surface_closed: bool,
    /// The connected component (of the input, see [`Locator`]) the stroke started on.
    component: Option<u32>,
}

/// A scalpel working on one mesh.
#[derive(Clone, Debug)]
pub struct Scalpel {
    pub(crate) mesh: DynMesh,
    options: ScalpelOptions,
    tolerance: f64,
    stroke: Option<Stroke>,
    /// Mesh state, segment count and fixed-vertex count before each committed stroke, and the
    /// component the stroke opened (left a boundary edge on) if it was closed before (undo).
    undo: Vec<(Mark, usize, usize, Option<u32>)>,
    /// Finds where a stroke starts without a pass over the mesh ([`super::locate`]).
    pub(crate) locator: Locator,
    /// Whether each input component (see [`Locator`]) is closed now.
    pub(crate) closed_components: Vec<bool>,
    /// Every cut segment so far (rest pose), in cutting order.
    pub(crate) segments: Vec<CutSegment>,
    /// Vertices the opening must not move (groove bottoms).
    pub(crate) fixed: Vec<u32>,
    /// The tool samples of the committed steps, for the opening ([`super::drawn`]).
    pub(crate) drawn: Vec<super::sample::Sample>,
    clock: f64,
    scratch: Vec<u32>,
    /// Why the last refused step was refused (a short phrase; statistics only, see
    /// [`Scalpel::last_refusal`]). Set at the refusal sites, read after a step failed.
    reason: &'static str,
}

impl Scalpel {
    /// Starts cutting `mesh`.
    pub fn new(mesh: &csg::Mesh, options: ScalpelOptions) -> Result<Scalpel, ScalpelError> {
        if !(options.depth >= 0.0 && options.depth.is_finite()) {
            return Err(ScalpelError::BadOptions(format!(
                "depth {} must be >= 0",
                options.depth
            )));
        }
        for (name, v) in [
            ("snap_edge", options.snap_edge),
            ("groove_snap_edge", options.groove_snap_edge),
            ("snap_end", options.snap_end),
        ] {
            if !(0.0..0.5).contains(&v) {
                return Err(ScalpelError::BadOptions(format!(
                    "{name} {v} must be in [0, 0.5)"
                )));
            }
        }
        if mesh.triangles.is_empty() {
            return Err(ScalpelError::EmptyMesh);
        }
        let tolerance = options
            .max_surface_distance
            .unwrap_or(options.depth + 0.05 * mesh.bbox().diagonal());
        let mut dyn_mesh = DynMesh::from_mesh(mesh);
        let locator = Locator::build(mesh, &dyn_mesh);
        // Room for the cuts of a session, so that no step pays for growing the arrays
        // (notes/scalpel.md §2: one reallocation of a 2M-element array costs 26–37 ms).
        dyn_mesh.reserve(RESERVED_TRIANGLES.max(mesh.triangles.len() / 16));
        Ok(Scalpel {
            closed_components: locator.closed_input(),
            locator,
            mesh: dyn_mesh,
            options,
            tolerance,
            stroke: None,
            undo: Vec::new(),
            segments: Vec::new(),
            fixed: Vec::new(),
            drawn: Vec::new(),
            clock: 0.0,
            scratch: Vec::new(),
            reason: "",
        })
    }

    /// The mesh being cut.
    pub fn dyn_mesh(&self) -> &DynMesh {
        &self.mesh
    }

    /// The mesh in its rest pose (no opening).
    pub fn mesh(&self) -> csg::Mesh {
        self.mesh.to_mesh()
    }

    pub fn options(&self) -> &ScalpelOptions {
        &self.options
    }

    /// Changes the blade for the next stroke.
    pub fn set_options(&mut self, options: ScalpelOptions) {
        self.options = options;
    }

    /// Reserves room for `triangles` more triangles (no reallocation inside steps).
    pub fn reserve(&mut self, triangles: usize) {
        self.mesh.reserve(triangles);
    }

    /// Tool clock in seconds ([`SAMPLE_PERIOD`] per sample).
    pub fn clock(&self) -> f64 {
        self.clock
    }

    /// Advances the tool clock without cutting (the opening keeps progressing).
    pub fn advance_clock(&mut self, seconds: f64) {
        self.clock += seconds.max(0.0);
    }

    /// Cut segments so far.
    pub fn segments(&self) -> &[CutSegment] {
        &self.segments
    }

    /// True while a stroke is in progress.
    pub fn in_stroke(&self) -> bool {
        self.stroke.is_some()
    }

    /// Starts a stroke at `q` (ends a stroke in progress first). Error (nothing changed) when
    /// `q` is off the mesh.
    pub fn begin_stroke(&mut self, q: DVec3) -> Result<StepReport, ScalpelError> {
        if self.stroke.is_some() {
            self.end_stroke()?;
        }
        self.stroke = Some(Stroke {
            mark: self.mesh.mark(),
            records: (self.segments.len(), self.fixed.len()),
            triangles_before: self.mesh.triangle_count(),
            cut: None,
            tip: None,
            tip_q: None,
            touched: false,
            merged: false,
            crossed: 0,
            first_start: None,
            closed: false,
            far: None,
            thickness: 0.0,
            last_end: None,
            surface_closed: false,
            component: None,
        });
        let segments = self.segments.len();
        let fixed = self.fixed.len();
        match self.step(q) {
            Ok(r) => Ok(r),
            Err(e) => {
                if let Some(s) = self.stroke.take() {
                    self.mesh.rollback(s.mark);
                }
                self.segments.truncate(segments);
                self.fixed.truncate(fixed);
                Err(e)
            }
        }
    }

    /// Moves the tool to `q`: cuts from the last cut point toward it. Atomic.
    pub fn step(&mut self, q: DVec3) -> Result<StepReport, ScalpelError> {
        if !q.is_finite() {
            return Err(ScalpelError::NonFinite {
                point: q.to_array(),
            });
        }
        let mut stroke = self.stroke.take().ok_or(ScalpelError::NoStroke)?;
        self.clock += SAMPLE_PERIOD;
        self.reason = "";
        self.undo_tip(&mut stroke);
        let mark = self.mesh.mark();
        let saved = stroke.clone();
        let (segments, fixed) = (self.segments.len(), self.fixed.len());
        let result = self.advance(&mut stroke, q).and_then(|report| {
            let touched = self.mesh.touched_since(mark);
            if self.mesh.local_check(&touched, stroke.closed) {
                Ok(report)
            } else {
                self.reason = "local check";
                Err(ScalpelError::WalkFailed {
                    point: q.to_array(),
                })
            }
        });
        match result {
            Ok(report) => {
                self.stroke = Some(stroke);
                self.drawn
                    .push(super::sample::Sample::new(self.undo.len(), self.clock, q));
                Ok(report)
            }
            Err(e) => {
                if self.reason.is_empty() {
                    self.reason = match e {
                        ScalpelError::OffMesh { .. } => "off the mesh",
                        ScalpelError::NonManifold { .. } => "non-manifold",
                        _ => "walk failed (other)",
                    };
                }
                self.mesh.rollback(mark);
                self.segments.truncate(segments);
                self.fixed.truncate(fixed);
                stroke = saved;
                if let Some(pq) = stroke.tip_q {
                    // Deterministic: the same walk from the same anchor places the same tip.
                    let _ = self.place_tip(&mut stroke, pq);
                }
                let unstarted = |c: &Option<Cut>| c.as_ref().is_some_and(|c| c.path.len() == 1);
                if self.reason == SLOT_BLOCKED
                    && stroke.far.is_some()
                    && (stroke.tip.is_some() || (unstarted(&stroke.cut) && unstarted(&stroke.far)))
                {
                    // A slot reaching another cut or a boundary cannot open into it (its end there
                    // would not close): it ends at its last tip, made permanent as at the end of
                    // a stroke (or, not started yet, is given up), and the stroke starts a new
                    // slot past the other cut (`start_cut`, once the blade is off that cut's lips).
                    stroke.crossed += stroke.tip.take().map_or(0, |t| t.crossed);
                    stroke.last_end = stroke.cut.as_ref().map(|c| c.anchor);
                    stroke.cut = None;
                    stroke.far = None;
                    stroke.tip_q = None;
                    stroke.merged = true;
                    self.stroke = Some(stroke);
                    return Ok(StepReport {
                        triangles_crossed: 0,
                        on_mesh: false,
                    });
                }
                self.stroke = Some(stroke);
                Err(e)
            }
        }
    }

    /// Ends the stroke: the tip becomes permanent; a loop is closed back to its start.
    pub fn end_stroke(&mut self) -> Result<StrokeReport, ScalpelError> {
        let mut stroke = self.stroke.take().ok_or(ScalpelError::NoStroke)?;
        let mut detached = Vec::new();
        if self.options.tool == Tool::Loop {
            let saved = stroke.clone();
            let mark = self.mesh.mark();
            let segments = self.segments.len();
            self.undo_tip(&mut stroke);
            match self.close_loop(&mut stroke) {
                Ok(pieces) => detached = pieces,
                Err(e) => {
                    // Keep the stroke as it was (open): roll back the closing attempt only.
                    self.mesh.rollback(mark);
                    self.segments.truncate(segments);
                    self.stroke = Some(saved);
                    return Err(e);
                }
            }
        } else {
            if let Some(tip) = stroke.tip.take() {
                stroke.crossed += tip.crossed;
            }
            self.settle_tip(&stroke);
        }
        if let Some(g) = stroke.cut.as_ref().and_then(|c| c.groove.as_ref()) {
            self.fixed.extend_from_slice(&g.bottom_vertices);
        }
        // A stroke that left a boundary edge on a closed component opened it (only the
        // triangles it touched can have one: cost proportional to the stroke).
        let opened = stroke.component.filter(|&c| {
            self.closed_components.get(c as usize) == Some(&true)
                && self
                    .mesh
                    .touched_since(stroke.mark)
                    .iter()
                    .any(|&t| (0..3).any(|k| !is_real(self.mesh.twin(3 * t + k))))
        });
        if let Some(c) = opened {
            self.closed_components[c as usize] = false;
        }
        self.undo
            .push((stroke.mark, stroke.records.0, stroke.records.1, opened));
        Ok(StrokeReport {
            triangles_cut: stroke.crossed,
            triangles_created: self
                .mesh
                .triangle_count()
                .saturating_sub(stroke.triangles_before),
            detached,
        })
    }

    /// One whole stroke through `samples` (begin, a step per sample, end): the strokes the
    /// window and the command line replay without a tool in between (the layers below a
    /// stroke). Atomic: the first refused sample is the error, with the stroke undone.
    pub fn cut_stroke(&mut self, samples: &[DVec3]) -> Result<StrokeReport, ScalpelError> {
        let Some((&first, rest)) = samples.split_first() else {
            return Err(ScalpelError::NoStroke);
        };
        let result = self.begin_stroke(first).and_then(|_| {
            for &q in rest {
                self.step(q)?;
            }
            self.end_stroke()
        });
        if result.is_err() && self.stroke.is_some() {
            self.undo_stroke();
        }
        result
    }

    /// Undoes the last committed stroke (or the one in progress). Returns false when there is
    /// nothing to undo.
    pub fn undo_stroke(&mut self) -> bool {
        let (mark, segments, fixed, opened) = match self.stroke.take() {
            Some(s) => (s.mark, s.records.0, s.records.1, None),
            None => match self.undo.pop() {
                Some(u) => u,
                None => return false,
            },
        };
        if let Some(c) = opened {
            self.closed_components[c as usize] = true;
        }
        self.mesh.rollback(mark);
        self.segments.truncate(segments);
        self.fixed.truncate(fixed);
        self.drawn.retain(|d| d.stroke < self.undo.len());
        true
    }

    fn undo_tip(&mut self, stroke: &mut Stroke) {
        if let Some(tip) = stroke.tip.take() {
            self.mesh.rollback(tip.mark);
            self.segments.truncate(tip.segments);
            if let Some(cut) = stroke.cut.as_mut()
                && let (Some(g), Some(b)) = (cut.groove.as_mut(), tip.groove)
            {
                g.restore(b);
            }
        }
    }

    fn advance(&mut self, stroke: &mut Stroke, q: DVec3) -> Result<StepReport, ScalpelError> {
        stroke.tip_q = None;
        if stroke.cut.is_none() {
            return self.start_cut(stroke, q);
        }
        let before = stroke.crossed;
        let end = {
            let mut cut = stroke.cut.take().ok_or(ScalpelError::NoStroke)?;
            let snap = self.end_snap(stroke);
            let r = self.walk(&mut cut, q, None, &mut stroke.crossed, snap);
            stroke.cut = Some(cut);
            r?
        };
        let stuck = matches!(end, WalkEnd::Reached(End::AtVertex))
            && stroke.far.is_none()
            && stroke.cut.as_ref().is_some_and(|c| self.stuck(c.anchor, q));
        match end {
            WalkEnd::Reached(_) if stuck => {
                // The cut cannot leave its anchor toward the sample (a trench's lip or another
                // cut is in the way and it cannot cross there) while the blade has moved on
                // over the surface: the cut ends where it is and starts again under the blade
                // (at the next sample, once off the other cut's lips), instead of refusing
                // every later step of the stroke.
                self.finish_cut(stroke)?;
                stroke.merged = true;
            }
            WalkEnd::Reached(end) => {
                let tip = self.place_tips(stroke, end, q)?;
                let d = self.mesh.pos(tip).distance(q);
                if d > self.tolerance {
                    return Err(ScalpelError::OffMesh {
                        point: q.to_array(),
                        distance: d,
                        tolerance: self.tolerance,
                    });
                }
                stroke.tip_q = Some(q);
            }
            WalkEnd::Blocked { .. } if stroke.far.is_some() => {
                // A slot cannot open into another cut or a boundary (its end there would not
                // close): this step is undone and the slot ends at its last tip (see `step`).
                self.reason = SLOT_BLOCKED;
                return Err(ScalpelError::WalkFailed {
                    point: q.to_array(),
                });
            }
            WalkEnd::Blocked { merged } => {
                self.finish_cut(stroke)?;
                stroke.merged |= merged;
            }
            WalkEnd::Closed => {}
        }
        let tip_crossed = stroke.tip.as_ref().map_or(0, |t| t.crossed);
        Ok(StepReport {
            triangles_crossed: stroke.crossed - before + tip_crossed,
            on_mesh: stroke.cut.is_some(),
        })
    }

    /// Whether a cut whose walk toward `q` cannot leave anchor `v` is stuck rather than
    /// waiting: `q` is farther than [`STUCK_REACH`] of `v`'s longest surface edges (or than the
    /// off-mesh tolerance) from `v`, and
    /// on the surface (within the off-mesh tolerance of a triangle near `v`).
    fn stuck(&mut self, v: u32, q: DVec3) -> bool {
        let pv = self.mesh.pos(v);
        self.mesh.surface_fan_into(v, &mut self.scratch);
        let longest = self
            .scratch
            .iter()
            .map(|&h| self.mesh.longest_edge(h / 3))
            .fold(0.0, f64::max);
        // Beyond the off-mesh tolerance the tip could not be placed at all (the step would be
        // refused although the blade is on the surface), so that is "stuck" too, however long
        // the edges around `v` are (a lip of an opened trench has long floor edges beside it).
        let reach = (STUCK_REACH * longest).min(self.tolerance);
        pv.distance(q) > reach
            && closest_face_near(&self.mesh, v, q, RESTART_SEARCH)
                .is_some_and(|(_, _, d)| d <= self.tolerance)
    }

    /// Walks toward `q` and places the temporary tip (used to redo a tip after a failed step).
    fn place_tip(&mut self, stroke: &mut Stroke, q: DVec3) -> Result<(), ScalpelError> {
        let Some(mut cut) = stroke.cut.take() else {
            return Ok(());
        };
        let snap = self.end_snap(stroke);
        let r = self.walk(&mut cut, q, None, &mut stroke.crossed, snap);
        stroke.cut = Some(cut);
        if let WalkEnd::Reached(end) = r? {
            self.place_tips(stroke, end, q)?;
            stroke.tip_q = Some(q);
        }
        Ok(())
    }

    /// Why the last refused step was refused: a short phrase naming the refusal site (for
    /// statistics such as [`super::survey`]; empty before any refusal). Not part of the error:
    /// the error says what the user can do, this says which case the code does not handle.
    #[doc(hidden)]
    pub fn last_refusal(&self) -> &'static str {
        if self.reason.is_empty() {
            "unknown"
        } else {
            self.reason
        }
    }

    /// Internal: the start vertex of the stroke's current cut (tests).
    #[doc(hidden)]
    pub fn current_anchor(&self) -> Option<u32> {
        self.stroke.as_ref()?.cut.as_ref().map(|c| c.anchor)
    }

    /// Internal: the current cut's start vertex (tests).
    #[doc(hidden)]
    pub fn current_start(&self) -> Option<u32> {
        self.stroke.as_ref()?.cut.as_ref().map(|c| c.start)
    }

    pub(crate) fn merge_angle_deg(&self) -> f64 {
        self.options.merge_angle_deg
    }

    /// How straight the cut can leave `v` toward `q`: the cosine between `q - v` and the best
    /// exit of `v`'s surface fan; `None` when there is no exit.
    pub(crate) fn exit_cos(&mut self, v: u32, q: DVec3) -> Option<f64> {
        let n = self.mesh.surface_normal(v, &mut self.scratch);
        let pv = self.mesh.pos(v);
        let d = q - pv;
        let y = match self.find_exit(v, q, n, false) {
            Exit::Edge { y, .. } => y,
            Exit::Vertex { b, .. } => self.mesh.pos(b),
            _ => return None,
        };
        let l = (y - pv).length() * d.length();
        Some(if l > 0.0 { (y - pv).dot(d) / l } else { 0.0 })
    }
}

/// The floor vertices joined to `v` by an edge (`v` is on those trenches' lips).
fn floors_joined(mesh: &DynMesh, v: u32) -> Vec<u32> {
    let mut fan = Vec::new();
    mesh.fan_into(v, &mut fan);
    let mut out = Vec::new();
    for &h in &fan {
        for f in [mesh.dest(h), mesh.origin(prev(h))] {
            if mesh.is_floor(f) && !out.contains(&f) {
                out.push(f);
            }
        }
    }
    out
}

/// Whether `x` is joined by a wall edge to one of `floors` (on those trenches' lips).
fn on_trenches(mesh: &DynMesh, floors: &[u32], x: u32) -> bool {
    floors
        .iter()
        .any(|&f| super::groove::wall_edge(mesh, x, f).is_some())
}

/// The floor vertex of wall triangle `t` (the first one; `None` for a triangle without one).
fn wall_floor(mesh: &DynMesh, t: u32) -> Option<u32> {
    mesh.triangles[t as usize]
        .into_iter()
        .find(|&v| mesh.is_floor(v))
}

/// Whether surface half-edge `h` runs along a groove's lip (its twin is a wall triangle).
fn against_wall(mesh: &DynMesh, h: u32) -> bool {
    let g = mesh.twin(h);
    is_real(g) && mesh.is_wall(g / 3) && !mesh.is_wall(h / 3)
}

/// How far past edge `b c` (away from `v`, across the edge in the triangle's plane) a sample
/// must be before a groove splits that edge for good, relative to the edge's length.
const COMMIT_BEYOND: f64 = 0.25;

/// Whether `q` lies more than [`COMMIT_BEYOND`] edge lengths past edge `b c` of triangle
/// `v b c`.
fn clearly_beyond(pv: DVec3, pb: DVec3, pc: DVec3, q: DVec3) -> bool {
    let e = pc - pb;
    let n = e.cross(pv - pb);
    let out = n.cross(e).normalize_or_zero();
    // `out` points from the edge away from `v`.
    let out = if out.dot(pv - pb) > 0.0 { -out } else { out };
    (q - pb).dot(out) > COMMIT_BEYOND * e.length()
}

/// Parameter of the point of segment `a b` closest to `q` (unclamped).
fn foot(a: DVec3, b: DVec3, q: DVec3) -> f64 {
    let ab = b - a;
    let l = ab.length_squared();
    if l == 0.0 { 0.0 } else { (q - a).dot(ab) / l }
}
