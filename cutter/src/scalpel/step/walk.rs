//! The surface walk of a step: where the cut leaves the current vertex's fan (the exit, decided
//! by exact sides against the walking plane, see the parent module) and the permanent walk from
//! the anchor toward the tool sample, joining an earlier trench where the cut meets one.

use super::*;
use crate::scalpel::relocate;

/// A sample whose offset from the anchor across the surface normal is at most this fraction of
/// the anchor's longest edge is reached (see `walk`).
const REACHED: f64 = 1e-3;

impl Scalpel {
    /// Exit of the cut from `v`'s fan toward `q` (see the module doc).
    /// With `no_retrace`, never along a slit's lip (a groove's own cut must not double back
    /// along its open slit).
    pub(super) fn find_exit(&mut self, v: u32, q: DVec3, n: DVec3, no_retrace: bool) -> Exit {
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
    pub(super) fn walk(
        &mut self,
        cut: &mut Cut,
        q: DVec3,
        close_to: Option<u32>,
        crossed: &mut usize,
        tau_end: f64,
    ) -> Result<WalkEnd, ScalpelError> {
        let tau = if cut.groove.is_some() {
            self.options.groove_snap_edge
        } else {
            self.options.snap_edge
        };
        // Vertices are moved onto the cut (`relocate`) by open cuts and grooves; a slot's two
        // slits are joined by walls built from both paths, and a loop's closing walk aims at a
        // vertex, not along the drawn path: those go through vertices as they are.
        let relocating = !cut.through && close_to.is_none();
        for _ in 0..MAX_CROSSINGS {
            let v = cut.anchor;
            let k = cut.path.len() - 1;
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
            let dq = q - pv;
            let across = (dq - n * dq.dot(n)).length();
            if is_real(h)
                && (pv.distance(q) <= 1e-9 * self.mesh.longest_edge(h / 3)
                    || across <= REACHED * self.mesh.longest_edge(h / 3))
            {
                // The sample is on the anchor (a through-cut's far side found exactly under
                // the sample at a vertex), or straight above or below it (an anchor moved onto
                // the cut, `relocate`, lies on a chord of a curved surface, under a sample on
                // the surface): nothing to cut, no direction to find an exit in.
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
                        if let Some(floor) = crate::scalpel::groove::floor_under(&self.mesh, v, n)
                            && !unfinished(floor)
                        {
                            // A groove meeting a groove: open into its trench here, then go on
                            // from the other lip (crossing) or end here (merging). When the
                            // stroke crosses but the sample is not beyond the lip yet, the tip
                            // waits on the lip.
                            let mate = crate::scalpel::cross::crossing_mate(self, v, q, dir);
                            if mate.is_none() {
                                let angle = self.mesh.copies(v).first().map_or(0.0, |&c| {
                                    crate::scalpel::cross::angle_to_lip(
                                        &self.mesh,
                                        c,
                                        dir,
                                        &mut Vec::new(),
                                    )
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
                        && let Some(m) = crate::scalpel::cross::crossing_mate(self, v, q, dir)
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
                        // Through `b`, moved onto the cut where that keeps its triangles well
                        // shaped (`relocate`): the cut keeps its line instead of kinking to `b`.
                        if relocating {
                            relocate::onto_cut(&mut self.mesh, b, y, &mut self.scratch);
                        }
                        (b, None)
                    } else if near_c && forward(pc) {
                        if relocating {
                            relocate::onto_cut(&mut self.mesh, c, y, &mut self.scratch);
                        }
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
    pub(super) fn join_trench(
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
            cut.path.insert(1, mid);
            if let Some(g) = cut.groove.as_mut() {
                g.insert_vertex(1);
                g.make_bottom(&mut self.mesh, 1, mid);
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
            crate::scalpel::taper::shape_end(g, &mut self.mesh, &cut.path, k);
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
        let far_floor =
            crate::scalpel::groove::floor_under(&self.mesh, m, nm).ok_or_else(|| fail(pv))?;
        let mut groove = Groove::new(depth, m, self.mesh.pos(m));
        groove.set_junction(0, far_floor);
        cut.groove = Some(groove);
        cut.start = m;
        cut.anchor = m;
        cut.split_edge = None;
        cut.path = vec![m];
        Ok(Some(m))
    }
}
