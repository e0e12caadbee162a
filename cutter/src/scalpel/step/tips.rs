//! The tips of a stroke: the temporary tip placed under the tool sample with the groove walls
//! that close it, the far tip of a through-cut and the walls joining its two slits, and what a
//! finished stroke or a closed loop leaves behind.

use super::*;
use crate::scalpel::{relocate, taper};

impl Scalpel {
    /// Places the temporary tip at `end`; when cutting through, first moves the far cut on
    /// (permanently) under the sample `q`, then places its tip and the walls joining the two
    /// slits (temporary, with the tip).
    pub(super) fn place_tips(
        &mut self,
        stroke: &mut Stroke,
        end: End,
        q: DVec3,
    ) -> Result<u32, ScalpelError> {
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
                let w = crate::scalpel::cut_point::closest_on_triangle(p, a, b, c);
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
        let q_far = match crate::scalpel::through::ray_hit_near(
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
    pub(super) fn end_snap(&self, stroke: &Stroke) -> f64 {
        if stroke.far.is_some() {
            THROUGH_SNAP_END
        } else {
            self.options.snap_end
        }
    }

    /// The far cut's temporary tip and the walls of the whole slot (see [`super::through`]).
    pub(super) fn far_tip(
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
        if !crate::scalpel::through::build_walls(&mut self.mesh, &near, &far_path) {
            self.reason = "slot walls";
            return Err(ScalpelError::WalkFailed {
                point: self.mesh.pos(fx).to_array(),
            });
        }
        Ok(())
    }

    /// Splits both lips of the open slit edge between `a` and `b` at its middle; returns one of
    /// the two new (coincident) vertices.
    pub(super) fn split_lips(&mut self, a: u32, b: u32) -> Result<u32, ScalpelError> {
        let p = self.mesh.pos(a).lerp(self.mesh.pos(b), 0.5);
        let (ab, ba) = crate::scalpel::groove::find_lips(&self.mesh, a, b).ok_or(
            ScalpelError::WalkFailed {
                point: p.to_array(),
            },
        )?;
        let x = self.mesh.split_edge(ab, p);
        let y = self.mesh.split_edge(ba, p);
        self.mesh.join_copies(x, y);
        Ok(x)
    }

    /// Whether a cut starting at `v` goes through the structure: the far side's vertex (made
    /// where the inward ray from `v` leaves it) and the thickness there, when that is less than
    /// the blade's depth.
    /// With `near` (the thickness where the stroke's last slot ended), the far side is searched
    /// outward from `v` ([`crate::scalpel::through::ray_hit_near`]), not over the whole mesh.
    pub(super) fn through_start(
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
            None => self
                .locator
                .far_side(&self.mesh, v, pv, -n, self.options.depth),
            Some(expected) => crate::scalpel::through::ray_hit_near(
                &self.mesh,
                v,
                pv,
                -n,
                expected,
                RESTART_SEARCH,
            )
            .filter(|&(t, _, _)| {
                !self.mesh.triangles[t as usize]
                    .iter()
                    .any(|&x| self.mesh.same_point(x, v))
            }),
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
    pub(super) fn insert_tip(
        &mut self,
        stroke: &mut Stroke,
        end: End,
    ) -> Result<u32, ScalpelError> {
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
                if k >= 1 {
                    g.make_bottom(&mut self.mesh, k, v);
                }
                cut.path.push(x);
            }
            let last = cut.path.len() - 1;
            g.make_tip(last, cut.path[last]);
            taper::shape_end(g, &mut self.mesh, &cut.path, last);
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
    pub(super) fn finish_cut(&mut self, stroke: &mut Stroke) -> Result<(), ScalpelError> {
        if let Some(far) = stroke.far.take()
            && let Some(cut) = stroke.cut.take()
            && !crate::scalpel::through::build_walls(&mut self.mesh, &cut.path, &far.path)
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
            taper::shape_end(g, &mut self.mesh, &cut.path, k);
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

    /// At the end of a stroke (not a loop, not cutting through): moves the cut's end tip from
    /// where the walk snapped it (a vertex or an edge near the last sample, so as to make no
    /// sliver) onto the last sample's nearest point on the surface around it, where that keeps
    /// the tip's triangles well shaped ([`relocate::tip_onto`]), so the lips end where the user
    /// drew. The cut segments ending there follow (the opening tapers to the moved tip), and so
    /// does a groove's taper toward the tip.
    pub(super) fn settle_tip(&mut self, stroke: &Stroke) {
        let (Some(cut), Some(q), None) = (stroke.cut.as_ref(), stroke.tip_q, stroke.far.as_ref())
        else {
            return;
        };
        let Some(last) = self.segments[stroke.records.0.min(self.segments.len())..].last() else {
            return;
        };
        // The cut's own last segment (not one of a cut it merged into before restarting).
        if last.a != cut.anchor && last.b != cut.anchor {
            return;
        }
        let x = last.b;
        if !self.mesh.surface_fan_into(x, &mut self.scratch) {
            return;
        }
        let mut best: Option<(f64, DVec3)> = None;
        for &h in &self.scratch {
            let tri = self.mesh.triangles[(h / 3) as usize];
            let [a, b, c] = tri.map(|v| self.mesh.pos(v));
            let w = crate::scalpel::cut_point::closest_on_triangle(q, a, b, c);
            let y = a * w.x + b * w.y + c * w.z;
            let d = y.distance_squared(q);
            if best.is_none_or(|(e, _)| d < e) {
                best = Some((d, y));
            }
        }
        let Some((_, y)) = best else {
            return;
        };
        if !relocate::tip_onto(&mut self.mesh, x, y, &mut self.scratch) {
            return;
        }
        for s in &mut self.segments[stroke.records.0..] {
            if s.a == x {
                s.pa = y;
            }
            if s.b == x {
                s.pb = y;
            }
        }
        if let Some(g) = cut.groove.as_ref() {
            // The taper toward the tip, again from where the tip is now.
            let mut path = cut.path.clone();
            if x != cut.anchor {
                path.push(x);
            }
            taper::shape_end(g, &mut self.mesh, &path, path.len() - 1);
        }
    }

    /// Loop tool: cut from the anchor back to the stroke's start, then report detached pieces.
    pub(super) fn close_loop(
        &mut self,
        stroke: &mut Stroke,
    ) -> Result<Vec<csg::Mesh>, ScalpelError> {
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
        Ok(crate::scalpel::loop_tool::detached_pieces(
            &self.mesh, start,
        ))
    }
}
