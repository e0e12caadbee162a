//! Groove walls: a cut with depth on a closed surface stays closed.
//!
//! The slit of a path `p0 … pk` has two lips; each interior path vertex `pi` gets a bottom vertex
//! `bi = pi - depth · n(pi)` and each path segment two wall quads, `(y, x, bx, by)` on one lip and
//! the mirror on the other, so the walls meet along the bottom polyline (a V groove: 4 wall
//! triangles per segment, T4 of the notes). At a crack tip the bottom is the tip itself and the
//! quad degenerates to one triangle, so the groove ends in a point and the surface is closed.
//!
//! Walls trail the cut by one segment: segment `i`'s walls need the bottom of `p(i+1)`, which
//! exists only once the cut has left `p(i+1)`. The last segment gets its walls with the tool tip
//! in the temporary part of each step.

use std::collections::HashMap;

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, prev};

/// Groove bookkeeping of one cut.
#[derive(Clone, Debug)]
pub struct Groove {
    /// Blade depth (> 0).
    pub depth: f64,
    /// Bottom vertex of each path vertex (`NO_TWIN` until it is made); the first path vertex is
    /// its own bottom (a crack tip).
    pub bottoms: Vec<u32>,
    /// Segments `0..walls_done` have their walls.
    pub walls_done: usize,
    /// Wall half-edges still waiting for their twin, by `(origin, destination)`.
    pub frontier: HashMap<(u32, u32), u32>,
    /// Bottom vertices created (never moved by the opening).
    pub bottom_vertices: Vec<u32>,
}

impl Groove {
    pub fn new(depth: f64, start: u32) -> Groove {
        Groove {
            depth,
            bottoms: vec![start],
            walls_done: 0,
            frontier: HashMap::new(),
            bottom_vertices: Vec::new(),
        }
    }

    /// Makes the bottom of path vertex `index` (at rest position `p`, normal `n`).
    pub fn make_bottom(&mut self, mesh: &mut DynMesh, index: usize, p: DVec3, n: DVec3) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        if self.bottoms[index] == NO_TWIN {
            let b = mesh.push_vertex(p - n * self.depth);
            self.bottoms[index] = b;
            self.bottom_vertices.push(b);
        }
    }

    /// Marks path vertex `index` (vertex `v`) as a crack tip: its own bottom.
    pub fn make_tip(&mut self, index: usize, v: u32) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        self.bottoms[index] = v;
    }

    /// Builds the walls of every segment of `path` from `walls_done` up to (excluding) `upto`.
    /// Returns false when a segment's lips cannot be found (the caller fails the step).
    pub fn build_walls(&mut self, mesh: &mut DynMesh, path: &[u32], upto: usize) -> bool {
        while self.walls_done < upto {
            let i = self.walls_done;
            let (Some(&ba), Some(&bb)) = (self.bottoms.get(i), self.bottoms.get(i + 1)) else {
                return false;
            };
            if ba == NO_TWIN || bb == NO_TWIN {
                return false;
            }
            let Some((lip_ab, lip_ba)) = find_lips(mesh, path[i], path[i + 1]) else {
                return false;
            };
            let w1 = self.wall(mesh, lip_ab, ba, bb);
            let w2 = self.wall(mesh, lip_ba, bb, ba);
            if !w1 && !w2 {
                // Both ends are crack tips: close the slit again (zero depth).
                mesh.link(lip_ab, lip_ba);
            }
            self.walls_done += 1;
        }
        true
    }

    /// Wall under boundary half-edge `lip` (`u → w`) with bottoms `bu` (of `u`) and `bw`.
    fn wall(&mut self, mesh: &mut DynMesh, lip: u32, bu: u32, bw: u32) -> bool {
        let (u, w) = (mesh.origin(lip), mesh.dest(lip));
        let bu = if mesh.same_point(bu, u) { u } else { bu };
        let bw = if mesh.same_point(bw, w) { w } else { bw };
        let mut tris = Vec::with_capacity(2);
        if bu != u {
            tris.push([w, u, bu]);
        }
        if bw != w {
            tris.push([w, bu, bw]);
        }
        if tris.is_empty() {
            return false;
        }
        let mut first = true;
        for tri in tris {
            let t = mesh.push_tri(tri);
            for k in 0..3u32 {
                let h = 3 * t + k;
                let (a, b) = (tri[k as usize], tri[((k + 1) % 3) as usize]);
                if first && k == 0 {
                    mesh.link(h, lip);
                    continue;
                }
                if let Some(g) = self.frontier.remove(&(b, a)) {
                    mesh.link(h, g);
                } else {
                    self.frontier.insert((a, b), h);
                }
            }
            mesh.refresh_vert_he(t);
            first = false;
        }
        true
    }
}

/// The two boundary half-edges (lips) between the copies of `a` and the copies of `b`: one from
/// `a`'s side to `b`'s, one back.
pub fn find_lips(mesh: &DynMesh, a: u32, b: u32) -> Option<(u32, u32)> {
    let mut ab = None;
    let mut ba = None;
    let mut fan = Vec::new();
    let mut ring = vec![b];
    ring.extend(mesh.copies(b));
    for y in ring {
        mesh.fan_into(y, &mut fan);
        let (Some(&first), Some(&last)) = (fan.first(), fan.last()) else {
            continue;
        };
        if mesh.twin(first) == NO_TWIN && mesh.same_point(mesh.dest(first), a) {
            ba = Some(first);
        }
        let incoming = prev(last);
        if mesh.twin(incoming) == NO_TWIN && mesh.same_point(mesh.origin(incoming), a) {
            ab = Some(incoming);
        }
    }
    Some((ab?, ba?))
}
