//! Groove walls: a cut with depth on a closed surface stays closed.
//!
//! The slit of a path `p0 … pk` has two lips; each interior path vertex `pi` gets a bottom vertex
//! `bi = pi - depth · n(pi)` and each path segment two wall quads, `(y, x, bx, by)` on one lip and
//! the mirror on the other, so the walls meet along the bottom polyline (a V groove, T4 of the
//! notes). Consecutive path vertices share a bottom while the path runs straight and near
//! ([`Groove::make_bottom`]): a quad whose two bottoms are one vertex is one triangle, so a
//! segment usually costs 2 wall triangles instead of 4. At a crack tip the bottom is the tip
//! itself and the quad degenerates to one triangle, so the groove ends in a point and the
//! surface is closed.
//!
//! Walls trail the cut by one segment: segment `i`'s walls need the bottom of `p(i+1)`, which
//! exists only once the cut has left `p(i+1)`. The last segment gets its walls with the tool tip
//! in the temporary part of each step.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, is_real, prev};

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
    /// Wall half-edges still waiting for their twin, by `(origin, destination)` (a handful: a
    /// vector is cheaper than a map to search and to snapshot).
    pub frontier: Vec<((u32, u32), u32)>,
    /// Bottom vertices created (never moved by the opening).
    pub bottom_vertices: Vec<u32>,
    /// Path indices (the cut's first or last vertex) whose bottom is a floor vertex of an
    /// existing trench this groove opens into (a junction, see [`super::cross`]); the wall edge
    /// between that path vertex and the floor is opened when the segment's walls are built.
    pub junctions: Vec<usize>,
    /// Where the last floor vertex was made: the path point above it and the path's direction
    /// there (for reusing it, see [`Groove::make_bottom`]).
    pub floor_top: Option<(DVec3, DVec3)>,
}

/// A new floor vertex once the path is farther than this many blade depths (or segment
/// lengths, when longer) from where the current one was made.
pub const FLOOR_REACH: f64 = 6.0;
/// A new floor vertex once the path turns more than this from where the current one was made.
pub const FLOOR_TURN_DEG: f64 = 35.0;

/// See [`Groove::backup`].
#[derive(Clone, Debug)]
pub struct GrooveBackup {
    bottoms_len: usize,
    from: usize,
    tail: Vec<u32>,
    walls_done: usize,
    frontier: Vec<((u32, u32), u32)>,
    bottom_vertices: usize,
    junctions: Vec<usize>,
    floor_top: Option<(DVec3, DVec3)>,
}

impl Groove {
    pub fn new(depth: f64, start: u32) -> Groove {
        Groove {
            depth,
            bottoms: vec![start],
            walls_done: 0,
            frontier: Vec::new(),
            bottom_vertices: Vec::new(),
            junctions: Vec::new(),
            floor_top: None,
        }
    }

    /// Makes path vertex `index` open into an existing trench whose floor vertex is `floor`.
    pub fn set_junction(&mut self, index: usize, floor: u32) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        self.bottoms[index] = floor;
        if !self.junctions.contains(&index) {
            self.junctions.push(index);
        }
    }

    /// True when every wall half-edge found its twin (the groove is closed up to its ends).
    pub fn is_closed(&self) -> bool {
        self.frontier.is_empty()
    }

    /// Makes the bottom of path vertex `index` (at rest position `p`, previous path vertex at
    /// `prev`, normal `n`). The floor is coarser than the lips: the bottom of the previous path
    /// vertex is reused while the path stays within [`FLOOR_REACH`] of where that floor vertex
    /// was made and turns less than [`FLOOR_TURN_DEG`] from the way it was going then, so each
    /// path segment costs one wall triangle per lip plus a share of the floor (notes T4).
    pub fn make_bottom(
        &mut self,
        mesh: &mut DynMesh,
        index: usize,
        p: DVec3,
        prev: DVec3,
        n: DVec3,
    ) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        if self.bottoms[index] != NO_TWIN {
            return;
        }
        if index >= 1
            && let Some((top, dir)) = self.floor_top
            && self.bottom_vertices.last() == Some(&self.bottoms[index - 1])
        {
            let d = p - top;
            let reach = FLOOR_REACH * self.depth.max(p.distance(prev));
            let l = d.length() * dir.length();
            let straight = l == 0.0 || d.dot(dir) >= l * FLOOR_TURN_DEG.to_radians().cos();
            if d.length() <= reach && straight {
                self.bottoms[index] = self.bottoms[index - 1];
                return;
            }
        }
        let b = mesh.push_floor_vertex(p - n * self.depth);
        self.bottoms[index] = b;
        self.bottom_vertices.push(b);
        self.floor_top = Some((p, p - prev));
    }

    /// What the temporary tip may change, to restore it without copying the whole groove
    /// (`from`: the first path index the tip may write).
    pub fn backup(&self, from: usize) -> GrooveBackup {
        GrooveBackup {
            bottoms_len: self.bottoms.len(),
            from,
            tail: self
                .bottoms
                .get(from..)
                .map(<[u32]>::to_vec)
                .unwrap_or_default(),
            walls_done: self.walls_done,
            frontier: self.frontier.clone(),
            bottom_vertices: self.bottom_vertices.len(),
            junctions: self.junctions.clone(),
            floor_top: self.floor_top,
        }
    }

    /// Undoes everything since `backup`.
    pub fn restore(&mut self, backup: GrooveBackup) {
        self.bottoms.truncate(backup.from.min(backup.bottoms_len));
        self.bottoms.extend_from_slice(&backup.tail);
        self.bottoms.resize(backup.bottoms_len, NO_TWIN);
        self.walls_done = backup.walls_done;
        self.frontier = backup.frontier;
        self.bottom_vertices.truncate(backup.bottom_vertices);
        self.junctions = backup.junctions;
        self.floor_top = backup.floor_top;
    }

    /// Marks path vertex `index` (vertex `v`) as a crack tip: its own bottom.
    pub fn make_tip(&mut self, index: usize, v: u32) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        self.bottoms[index] = v;
        self.junctions.retain(|&j| j != index);
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
            if self.junctions.contains(&i) && self.junctions.contains(&(i + 1)) {
                // One segment from trench to trench: its walls would lie in the old walls.
                return false;
            }
            for j in [i, i + 1] {
                if let Some(at) = self.junctions.iter().position(|&x| x == j) {
                    self.junctions.swap_remove(at);
                    if !self.open_junction(mesh, path[j], self.bottoms[j]) {
                        return false;
                    }
                }
            }
            let Some((lip_ab, lip_ba)) = find_lips(mesh, path[i], path[i + 1]) else {
                return false;
            };
            let (Some(w1), Some(w2)) = (
                self.wall(mesh, lip_ab, ba, bb),
                self.wall(mesh, lip_ba, bb, ba),
            ) else {
                return false;
            };
            if !w1 && !w2 {
                // Both ends are crack tips: close the slit again (zero depth).
                mesh.link(lip_ab, lip_ba);
            }
            self.walls_done += 1;
        }
        true
    }

    /// Opens the existing wall edge between lip vertex `v` and floor vertex `floor` and leaves
    /// its two half-edges waiting for this groove's walls (which then sit between the two halves
    /// of the old wall: the trenches join at `floor`).
    fn open_junction(&mut self, mesh: &mut DynMesh, v: u32, floor: u32) -> bool {
        let Some(h) = wall_edge(mesh, v, floor) else {
            return false;
        };
        let g = mesh.twin(h);
        let mut created = Vec::new();
        mesh.open_edge(h, &mut created);
        for x in [h, g] {
            self.frontier.push(((mesh.origin(x), mesh.dest(x)), x));
        }
        true
    }

    /// Wall under boundary half-edge `lip` (`u → w`) with bottoms `bu` (of `u`) and `bw`.
    /// Returns whether triangles were made (`Option` for the callers' failure path; a wall that
    /// duplicates an existing edge, where a cut doubled back into a trench, is caught by the
    /// step's local validation, which refuses the step).
    fn wall(&mut self, mesh: &mut DynMesh, lip: u32, bu: u32, bw: u32) -> Option<bool> {
        let (u, w) = (mesh.origin(lip), mesh.dest(lip));
        let bu = if mesh.same_point(bu, u) { u } else { bu };
        let bw = if mesh.same_point(bw, w) { w } else { bw };
        let mut tris = Vec::with_capacity(2);
        if bu != u {
            tris.push([w, u, bu]);
        }
        if bw != w && bw != bu {
            tris.push([w, bu, bw]);
        }
        if tris.is_empty() {
            return Some(false);
        }
        let mut first = true;
        for tri in tris {
            let t = mesh.push_wall_tri(tri);
            for k in 0..3u32 {
                let h = 3 * t + k;
                let (a, b) = (tri[k as usize], tri[((k + 1) % 3) as usize]);
                if first && k == 0 {
                    mesh.link(h, lip);
                    continue;
                }
                if let Some(at) = self.frontier.iter().position(|e| e.0 == (b, a)) {
                    let g = self.frontier.swap_remove(at).1;
                    mesh.link(h, g);
                } else {
                    self.frontier.push(((a, b), h));
                }
            }
            mesh.refresh_vert_he(t);
            first = false;
        }
        Some(true)
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

/// An interior half-edge of `v`'s fan between `v` and `floor` (either direction).
pub fn wall_edge(mesh: &DynMesh, v: u32, floor: u32) -> Option<u32> {
    let mut fan = Vec::new();
    mesh.fan_into(v, &mut fan);
    fan.iter().find_map(|&h| {
        if mesh.dest(h) == floor && is_real(mesh.twin(h)) {
            Some(h)
        } else if mesh.origin(prev(h)) == floor && is_real(mesh.twin(prev(h))) {
            Some(prev(h))
        } else {
            None
        }
    })
}

/// The floor vertex of the trench under lip vertex `v` (a wall edge joins them), the one most
/// nearly straight below `v` (least offset across the normal `n`). `None` when `v` is not on a
/// groove's lip.
pub fn floor_under(mesh: &DynMesh, v: u32, n: DVec3) -> Option<u32> {
    let mut fan = Vec::new();
    mesh.fan_into(v, &mut fan);
    let pv = mesh.pos(v);
    let mut best: Option<(f64, u32)> = None;
    for &h in &fan {
        for (f, e) in [(mesh.dest(h), h), (mesh.origin(prev(h)), prev(h))] {
            if mesh.is_floor(f) && is_real(mesh.twin(e)) {
                let off = mesh.pos(f) - pv;
                let across = (off - n * off.dot(n)).length();
                if best.is_none_or(|(b, _)| across < b) {
                    best = Some((across, f));
                }
            }
        }
    }
    best.map(|(_, f)| f)
}
