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

use super::cut_point::{CutPoint, classify, closest_face, side};
use super::dyn_mesh::{DynMesh, Mark, NO_TWIN, NONMANIFOLD, is_real, next, prev};
use super::groove::Groove;
use super::{ScalpelError, ScalpelOptions, Tool};

/// Seconds between two tool samples (the tool clock the opening's time window runs on).
pub const SAMPLE_PERIOD: f64 = 1.0 / 60.0;

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
    groove: Option<Groove>,
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
        self.undo_tip(&mut stroke);
        let mark = self.mesh.mark();
        let saved = stroke.clone();
        let (segments, fixed) = (self.segments.len(), self.fixed.len());
        match self.advance(&mut stroke, q) {
            Ok(report) => {
                self.stroke = Some(stroke);
                Ok(report)
            }
            Err(e) => {
                self.mesh.rollback(mark);
                self.segments.truncate(segments);
                self.fixed.truncate(fixed);
                stroke = saved;
                if let Some(pq) = stroke.tip_q {
                    // Deterministic: the same walk from the same anchor places the same tip.
                    let _ = self.place_tip(&mut stroke, pq);
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
            if let Some(cut) = stroke.cut.as_mut() {
                cut.groove = tip.groove;
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
            let r = self.walk(&mut cut, q, None, &mut stroke.crossed);
            stroke.cut = Some(cut);
            r?
        };
        match end {
            WalkEnd::Reached(end) => {
                let tip = self.insert_tip(stroke, end)?;
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

    /// Walks toward `q` and places the temporary tip (used to redo a tip after a failed step).
    fn place_tip(&mut self, stroke: &mut Stroke, q: DVec3) -> Result<(), ScalpelError> {
        let Some(mut cut) = stroke.cut.take() else {
            return Ok(());
        };
        let r = self.walk(&mut cut, q, None, &mut stroke.crossed);
        stroke.cut = Some(cut);
        if let WalkEnd::Reached(end) = r? {
            self.insert_tip(stroke, end)?;
            stroke.tip_q = Some(q);
        }
        Ok(())
    }

    /// Starts a cut at the surface point nearest `q` (a global search: only where a cut starts).
    fn start_cut(&mut self, stroke: &mut Stroke, q: DVec3) -> Result<StepReport, ScalpelError> {
        let (t, bary, dist) = closest_face(&self.mesh, q).ok_or(ScalpelError::EmptyMesh)?;
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
        let cp = classify(&self.mesh, t, bary, self.options.snap_end);
        if stroke.merged {
            // After merging into an existing slit, stay merged while the blade is on its lips.
            let tri = self.mesh.triangles[t as usize];
            if tri.iter().any(|&v| !self.mesh.copies(v).is_empty()) {
                return Ok(StepReport::default());
            }
        }
        let v = match cp {
            CutPoint::Vertex(v) => v,
            CutPoint::Edge { h, point } => self.split_edge_with_mate(h, point)?,
            CutPoint::Face { t, point } => self.mesh.split_face(t, point),
        };
        if self.mesh.singular[v as usize] {
            return Err(self.nonmanifold(v));
        }
        let groove = (self.options.depth > 0.0
            && self.options.tool == Tool::Scalpel
            && self.component_closed(v))
        .then(|| Groove::new(self.options.depth, v));
        stroke.cut = Some(Cut {
            start: v,
            anchor: v,
            path: vec![v],
            groove,
        });
        stroke.touched = true;
        stroke.first_start.get_or_insert(v);
        Ok(StepReport {
            triangles_crossed: 1,
            on_mesh: true,
        })
    }

    /// Whether the connected surface around `v` is closed (no boundary edge reachable).
    fn component_closed(&self, v: u32) -> bool {
        let h = self.mesh.vert_he[v as usize];
        if h == NO_TWIN {
            return false;
        }
        let mut seen = vec![false; self.mesh.triangle_count()];
        let mut stack = vec![h / 3];
        seen[(h / 3) as usize] = true;
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

    /// Permanent move of the cut from the anchor `v` to its neighbour `x`.
    fn move_to(&mut self, cut: &mut Cut, v: u32, x: u32) -> Result<(), ScalpelError> {
        let n = self.mesh.vertex_normal(v, &mut self.scratch);
        if let Some(g) = cut.groove.as_mut() {
            let k = cut.path.len() - 1;
            if k >= 1 {
                let pv = self.mesh.pos(v);
                g.make_bottom(&mut self.mesh, k, pv, n);
            }
        }
        self.open_between(v, x)?;
        cut.path.push(x);
        cut.anchor = x;
        self.record_segment(v, x, n);
        if let Some(g) = cut.groove.as_mut() {
            let upto = cut.path.len() - 2;
            if !g.build_walls(&mut self.mesh, &cut.path, upto) {
                return Err(ScalpelError::WalkFailed {
                    point: self.mesh.pos(x).to_array(),
                });
            }
        }
        Ok(())
    }

    /// Exit of the cut from `v`'s fan toward `q` (see the module doc).
    fn find_exit(&mut self, v: u32, q: DVec3, n: DVec3) -> Exit {
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
        mesh.fan_into(v, &mut self.scratch);
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
                if sx == 0 {
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
    ) -> Result<WalkEnd, ScalpelError> {
        let tau = self.options.snap_edge;
        let tau_end = self.options.snap_end;
        for _ in 0..MAX_CROSSINGS {
            let v = cut.anchor;
            if let Some(s) = close_to {
                if self.mesh.same_point(v, s) {
                    return Ok(WalkEnd::Closed);
                }
                if self.mesh.edge_between(v, s, &mut self.scratch).is_some() {
                    self.move_to(cut, v, s)?;
                    *crossed += 1;
                    return Ok(WalkEnd::Closed);
                }
            }
            let n = self.mesh.vertex_normal(v, &mut self.scratch);
            let pv = self.mesh.pos(v);
            let forward = |p: DVec3| (p - pv).dot(q - pv) > 0.0;
            match self.find_exit(v, q, n) {
                Exit::Degenerate => return Ok(WalkEnd::Reached(End::AtVertex)),
                Exit::Blocked => {
                    let back = cut.path[cut.path.len().saturating_sub(5)];
                    let dir = if back == v {
                        q - pv
                    } else {
                        q - self.mesh.pos(back)
                    };
                    if cut.groove.is_none()
                        && let Some(m) = super::cross::crossing_mate(self, v, q, dir)
                    {
                        cut.anchor = m;
                        cut.path.push(m);
                        continue;
                    }
                    let merged = !self.mesh.copies(v).is_empty();
                    return Ok(WalkEnd::Blocked { merged });
                }
                Exit::Vertex { e, b } => {
                    let pb = self.mesh.pos(b);
                    let s = foot(pv, pb, q);
                    if s <= 1.0 {
                        let end = if s < tau_end {
                            End::AtVertex
                        } else if s > 1.0 - tau_end {
                            End::OnVertex(b)
                        } else {
                            End::OnEdge {
                                h: e,
                                p: pv.lerp(pb, s),
                            }
                        };
                        return Ok(WalkEnd::Reached(end));
                    }
                    self.move_to(cut, v, b)?;
                    *crossed += 1;
                }
                Exit::Edge { h0, t, y } => {
                    let b = self.mesh.dest(h0);
                    let c = self.mesh.origin(prev(h0));
                    let (pb, pc) = (self.mesh.pos(b), self.mesh.pos(c));
                    let s = foot(pv, y, q);
                    if s <= 1.0 {
                        let end = if s < tau_end {
                            End::AtVertex
                        } else if s > 1.0 - tau_end {
                            if t < tau {
                                End::OnVertex(b)
                            } else if t > 1.0 - tau {
                                End::OnVertex(c)
                            } else {
                                End::OnEdge { h: next(h0), p: y }
                            }
                        } else if t < tau {
                            End::OnEdge {
                                h: h0,
                                p: pv.lerp(pb, s),
                            }
                        } else if t > 1.0 - tau {
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
                    let x = if t < tau && forward(pb) {
                        b
                    } else if t > 1.0 - tau && forward(pc) {
                        c
                    } else {
                        self.split_edge_with_mate(next(h0), y)?
                    };
                    self.move_to(cut, v, x)?;
                    *crossed += 1;
                }
            }
        }
        Err(ScalpelError::WalkFailed {
            point: q.to_array(),
        })
    }

    /// Places the temporary tip at `end` (relative to the anchor) and closes the groove to it.
    fn insert_tip(&mut self, stroke: &mut Stroke, end: End) -> Result<u32, ScalpelError> {
        let mark = self.mesh.mark();
        let segments = self.segments.len();
        let Some(cut) = stroke.cut.as_mut() else {
            return Err(ScalpelError::NoStroke);
        };
        let backup = cut.groove.clone();
        let v = cut.anchor;
        let n = self.mesh.vertex_normal(v, &mut self.scratch);
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
            let mut path = cut.path.clone();
            let k = path.len() - 1;
            if x != v {
                if k >= 1 {
                    let pv = self.mesh.pos(v);
                    g.make_bottom(&mut self.mesh, k, pv, n);
                }
                path.push(x);
            }
            g.make_tip(path.len() - 1, *path.last().unwrap_or(&v));
            if !g.build_walls(&mut self.mesh, &path, path.len() - 1) {
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
        if let Some(mut cut) = stroke.cut.take()
            && let Some(g) = cut.groove.as_mut()
        {
            let k = cut.path.len() - 1;
            g.make_tip(k, cut.anchor);
            if !g.build_walls(&mut self.mesh, &cut.path, k) {
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
        let r = self.walk(&mut cut, target, Some(start), &mut stroke.crossed)?;
        let anchor = cut.anchor;
        if !matches!(r, WalkEnd::Closed) {
            return Err(ScalpelError::LoopNotClosed {
                gap: self.mesh.pos(anchor).distance(target),
            });
        }
        Ok(super::loop_tool::detached_pieces(&self.mesh, start))
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

    pub(crate) fn exit_exists(&mut self, v: u32, q: DVec3) -> bool {
        let n = self.mesh.vertex_normal(v, &mut self.scratch);
        matches!(
            self.find_exit(v, q, n),
            Exit::Edge { .. } | Exit::Vertex { .. }
        )
    }
}

/// Parameter of the point of segment `a b` closest to `q` (unclamped).
fn foot(a: DVec3, b: DVec3, q: DVec3) -> f64 {
    let ab = b - a;
    let l = ab.length_squared();
    if l == 0.0 { 0.0 } else { (q - a).dot(ab) / l }
}
