//! The mesh edits a cut makes: starting a cut at the first sample, splitting an edge together
//! with its mate across a slit, opening the surface between two cut vertices, moving the cut on
//! and recording the cut segments the opening deforms.

use super::*;

impl Scalpel {
    /// Starts a cut at the surface point nearest `q`. Where the stroke starts this is a global
    /// search (linear scans for the nearest face, whether the surface is closed and, for a
    /// groove, the through-cut ray: `begin_stroke` costs O(mesh)); where a cut restarts inside
    /// the stroke (after merging into another cut) the nearest face is searched outward from
    /// where the last cut ended ([`closest_face_near`], at most [`RESTART_SEARCH`] triangles),
    /// and the stroke keeps its surface's closedness and its kind (a groove restarts as a
    /// groove): no step scans the mesh.
    pub(super) fn start_cut(
        &mut self,
        stroke: &mut Stroke,
        q: DVec3,
    ) -> Result<StepReport, ScalpelError> {
        let restart = stroke.touched.then_some(stroke.last_end).flatten();
        let found = match restart {
            Some(v) => closest_face_near(&self.mesh, v, q, RESTART_SEARCH),
            None if stroke.touched => None,
            None => self
                .locator
                .closest_face(&self.mesh, q)
                .map(|(t, w, d, component)| {
                    stroke.component = Some(component);
                    (t, w, d)
                }),
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
            stroke.surface_closed = stroke
                .component
                .and_then(|c| self.closed_components.get(c as usize).copied())
                .unwrap_or_else(|| self.component_closed(t));
        }
        let groove_mode =
            self.options.depth > 0.0 && self.options.tool == Tool::Scalpel && stroke.surface_closed;
        // Where the user drew the start, on the surface.
        let drawn = {
            let [a, b, c] = self.mesh.triangles[t as usize].map(|x| self.mesh.pos(x));
            a * bary.x + b * bary.y + c * bary.z
        };
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
        let v = match cp {
            CutPoint::Vertex(v) => v,
            CutPoint::Edge { h, point } => self.split_edge_with_mate(h, point)?,
            CutPoint::Face { t, point } => self.mesh.split_face(t, point),
        };
        if self.mesh.singular[v as usize] {
            return Err(self.nonmanifold(v));
        }
        if !stroke.touched && self.options.tool == Tool::Scalpel {
            // The stroke's first cut starts where the user drew, not where the start snapped
            // to (a vertex or an edge near it, so as to make no sliver), where the triangles
            // around it stay well shaped; before anything else is built on it. (A loop's start
            // is where it closes.)
            crate::scalpel::relocate::tip_onto(&mut self.mesh, v, drawn, &mut self.scratch);
        }
        let mut groove = groove_mode.then(|| Groove::new(self.options.depth, v, self.mesh.pos(v)));
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
    pub(super) fn component_closed(&self, t: u32) -> bool {
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

    pub(super) fn nonmanifold(&self, v: u32) -> ScalpelError {
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
            crate::scalpel::cross::find_mate(&self.mesh, h, &mut self.scratch)
        } else if against_wall(&self.mesh, h) {
            // A groove's lip: split the coincident edge of the other lip too, so that a crossing
            // finds its way on at the same point.
            crate::scalpel::cross::find_groove_mate(&self.mesh, h, &mut self.scratch)
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
    pub(super) fn open_between(&mut self, v: u32, x: u32) -> Result<(), ScalpelError> {
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

    pub(super) fn record_segment(&mut self, a: u32, b: u32, normal: DVec3) {
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
    /// by splitting the edge `split_edge` (`None`: a vertex it goes through).
    pub(super) fn move_to(
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
            if k >= 1 {
                g.make_bottom(&mut self.mesh, k, v);
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
}
