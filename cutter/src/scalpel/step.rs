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

use glam::DVec3;

use super::cut_point::{
    CutPoint, classify, classify_on_edges, closest_face, closest_face_near, side,
};
use super::dyn_mesh::{DynMesh, Mark, NO_TWIN, NONMANIFOLD, is_real, next, prev};
use super::groove::{Groove, GrooveBackup};
use super::{ScalpelError, ScalpelOptions, Tool};

/// Seconds between two tool samples (the tool clock the opening's time window runs on).
pub const SAMPLE_PERIOD: f64 = 1.0 / 60.0;

/// Tip snapping radius of both slits of a through-cut (see `Scalpel::end_snap`).
const THROUGH_SNAP_END: f64 = 0.02;

/// At most this many triangles examined when a cut restarts inside a stroke (see
/// `Scalpel::start_cut`).
pub const RESTART_SEARCH: usize = 4096;

/// A cut that cannot leave its anchor is stuck (see `Scalpel::stuck`) once the blade is this
/// many of the anchor's longest surface edges away.
const STUCK_REACH: f64 = 2.0;

/// Edge snapping of a groove whose floor is due for a new vertex (see `walk`): every crossing
/// not blocked from it goes through the nearer end of its edge.
const FLOOR_DUE_SNAP: f64 = 0.5;

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
}

/// A scalpel working on one mesh.
#[derive(Clone, Debug)]
pub struct Scalpel {
    pub(crate) mesh: DynMesh,
    options: ScalpelOptions,
    tolerance: f64,
    stroke: Option<Stroke>,
    /// Mesh state, segment count and fixed-vertex count before each committed stroke (undo).
    undo: Vec<(Mark, usize, usize)>,
    /// Every cut segment so far (rest pose), in cutting order.
    pub(crate) segments: Vec<CutSegment>,
    /// Vertices the opening must not move (groove bottoms).
    pub(crate) fixed: Vec<u32>,
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
        Ok(Scalpel {
            mesh: DynMesh::from_mesh(mesh),
            options,
            tolerance,
            stroke: None,
            undo: Vec::new(),
            segments: Vec::new(),
            fixed: Vec::new(),
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
        } else if let Some(tip) = stroke.tip.take() {
            stroke.crossed += tip.crossed;
        }
        if let Some(g) = stroke.cut.as_ref().and_then(|c| c.groove.as_ref()) {
            self.fixed.extend_from_slice(&g.bottom_vertices);
        }
        self.undo
            .push((stroke.mark, stroke.records.0, stroke.records.1));
        Ok(StrokeReport {
            triangles_cut: stroke.crossed,
            triangles_created: self
                .mesh
                .triangle_count()
                .saturating_sub(stroke.triangles_before),
            detached,
        })
    }

    /// Undoes the last committed stroke (or the one in progress). Returns false when there is
    /// nothing to undo.
    pub fn undo_stroke(&mut self) -> bool {
        let (mark, segments, fixed) = match self.stroke.take() {
            Some(s) => (s.mark, s.records.0, s.records.1),
            None => match self.undo.pop() {
                Some(u) => u,
                None => return false,
            },
        };
        self.mesh.rollback(mark);
        self.segments.truncate(segments);
        self.fixed.truncate(fixed);
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

    /// Starts a cut at the surface point nearest `q`. Where the stroke starts this is a global
    /// search (linear scans for the nearest face, whether the surface is closed and, for a
    /// groove, the through-cut ray: `begin_stroke` costs O(mesh)); where a cut restarts inside
    /// the stroke (after merging into another cut) the nearest face is searched outward from
    /// where the last cut ended ([`closest_face_near`], at most [`RESTART_SEARCH`] triangles),
    /// and the stroke keeps its surface's closedness and its kind (a groove restarts as a
    /// groove): no step scans the mesh.
    fn start_cut(&mut self, stroke: &mut Stroke, q: DVec3) -> Result<StepReport, ScalpelError> {
        let restart = stroke.touched.then_some(stroke.last_end).flatten();
        let found = match restart {
            Some(v) => closest_face_near(&self.mesh, v, q, RESTART_SEARCH),
            None if stroke.touched => None,
            None => closest_face(&self.mesh, q),
        };
        let (t, bary, dist) = match found {
            Some(f) => f,
            None if stroke.touched => return Ok(StepReport::default()),
            None => return Err(ScalpelError::EmptyMesh),
        };
        if dist > self.tolerance {
            if stroke.touched {
                // The blade left the mesh earlier in this stroke: moving in the air.
                return Ok(StepReport::default());
            }
            return Err(ScalpelError::OffMesh {
                point: q.to_array(),
                distance: dist,
                tolerance: self.tolerance,
            });
        }
        if !stroke.touched {
            stroke.surface_closed = self.component_closed(t);
        }
        let groove_mode =
            self.options.depth > 0.0 && self.options.tool == Tool::Scalpel && stroke.surface_closed;
        let cp = if groove_mode {
            // A groove never starts inside a face (a face split, the crossing out of it and the
            // walls would be 5 new triangles in one): it starts on the nearest edge.
            classify_on_edges(&self.mesh, t, bary, self.options.snap_end)
        } else {
            classify(&self.mesh, t, bary, self.options.snap_end)
        };
        if stroke.merged {
            // After merging into an existing slit, stay merged while the blade is on its lips.
            let tri = self.mesh.triangles[t as usize];
            if tri.iter().any(|&v| !self.mesh.copies(v).is_empty()) {
                return Ok(StepReport::default());
            }
        }
        let (v, start_split) = match cp {
            CutPoint::Vertex(v) => (v, 0),
            CutPoint::Edge { h, point } => (self.split_edge_with_mate(h, point)?, 1),
            CutPoint::Face { t, point } => (self.mesh.split_face(t, point), 2),
        };
        if self.mesh.singular[v as usize] {
            return Err(self.nonmanifold(v));
        }
        let mut groove = groove_mode.then(|| Groove::new(self.options.depth, v, start_split));
        stroke.far = None;
        let through = if !groove_mode {
            None
        } else if !stroke.touched {
            self.through_start(v, None)?
        } else if stroke.thickness > 0.0 {
            // A slot restarting past another cut: its far side is searched near here.
            self.through_start(v, Some(stroke.thickness))?
        } else {
            None
        };
        if let Some((far, thickness)) = through {
            // Deeper than the structure is thick: a slot through it instead of a groove.
            groove = None;
            stroke.far = Some(Cut {
                start: far,
                anchor: far,
                path: vec![far],
                groove: None,
                through: true,
                split_edge: None,
            });
            stroke.thickness = thickness;
        }
        stroke.cut = Some(Cut {
            through: stroke.far.is_some(),
            split_edge: None,
            start: v,
            anchor: v,
            path: vec![v],
            groove,
        });
        stroke.touched = true;
        stroke.closed = groove_mode;
        stroke.first_start.get_or_insert(v);
        Ok(StepReport {
            triangles_crossed: 1,
            on_mesh: true,
        })
    }

    /// Whether the connected surface of triangle `t` is closed (no boundary edge reachable).
    fn component_closed(&self, t: u32) -> bool {
        let mut seen = vec![false; self.mesh.triangle_count()];
        let mut stack = vec![t];
        seen[t as usize] = true;
        while let Some(t) = stack.pop() {
            for k in 0..3 {
                let g = self.mesh.twin(3 * t + k);
                if !is_real(g) {
                    return false;
                }
                let u = (g / 3) as usize;
                if !seen[u] {
                    seen[u] = true;
                    stack.push(u as u32);
                }
            }
        }
        true
    }

    fn nonmanifold(&self, v: u32) -> ScalpelError {
        ScalpelError::NonManifold {
            point: self.mesh.pos(v).to_array(),
        }
    }

    /// Splits the edge of `h` at `p`; a slit lip's coincident mate edge is split at the same
    /// point, so that the two lips stay vertex-for-vertex mates (no T-junction).
    pub(crate) fn split_edge_with_mate(&mut self, h: u32, p: DVec3) -> Result<u32, ScalpelError> {
        let g = self.mesh.twin(h);
        if g == NONMANIFOLD {
            return Err(ScalpelError::NonManifold {
                point: p.to_array(),
            });
        }
        let mate = if g == NO_TWIN {
            super::cross::find_mate(&self.mesh, h, &mut self.scratch)
        } else if against_wall(&self.mesh, h) {
            // A groove's lip: split the coincident edge of the other lip too, so that a crossing
            // finds its way on at the same point.
            super::cross::find_groove_mate(&self.mesh, h, &mut self.scratch)
        } else {
            None
        };
        let x = self.mesh.split_edge(h, p);
        if let Some(m) = mate {
            let x2 = self.mesh.split_edge(m, p);
            self.mesh.join_copies(x, x2);
        }
        Ok(x)
    }

    /// Opens the edge between `v` and `x` (a slit) unless it is open already.
    fn open_between(&mut self, v: u32, x: u32) -> Result<(), ScalpelError> {
        let h =
            self.mesh
                .edge_between(v, x, &mut self.scratch)
                .ok_or(ScalpelError::WalkFailed {
                    point: self.mesh.pos(x).to_array(),
                })?;
        let g = self.mesh.twin(h);
        if g == NONMANIFOLD {
            return Err(self.nonmanifold(v));
        }
        if is_real(g) && (self.mesh.is_wall(g / 3) || self.mesh.is_wall(h / 3)) {
            // Opening a lip against its wall would tear the groove open.
            self.reason = "lip against a groove wall";
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(x).to_array(),
            });
        }
        if self.mesh.singular[v as usize] {
            return Err(self.nonmanifold(v));
        }
        if self.mesh.singular[x as usize] {
            return Err(self.nonmanifold(x));
        }
        if is_real(g) {
            let mut created = Vec::new();
            self.mesh.open_edge(h, &mut created);
        }
        Ok(())
    }

    fn record_segment(&mut self, a: u32, b: u32, normal: DVec3) {
        self.segments.push(CutSegment {
            a,
            b,
            pa: self.mesh.pos(a),
            pb: self.mesh.pos(b),
            normal,
            time: self.clock,
        });
    }

    /// Permanent move of the cut from the anchor `v` to its neighbour `x`, which the cut made
    /// by splitting the edge `split_edge` (`None`: a vertex it goes through; see
    /// [`Groove::split`]).
    fn move_to(
        &mut self,
        cut: &mut Cut,
        v: u32,
        x: u32,
        split_edge: Option<(u32, u32)>,
    ) -> Result<(), ScalpelError> {
        let n = self.mesh.surface_normal(v, &mut self.scratch);
        cut.split_edge = split_edge;
        if let Some(g) = cut.groove.as_mut() {
            let k = cut.path.len() - 1;
            g.set_split(k + 1, u8::from(split_edge.is_some()));
            if k >= 1 {
                let pv = self.mesh.pos(v);
                let prev = self.mesh.pos(cut.path[k - 1]);
                g.make_bottom(&mut self.mesh, k, pv, prev, n);
            }
        }
        self.open_between(v, x)?;
        cut.path.push(x);
        cut.anchor = x;
        self.record_segment(v, x, n);
        if let Some(g) = cut.groove.as_mut() {
            let upto = cut.path.len() - 2;
            if !g.build_walls(&mut self.mesh, &cut.path, upto) {
                self.reason = "groove walls (permanent)";
                return Err(ScalpelError::WalkFailed {
                    point: self.mesh.pos(x).to_array(),
                });
            }
        }
        Ok(())
    }

    /// Exit of the cut from `v`'s fan toward `q` (see the module doc).
    /// With `no_retrace`, never along a slit's lip (a groove's own cut must not double back
    /// along its open slit).
    fn find_exit(&mut self, v: u32, q: DVec3, n: DVec3, no_retrace: bool) -> Exit {
        let mesh = &self.mesh;
        let pv = mesh.pos(v);
        let d = q - pv;
        let dl = d.length();
        if dl == 0.0 || n == DVec3::ZERO {
            return Exit::Degenerate;
        }
        let m = d.cross(n);
        if m.length() <= 1e-9 * dl {
            return Exit::Degenerate;
        }
        let w = pv + n * dl;
        mesh.surface_fan_into(v, &mut self.scratch);
        if self.scratch.is_empty() {
            return Exit::Blocked;
        }
        let cos = |x: DVec3| {
            let l = x.length() * dl;
            if l > 0.0 { x.dot(d) / l } else { -1.0 }
        };
        let mut best = Exit::Blocked;
        let mut best_cos = 1e-9;
        for &h0 in self.scratch.iter() {
            let b = mesh.dest(h0);
            let c = mesh.origin(prev(h0));
            let (pb, pc) = (mesh.pos(b), mesh.pos(c));
            let sb = side(pv, q, w, pb);
            let sc = side(pv, q, w, pc);
            for (x, px, sx, e) in [(b, pb, sb, h0), (c, pc, sc, prev(h0))] {
                // Never along a groove's lip: its other side is the wall, not a slit.
                if sx == 0 && !against_wall(mesh, e) && !(no_retrace && mesh.twin(e) == NO_TWIN) {
                    let cs = cos(px - pv);
                    if cs > best_cos {
                        best_cos = cs;
                        best = Exit::Vertex { e, b: x };
                    }
                }
            }
            if sb != 0 && sc != 0 && sb != sc {
                let (fb, fc) = (m.dot(pb - pv), m.dot(pc - pv));
                let t = if fb != fc {
                    (fb / (fb - fc)).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                let y = pb.lerp(pc, t);
                let cs = cos(y - pv);
                if cs > best_cos {
                    best_cos = cs;
                    best = Exit::Edge { h0, t, y };
                }
            }
        }
        best
    }

    /// Walks the cut from its anchor toward `q`, cutting permanently every crossing before the
    /// foot of `q`. With `close_to`, stops as soon as that vertex is a neighbour (closing a loop).
    fn walk(
        &mut self,
        cut: &mut Cut,
        q: DVec3,
        close_to: Option<u32>,
        crossed: &mut usize,
        tau_end: f64,
    ) -> Result<WalkEnd, ScalpelError> {
        let tau0 = if cut.groove.is_some() {
            self.options.groove_snap_edge
        } else {
            self.options.snap_edge
        };
        for _ in 0..MAX_CROSSINGS {
            let v = cut.anchor;
            // A groove whose floor is due for a new vertex where the anchor split an edge (no
            // room for the floor triangles there, see `Groove::make_bottom`) snaps its next
            // crossing to the nearer vertex, where the floor can change.
            let k = cut.path.len() - 1;
            let tau = match cut.groove.as_ref() {
                Some(g)
                    if k >= 1
                        && g.split.get(k).is_some_and(|&x| x > 0)
                        && g.floor_due(k, self.mesh.pos(v), self.mesh.pos(cut.path[k - 1])) =>
                {
                    FLOOR_DUE_SNAP
                }
                _ => tau0,
            };
            if let Some(s) = close_to {
                if self.mesh.same_point(v, s) {
                    return Ok(WalkEnd::Closed);
                }
                if self.mesh.edge_between(v, s, &mut self.scratch).is_some() {
                    self.move_to(cut, v, s, None)?;
                    *crossed += 1;
                    return Ok(WalkEnd::Closed);
                }
            }
            let n = self.mesh.surface_normal(v, &mut self.scratch);
            let pv = self.mesh.pos(v);
            let h = self.mesh.vert_he[v as usize];
            if is_real(h) && pv.distance(q) <= 1e-9 * self.mesh.longest_edge(h / 3) {
                // The sample is on the anchor (a through-cut's far side found exactly under
                // the sample at a vertex): nothing to cut, no direction to find an exit in.
                return Ok(WalkEnd::Reached(End::AtVertex));
            }
            let forward = |p: DVec3| (p - pv).dot(q - pv) > 0.0;
            // A groove still at its start, on a trench's lip: the floor vertices there.
            let start_floors = match cut.groove.as_ref() {
                Some(g) if k == 0 => {
                    let mut f = floors_joined(&self.mesh, v);
                    if g.junctions.contains(&0) {
                        f.extend(g.bottoms.first().copied());
                    }
                    f
                }
                _ => Vec::new(),
            };

            match self.find_exit(v, q, n, cut.groove.is_some() || cut.through) {
                Exit::Degenerate => return Ok(WalkEnd::Reached(End::AtVertex)),
                Exit::Blocked => {
                    let back = cut.path[cut.path.len().saturating_sub(5)];
                    let dir = if back == v {
                        q - pv
                    } else {
                        q - self.mesh.pos(back)
                    };
                    if cut.groove.is_some() && cut.path.len() >= 2 {
                        let n = self.mesh.surface_normal(v, &mut self.scratch);
                        // Only a finished trench (not this groove's own walls still to come).
                        let unfinished = |f: u32| {
                            cut.groove.as_ref().is_some_and(|g| {
                                g.bottoms[g.walls_done.min(g.bottoms.len())..].contains(&f)
                            })
                        };
                        if let Some(floor) = super::groove::floor_under(&self.mesh, v, n)
                            && !unfinished(floor)
                        {
                            // A groove meeting a groove: open into its trench here, then go on
                            // from the other lip (crossing) or end here (merging). When the
                            // stroke crosses but the sample is not beyond the lip yet, the tip
                            // waits on the lip.
                            let mate = super::cross::crossing_mate(self, v, q, dir);
                            if mate.is_none() {
                                let angle = self.mesh.copies(v).first().map_or(0.0, |&c| {
                                    super::cross::angle_to_lip(&self.mesh, c, dir, &mut Vec::new())
                                });
                                if angle >= self.options.merge_angle_deg {
                                    return Ok(WalkEnd::Reached(End::AtVertex));
                                }
                            }
                            match self.join_trench(cut, v, floor, mate)? {
                                Some(_) => continue,
                                None => return Ok(WalkEnd::Blocked { merged: true }),
                            }
                        }
                    }
                    if cut.groove.is_none()
                        && !cut.through
                        && let Some(m) = super::cross::crossing_mate(self, v, q, dir)
                    {
                        cut.anchor = m;
                        cut.split_edge = None;
                        cut.path.push(m);
                        continue;
                    }
                    let merged = !self.mesh.copies(v).is_empty();
                    return Ok(WalkEnd::Blocked { merged });
                }
                Exit::Vertex { e, b } => {
                    if on_trenches(&self.mesh, &start_floors, b) {
                        // See the same case in `Exit::Edge` below.
                        return Ok(WalkEnd::Blocked { merged: true });
                    }
                    let pb = self.mesh.pos(b);
                    let s = foot(pv, pb, q);
                    if s <= 1.0 {
                        let end = if s < tau_end || (cut.groove.is_some() && s < 0.5) {
                            End::AtVertex
                        } else if s > 1.0 - tau_end || cut.groove.is_some() {
                            // A groove's tip is never in the middle of an edge from its anchor:
                            // that edge may lie inside the triangle the groove just crossed (two
                            // pieces more there). It goes to the nearer end.
                            End::OnVertex(b)
                        } else {
                            End::OnEdge {
                                h: e,
                                p: pv.lerp(pb, s),
                            }
                        };
                        return Ok(WalkEnd::Reached(end));
                    }
                    self.move_to(cut, v, b, None)?;
                    *crossed += 1;
                }
                Exit::Edge { h0, t, .. } => {
                    let b = self.mesh.dest(h0);
                    let c = self.mesh.origin(prev(h0));
                    let lip_floor = against_wall(&self.mesh, next(h0))
                        .then(|| wall_floor(&self.mesh, self.mesh.twin(next(h0)) / 3))
                        .flatten();
                    if lip_floor.is_some_and(|f| start_floors.contains(&f))
                        || (t < tau && on_trenches(&self.mesh, &start_floors, b))
                        || (t > 1.0 - tau && on_trenches(&self.mesh, &start_floors, c))
                    {
                        // Starting on a trench's lip (or just past a trench it crossed), the
                        // groove would reach a lip of the same trench again at once (the trench
                        // bends or ends there): its first segment would run from that trench's
                        // floor back to its lip, inside the trench's own walls. It ends here
                        // instead (merged), as it does meeting a trench at a small angle.
                        return Ok(WalkEnd::Blocked { merged: true });
                    }
                    let (pb, pc) = (self.mesh.pos(b), self.mesh.pos(c));
                    // Snapping to `b` (or `c`) cuts along the edge from `v`; never along a
                    // groove's lip (its other side is the wall): then cross the edge away
                    // from that end instead (no sliver either).
                    // A groove does not snap back onto the edge its anchor split: it would run
                    // along the triangle it just crossed, a wall more there (5 new in one).
                    let split_end = |x: u32| {
                        cut.groove.is_some()
                            && cut.split_edge.is_some_and(|(p, q)| {
                                self.mesh.same_point(x, p) || self.mesh.same_point(x, q)
                            })
                    };
                    let near_b = t < tau && !against_wall(&self.mesh, h0) && !split_end(b);
                    let near_c =
                        t > 1.0 - tau && !against_wall(&self.mesh, prev(h0)) && !split_end(c);
                    let t = if (t < tau && !near_b) || (t > 1.0 - tau && !near_c) {
                        t.clamp(tau, 1.0 - tau)
                    } else {
                        t
                    };
                    let y = pb.lerp(pc, t);
                    let mut s = foot(pv, y, q);
                    if s > 1.0
                        && cut.groove.is_some()
                        && !(near_b && forward(pb) || near_c && forward(pc))
                        && !clearly_beyond(pv, pb, pc, q)
                    {
                        // A groove splits an edge for good only once the sample is clearly past
                        // it: a path grazing the edge and turning back would otherwise cut the
                        // triangle it left a second time (more than 4 new triangles in one).
                        // Until then the tip waits on the edge.
                        s = 1.0;
                    }
                    if s <= 1.0 {
                        let end = if let Some(end) = cut.groove.is_some().then(|| {
                            // A groove's tip goes to the nearer of its anchor and where the cut
                            // leaves the triangle: never inside a face (a face split, the
                            // crossing and the tip's walls would be 5 new triangles in one), nor
                            // in the middle of an edge from the anchor (which may lie inside the
                            // triangle the groove just crossed: two pieces more there). At most
                            // half a triangle from the sample; the next sample moves it on.
                            if s < 0.5 {
                                End::AtVertex
                            } else if near_b {
                                if forward(pb) {
                                    End::OnVertex(b)
                                } else {
                                    End::AtVertex
                                }
                            } else if near_c {
                                if forward(pc) {
                                    End::OnVertex(c)
                                } else {
                                    End::AtVertex
                                }
                            } else {
                                End::OnEdge { h: next(h0), p: y }
                            }
                        }) {
                            end
                        } else if s < tau_end {
                            End::AtVertex
                        } else if s > 1.0 - tau_end {
                            if near_b {
                                End::OnVertex(b)
                            } else if near_c {
                                End::OnVertex(c)
                            } else {
                                End::OnEdge { h: next(h0), p: y }
                            }
                        } else if near_b {
                            End::OnEdge {
                                h: h0,
                                p: pv.lerp(pb, s),
                            }
                        } else if near_c {
                            End::OnEdge {
                                h: prev(h0),
                                p: pv.lerp(pc, s),
                            }
                        } else {
                            End::InFace {
                                t: h0 / 3,
                                p: pv.lerp(y, s),
                            }
                        };
                        return Ok(WalkEnd::Reached(end));
                    }
                    let (x, split_edge) = if near_b && forward(pb) {
                        (b, None)
                    } else if near_c && forward(pc) {
                        (c, None)
                    } else {
                        (self.split_edge_with_mate(next(h0), y)?, Some((b, c)))
                    };
                    self.move_to(cut, v, x, split_edge)?;
                    *crossed += 1;
                }
            }
        }
        self.reason = "walk did not converge";
        Err(ScalpelError::WalkFailed {
            point: q.to_array(),
        })
    }

    /// The groove of `cut` reached lip vertex `v` of an existing trench (floor vertex `floor`
    /// under `v`): its walls are completed into that trench (interactive cross cutting, Fig. 10:
    /// the grooves join at the floor; the deeper cut determines the floor at the crossing, so a
    /// shallower floor is lowered to this blade's depth). Then, with the lip copy `mate` on the
    /// far side (the stroke crosses: it meets the lip at the merge angle or more), the cut goes
    /// on from there, opening into the trench from that side too, and the new anchor is
    /// returned; without (the grooves merge) the cut ends (`None`).
    fn join_trench(
        &mut self,
        cut: &mut Cut,
        v: u32,
        floor: u32,
        mate: Option<u32>,
    ) -> Result<Option<u32>, ScalpelError> {
        let fail = |p: DVec3| ScalpelError::WalkFailed {
            point: p.to_array(),
        };
        let pv = self.mesh.pos(v);
        let n = self.mesh.surface_normal(v, &mut self.scratch);
        let depth = self.options.depth;
        let mut k = cut.path.len() - 1;
        if k == 1
            && cut
                .groove
                .as_ref()
                .is_some_and(|g| g.junctions.contains(&0))
        {
            // One segment from trench to trench (the groove crossed a trench and its first
            // segment reached the lip of another one, or of the same one where it bends): its
            // walls would lie in the old walls. Split the segment in the middle so that the
            // new vertex gets a floor of its own between the two junctions.
            let a = cut.path[0];
            let mid = self.split_lips(a, v)?;
            let pm = self.mesh.pos(mid);
            let nm = self.mesh.surface_normal(mid, &mut self.scratch);
            let pa = self.mesh.pos(a);
            cut.path.insert(1, mid);
            if let Some(g) = cut.groove.as_mut() {
                g.insert_split(1);
                g.make_bottom(&mut self.mesh, 1, pm, pa, nm);
            }
            k = 2;
        }
        let Some(g) = cut.groove.as_mut() else {
            self.reason = "joining a trench";
            return Err(fail(pv));
        };
        if k >= 2 && g.bottoms.first() == Some(&floor) && g.bottoms[1] == g.bottoms[k - 1] {
            // The groove crossed this trench and comes straight back into it at the same floor
            // vertex, its own floor shared all along: the last segment's walls would repeat the
            // first segment's floor edge. It ends on the lip instead (a crack tip there, its
            // walls closing at the tip), merged, even where the stroke would cross again: it
            // restarts past the trench (see `start_cut`).
            g.make_tip(k, v);
            if !g.build_walls(&mut self.mesh, &cut.path, k) || !g.is_closed() {
                self.reason = "ending on a trench's lip";
                return Err(fail(pv));
            }
            self.fixed.extend_from_slice(&g.bottom_vertices);
            cut.groove = None;
            return Ok(None);
        }
        if (pv - self.mesh.pos(floor)).dot(n) < depth && n != DVec3::ZERO {
            self.mesh.set_pos(floor, pv - n * depth);
        }
        g.set_junction(k, floor);
        if !g.build_walls(&mut self.mesh, &cut.path, k) {
            self.reason = "joining a trench: walls";
            return Err(fail(pv));
        }
        if !g.is_closed() {
            self.reason = "joining a trench: not closed";
            return Err(fail(pv));
        }
        self.fixed.extend_from_slice(&g.bottom_vertices);
        self.fixed.push(floor);
        let Some(m) = mate else {
            cut.groove = None;
            return Ok(None);
        };
        let nm = self.mesh.surface_normal(m, &mut self.scratch);
        let far_floor = super::groove::floor_under(&self.mesh, m, nm).ok_or_else(|| fail(pv))?;
        let mut groove = Groove::new(depth, m, 1);
        groove.set_junction(0, far_floor);
        cut.groove = Some(groove);
        cut.start = m;
        cut.anchor = m;
        cut.split_edge = None;
        cut.path = vec![m];
        Ok(Some(m))
    }

    /// Places the temporary tip at `end`; when cutting through, first moves the far cut on
    /// (permanently) under the sample `q`, then places its tip and the walls joining the two
    /// slits (temporary, with the tip).
    fn place_tips(&mut self, stroke: &mut Stroke, end: End, q: DVec3) -> Result<u32, ScalpelError> {
        let Some(mut far) = stroke.far.take() else {
            return self.insert_tip(stroke, end);
        };
        let fail = |p: DVec3| ScalpelError::WalkFailed {
            point: p.to_array(),
        };
        let anchor = stroke.cut.as_ref().map_or(far.anchor, |c| c.anchor);
        // The inward normal where the tip goes, interpolated from the vertex normals (not at the
        // anchor, and not a face normal: on a curved structure the far side would move against
        // the near one or jump with each face).
        let n = match end {
            End::InFace { t, p } => {
                let tri = self.mesh.triangles[t as usize];
                let [a, b, c] = tri.map(|v| self.mesh.pos(v));
                let w = super::cut_point::closest_on_triangle(p, a, b, c);
                let mut n = DVec3::ZERO;
                for (k, v) in tri.into_iter().enumerate() {
                    n += self.mesh.surface_normal(v, &mut self.scratch) * w[k];
                }
                n.normalize_or_zero()
            }
            End::OnEdge { h, p } => {
                let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
                let s = foot(self.mesh.pos(a), self.mesh.pos(b), p).clamp(0.0, 1.0);
                let na = self.mesh.surface_normal(a, &mut self.scratch);
                let nb = self.mesh.surface_normal(b, &mut self.scratch);
                na.lerp(nb, s).normalize_or_zero()
            }
            End::OnVertex(b) => self.mesh.surface_normal(b, &mut self.scratch),
            End::AtVertex => self.mesh.surface_normal(anchor, &mut self.scratch),
        };
        // The far side under the sample: where the ray from it along the inward normal leaves
        // the structure, searched near the far cut (the structure's thickness may change along
        // the stroke, by up to half from one sample to the next); where that is not found, the
        // thickness so far.
        let q_far = match super::through::ray_hit_near(
            &self.mesh,
            far.anchor,
            q,
            -n,
            stroke.thickness,
            FAR_SEARCH,
        ) {
            Some((_, _, s))
                if s < self.options.depth
                    && (s - stroke.thickness).abs() <= 0.5 * stroke.thickness =>
            {
                stroke.thickness = s;
                q - n * s
            }
            _ => q - n * stroke.thickness,
        };
        let mut crossed = 0;
        let r = self.walk(&mut far, q_far, None, &mut crossed, THROUGH_SNAP_END);
        let far_end = match r {
            Ok(WalkEnd::Reached(e)) => e,
            Ok(walk_end) => {
                stroke.far = Some(far);
                // The far cut has no way on from its anchor: it met another cut (a vertex of
                // that cut's slot, whose walls bound the fan) or a boundary. A slot cannot open
                // into it (see `step`): it ends at its last tip and starts again past it.
                self.reason = if matches!(walk_end, WalkEnd::Blocked { .. }) {
                    SLOT_BLOCKED
                } else {
                    "far cut did not reach its sample"
                };
                return Err(fail(q_far));
            }
            Err(e) => {
                stroke.far = Some(far);
                return Err(e);
            }
        };
        let x = match self.insert_tip(stroke, end) {
            Ok(x) => x,
            Err(e) => {
                stroke.far = Some(far);
                return Err(e);
            }
        };
        let result = self.far_tip(stroke, &far, far_end, x);
        stroke.far = Some(far);
        result?;
        Ok(x)
    }

    /// Snapping radius of the tip: the option's, except when cutting through, where both slits'
    /// tips follow the samples closely so that they advance together (a slot needs a segment on
    /// each side before its walls close).
    fn end_snap(&self, stroke: &Stroke) -> f64 {
        if stroke.far.is_some() {
            THROUGH_SNAP_END
        } else {
            self.options.snap_end
        }
    }

    /// The far cut's temporary tip and the walls of the whole slot (see [`super::through`]).
    fn far_tip(
        &mut self,
        stroke: &Stroke,
        far: &Cut,
        end: End,
        top_tip: u32,
    ) -> Result<(), ScalpelError> {
        let fv = far.anchor;
        let nf = self.mesh.surface_normal(fv, &mut self.scratch);
        let fx = match end {
            End::AtVertex => fv,
            End::OnVertex(b) => b,
            End::OnEdge { h, p } => self.split_edge_with_mate(h, p)?,
            End::InFace { t, p } => self.mesh.split_face(t, p),
        };
        if fx != fv {
            self.open_between(fv, fx)?;
            self.record_segment(fv, fx, nf);
        }
        let Some(cut) = stroke.cut.as_ref() else {
            return Err(ScalpelError::NoStroke);
        };
        let mut near = cut.path.clone();
        if top_tip != cut.anchor {
            near.push(top_tip);
        }
        let mut far_path = far.path.clone();
        if fx != fv {
            far_path.push(fx);
        }
        if (near.len() < 2) != (far_path.len() < 2) {
            // One side cut, the other not yet: no slot to close (the step is refused; the next
            // sample, farther on, cuts both).
            self.reason = "one side of the slot not cut yet";
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(fx).to_array(),
            });
        }
        // A slit of one edge runs from crack tip to crack tip: both its lips join the same two
        // vertices, so walls on both would use that edge four times. Split it in the middle.
        for path in [&mut near, &mut far_path] {
            if path.len() == 2 {
                let mid = self.split_lips(path[0], path[1])?;
                path.insert(1, mid);
            }
        }
        // Both tips on the end vertices of another slot (the blade ran onto that slot's end):
        // the edge between them is already that slot's end edge, and walls here would use it a
        // second time. That is the slot meeting another cut, not a failure of this one: it ends
        // at its last tip and restarts past the other cut (see `step`).
        let (near_end, far_end) = (near[near.len() - 1], far_path[far_path.len() - 1]);
        if self
            .mesh
            .edge_between(near_end, far_end, &mut self.scratch)
            .is_some()
        {
            self.reason = SLOT_BLOCKED;
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(fx).to_array(),
            });
        }
        if !super::through::build_walls(&mut self.mesh, &near, &far_path) {
            self.reason = "slot walls";
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(fx).to_array(),
            });
        }
        Ok(())
    }

    /// Splits both lips of the open slit edge between `a` and `b` at its middle; returns one of
    /// the two new (coincident) vertices.
    fn split_lips(&mut self, a: u32, b: u32) -> Result<u32, ScalpelError> {
        let p = self.mesh.pos(a).lerp(self.mesh.pos(b), 0.5);
        let (ab, ba) =
            super::groove::find_lips(&self.mesh, a, b).ok_or(ScalpelError::WalkFailed {
                point: p.to_array(),
            })?;
        let x = self.mesh.split_edge(ab, p);
        let y = self.mesh.split_edge(ba, p);
        self.mesh.join_copies(x, y);
        Ok(x)
    }

    /// Whether a cut starting at `v` goes through the structure: the far side's vertex (made
    /// where the inward ray from `v` leaves it) and the thickness there, when that is less than
    /// the blade's depth.
    /// With `near` (the thickness where the stroke's last slot ended), the far side is searched
    /// outward from `v` ([`super::through::ray_hit_near`]), not over the whole mesh.
    fn through_start(
        &mut self,
        v: u32,
        near: Option<f64>,
    ) -> Result<Option<(u32, f64)>, ScalpelError> {
        let n = self.mesh.surface_normal(v, &mut self.scratch);
        if n == DVec3::ZERO {
            return Ok(None);
        }
        let pv = self.mesh.pos(v);
        let hit = match near {
            None => super::through::ray_first_hit(&self.mesh, pv, -n, v),
            Some(expected) => {
                super::through::ray_hit_near(&self.mesh, v, pv, -n, expected, RESTART_SEARCH)
                    .filter(|&(t, _, _)| {
                        !self.mesh.triangles[t as usize]
                            .iter()
                            .any(|&x| self.mesh.same_point(x, v))
                    })
            }
        };
        let Some((t, bary, s)) = hit else {
            return Ok(None);
        };
        if s >= self.options.depth || self.mesh.face_normal_scaled(t).dot(n) >= 0.0 {
            return Ok(None);
        }
        let far = match classify(&self.mesh, t, bary, self.options.snap_end) {
            CutPoint::Vertex(f) => f,
            CutPoint::Edge { h, point } => self.split_edge_with_mate(h, point)?,
            CutPoint::Face { t, point } => self.mesh.split_face(t, point),
        };
        if self.mesh.singular[far as usize] {
            return Err(self.nonmanifold(far));
        }
        Ok(Some((far, s)))
    }

    /// Places the temporary tip at `end` (relative to the anchor) and closes the groove to it.
    fn insert_tip(&mut self, stroke: &mut Stroke, end: End) -> Result<u32, ScalpelError> {
        let mark = self.mesh.mark();
        let segments = self.segments.len();
        let Some(cut) = stroke.cut.as_mut() else {
            return Err(ScalpelError::NoStroke);
        };
        let backup = cut.groove.as_ref().map(|g| g.backup(cut.path.len() - 1));
        let v = cut.anchor;
        let n = self.mesh.surface_normal(v, &mut self.scratch);
        let x = match end {
            End::AtVertex => v,
            End::OnVertex(b) => b,
            End::OnEdge { h, p } => self.split_edge_with_mate(h, p)?,
            End::InFace { t, p } => self.mesh.split_face(t, p),
        };
        let crossed = usize::from(x != v);
        if x != v {
            self.open_between(v, x)?;
            self.record_segment(v, x, n);
        }
        if let Some(g) = cut.groove.as_mut() {
            // The tip joins the path only for building the walls (popped again below).
            let k = cut.path.len() - 1;
            if x != v {
                g.set_split(
                    k + 1,
                    match end {
                        End::OnEdge { .. } => 1,
                        End::InFace { .. } => 2,
                        _ => 0,
                    },
                );
                if k >= 1 {
                    let pv = self.mesh.pos(v);
                    let prev = self.mesh.pos(cut.path[k - 1]);
                    g.make_bottom(&mut self.mesh, k, pv, prev, n);
                }
                cut.path.push(x);
            }
            let last = cut.path.len() - 1;
            g.make_tip(last, cut.path[last]);
            let closed = g.build_walls(&mut self.mesh, &cut.path, last) && g.is_closed();
            if x != v {
                cut.path.pop();
            }
            if !closed {
                self.reason = "groove tip walls not closed";
                return Err(ScalpelError::WalkFailed {
                    point: self.mesh.pos(x).to_array(),
                });
            }
        }
        stroke.tip = Some(Tip {
            mark,
            groove: backup,
            segments,
            crossed,
        });
        Ok(x)
    }

    /// Ends the current cut where its anchor is (the blade left the surface): walls to the tip.
    fn finish_cut(&mut self, stroke: &mut Stroke) -> Result<(), ScalpelError> {
        if let Some(far) = stroke.far.take()
            && let Some(cut) = stroke.cut.take()
            && !super::through::build_walls(&mut self.mesh, &cut.path, &far.path)
        {
            self.reason = "walls at the end of a slot";
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(cut.anchor).to_array(),
            });
        }
        if let Some(cut) = stroke.cut.as_ref() {
            stroke.last_end = Some(cut.anchor);
        }
        if let Some(mut cut) = stroke.cut.take()
            && let Some(g) = cut.groove.as_mut()
        {
            let k = cut.path.len() - 1;
            g.make_tip(k, cut.anchor);
            if !g.build_walls(&mut self.mesh, &cut.path, k) || !g.is_closed() {
                self.reason = "walls at the end of a groove";
                return Err(ScalpelError::WalkFailed {
                    point: self.mesh.pos(cut.anchor).to_array(),
                });
            }
            self.fixed.extend_from_slice(&g.bottom_vertices);
        }
        Ok(())
    }

    /// Loop tool: cut from the anchor back to the stroke's start, then report detached pieces.
    fn close_loop(&mut self, stroke: &mut Stroke) -> Result<Vec<csg::Mesh>, ScalpelError> {
        let (Some(start), Some(mut cut)) = (stroke.first_start, stroke.cut.take()) else {
            return Ok(Vec::new());
        };
        let target = self.mesh.pos(start);
        let snap = self.options.snap_end;
        let r = self.walk(&mut cut, target, Some(start), &mut stroke.crossed, snap)?;
        let anchor = cut.anchor;
        if !matches!(r, WalkEnd::Closed) {
            return Err(ScalpelError::LoopNotClosed {
                gap: self.mesh.pos(anchor).distance(target),
            });
        }
        Ok(super::loop_tool::detached_pieces(&self.mesh, start))
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
