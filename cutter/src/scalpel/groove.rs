//! Groove walls: a cut with depth on a closed surface stays closed.
//!
//! The slit of a path `p0 … pk` has two lips; each interior path vertex `pi` gets a floor
//! vertex `bi = pi - depth · n̄(pi)` and each path segment two wall quads, `(y, x, bx, by)` on one
//! lip and the mirror on the other, so the walls meet along the floor polyline (a V groove). At
//! a crack tip the bottom is the tip itself and the quad degenerates to one triangle, so the
//! groove ends in a point and the surface is closed; floor vertices near either end are
//! shallower, so that the groove deepens gradually from its tips ([`super::taper`]).
//!
//! ## Wall shape
//! Every path vertex gets a floor vertex of its own ([`Groove::make_bottom`]): each segment's
//! wall on each lip is a strip quad of two triangles, split along its better diagonal (the one
//! whose triangles have the larger smallest angle), and the floor is a polyline under the path.
//! A floor vertex shared by several path vertices would make a fan of wall triangles from it,
//! thinner the farther it reaches (angles of about `L·d / (s² + d²)` for a lip edge of length
//! `L`, `s` along the path from the floor vertex, at depth `d`, against about `L / d` for the
//! strip), and floor vertices far apart leave the floor off to one side of a curving path: both
//! showed as a torn incision once it opened.
//!
//! The floor lies along `n̄`, the surface normal averaged over the path within one blade depth
//! behind the vertex ([`FLOOR_NORMAL_SPAN`], weighted by path length), not the vertex's own
//! normal: on a noisy surface (the head skin) vertex normals scatter by tens of degrees from one
//! vertex to the next, which made the floor zigzag and the wall quads twist. Across the path,
//! the floor vertex also follows the path averaged over half a blade depth behind it
//! ([`FLOOR_SMOOTH_SPAN`]) rather than every wobble of the lips; along the path it stays under
//! its own lip vertex. The floor is placed from the path behind only: a floor vertex is made
//! when the cut leaves its path vertex, and walls trail the cut by one segment.
//!
//! ## Element budget
//! The notes' budgets are separate: the surface pieces the cut leaves in a crossed triangle (T1:
//! 3 edge to edge, at most 4 with an end inside) and the wall triangles of a path segment (T4:
//! at most 4 for a V groove, 2 per lip). Both are counted by
//! [`super::budget::element_budget`]. The walk still never starts or ends a groove inside a
//! face (the start goes onto the nearest edge, the tip to the nearer of the anchor and the
//! crossing), so T1 holds with the walls as they are.
//!
//! Walls trail the cut by one segment: segment `i`'s walls need the bottom of `p(i+1)`, which
//! exists only once the cut has left `p(i+1)`. The last segment gets its walls with the tool tip
//! in the temporary part of each step.

use glam::DVec3;

use super::dyn_mesh::{DynMesh, NO_TWIN, is_real, prev};
use super::relocate::min_angle;

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
    /// Per path vertex whose bottom was made: its rest position and the surface normal there
    /// (`None` for the others), for the averaged normal of later floor vertices
    /// ([`FLOOR_NORMAL_SPAN`]).
    pub tops: Vec<Option<(DVec3, DVec3)>>,
    /// Where the groove starts, while that start is a crack tip (not a trench it opens into):
    /// floor vertices near it are made shallower (`Groove::start_depth`).
    pub start_tip: Option<DVec3>,
}

/// The floor direction under a path vertex is the surface normal averaged (weights falling
/// linearly to zero) over the path within this many blade depths behind it (see "Wall shape").
pub const FLOOR_NORMAL_SPAN: f64 = 1.0;

/// The floor vertex under a path vertex follows the path averaged over this many blade depths
/// behind it, across the path (see [`Groove::across_wobble`]).
pub const FLOOR_SMOOTH_SPAN: f64 = 0.5;

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
    tops_len: usize,
    start_tip: Option<DVec3>,
}

/// The groove reaches its full depth this many blade depths from a crack tip (a slope of about
/// 27°; see [`super::taper`]).
pub const TAPER_DEPTHS: f64 = 2.0;

/// A floor vertex near a tip keeps at least this fraction of the blade depth.
pub const MIN_DEPTH: f64 = 0.2;

impl Groove {
    /// Depth of a floor vertex made under the path point `p`: the blade depth, less within the
    /// taper length of the groove's start when that is a crack tip (see [`super::taper`]).
    pub(crate) fn start_depth(&self, p: DVec3) -> f64 {
        match self.start_tip {
            Some(start) => {
                self.depth * (p.distance(start) / (TAPER_DEPTHS * self.depth)).clamp(MIN_DEPTH, 1.0)
            }
            None => self.depth,
        }
    }

    /// A groove starting at `start` (at `start_pos`), a crack tip.
    pub fn new(depth: f64, start: u32, start_pos: DVec3) -> Groove {
        Groove {
            depth,
            bottoms: vec![start],
            walls_done: 0,
            frontier: Vec::new(),
            bottom_vertices: Vec::new(),
            junctions: Vec::new(),
            tops: Vec::new(),
            start_tip: Some(start_pos),
        }
    }

    /// Inserts a path vertex at `index` (before any later one has its bottom), shifting the
    /// later ones.
    pub fn insert_vertex(&mut self, index: usize) {
        if self.tops.len() >= index {
            self.tops.insert(index, None);
        }
    }

    /// Makes path vertex `index` open into an existing trench whose floor vertex is `floor`.
    pub fn set_junction(&mut self, index: usize, floor: u32) {
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        self.bottoms[index] = floor;
        if index == 0 {
            self.start_tip = None;
        }
        if !self.junctions.contains(&index) {
            self.junctions.push(index);
        }
    }

    /// True when every wall half-edge found its twin (the groove is closed up to its ends).
    pub fn is_closed(&self) -> bool {
        self.frontier.is_empty()
    }

    /// Makes the floor vertex of path vertex `index` (mesh vertex `v`): one per path vertex,
    /// under it along the normal averaged over the path behind (see "Wall shape"), at the depth
    /// [`Groove::start_depth`] gives.
    pub fn make_bottom(&mut self, mesh: &mut DynMesh, index: usize, v: u32) {
        let (p, n) = (mesh.pos(v), whole_normal(mesh, v));
        if self.bottoms.len() <= index {
            self.bottoms.resize(index + 1, NO_TWIN);
        }
        if self.bottoms[index] != NO_TWIN {
            return;
        }
        if self.tops.len() <= index {
            self.tops.resize(index + 1, None);
        }
        self.tops[index] = Some((p, n));
        let n = self.floor_normal(index);
        let top = p + self.across_wobble(index);
        let b = mesh.push_floor_vertex(top - n * self.start_depth(p));
        self.bottoms[index] = b;
        self.bottom_vertices.push(b);
    }

    /// How far the path behind path vertex `index`, averaged over [`FLOOR_SMOOTH_SPAN`] blade
    /// depths (weights as in [`Groove::floor_normal`]), lies across the path from the vertex:
    /// the floor vertex is moved by that, so that it runs under the path's line rather than under
    /// every wobble of the lips around it (on a noisy surface the cut's vertices sit a few
    /// hundredths of an edge either side of the drawn line; over segments much shorter than the
    /// blade is deep, that turned the floor by tens of degrees). Only across: along the path the
    /// floor vertex stays under its own lip vertex.
    fn across_wobble(&self, index: usize) -> DVec3 {
        let Some(Some((p0, _))) = self.tops.get(index).copied() else {
            return DVec3::ZERO;
        };
        let span = FLOOR_SMOOTH_SPAN * self.depth;
        let (mut sum, mut total, mut arc) = (DVec3::ZERO, 0.0, 0.0);
        let (mut at, mut oldest) = (p0, p0);
        for j in (0..index).rev() {
            let Some((p, _)) = self.tops[j] else {
                break;
            };
            let length = p.distance(at);
            let w = (1.0 - arc / span).max(0.0) * length;
            sum += (at + p) * 0.5 * w;
            total += w;
            arc += length;
            (at, oldest) = (p, p);
            if arc >= span {
                break;
            }
        }
        let dir = (p0 - oldest).normalize_or_zero();
        if total <= 0.0 || dir == DVec3::ZERO {
            return DVec3::ZERO;
        }
        let off = sum / total - p0;
        off - dir * off.dot(dir)
    }

    /// The surface normal averaged over the path within [`FLOOR_NORMAL_SPAN`] blade depths
    /// (along the path) behind path vertex `index`: each path vertex's normal weighs the length
    /// of path behind it (so a run of short segments counts no more than one long one, and the
    /// floor direction turns in proportion to the path's length, not its vertex count: the floor
    /// vertices of a short segment stay in order under it), times a weight falling linearly
    /// with the distance from `index`. The vertex's own normal where that average vanishes.
    fn floor_normal(&self, index: usize) -> DVec3 {
        let Some(Some((p0, n0))) = self.tops.get(index).copied() else {
            return DVec3::ZERO;
        };
        let span = FLOOR_NORMAL_SPAN * self.depth;
        let (mut sum, mut arc) = (DVec3::ZERO, 0.0);
        let mut at = (p0, n0);
        for j in (0..index).rev() {
            let (p, n) = at;
            let behind = self.tops[j];
            let length = behind.map_or(0.0, |b| b.0.distance(p));
            sum += n.normalize_or_zero() * (1.0 - arc / span) * length.max(1e-9 * span);
            arc += length;
            match behind {
                Some(b) if arc < span => at = b,
                _ => break,
            }
        }
        let avg = sum.normalize_or_zero();
        if avg == DVec3::ZERO { n0 } else { avg }
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
            tops_len: self.tops.len().min(from),
            start_tip: self.start_tip,
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
        self.tops.truncate(backup.tops_len);
        self.start_tip = backup.start_tip;
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

    /// Wall under boundary half-edge `lip` (`u → w`) with bottoms `bu` (of `u`) and `bw`: the
    /// quad `u, bu, bw, w` split along its better diagonal ([`quad_split`]), or one triangle
    /// where an end is a crack tip (its own bottom).
    /// Returns whether triangles were made (`Option` for the callers' failure path; a wall that
    /// duplicates an existing edge, where a cut doubled back into a trench, is caught by the
    /// step's local validation, which refuses the step).
    fn wall(&mut self, mesh: &mut DynMesh, lip: u32, bu: u32, bw: u32) -> Option<bool> {
        let (u, w) = (mesh.origin(lip), mesh.dest(lip));
        let bu = if mesh.same_point(bu, u) { u } else { bu };
        let bw = if mesh.same_point(bw, w) { w } else { bw };
        let mut tris = Vec::with_capacity(2);
        if bu != u && bw != w && bw != bu {
            let [p_u, p_bu, p_bw, p_w] = [u, bu, bw, w].map(|x| mesh.pos(x));
            if quad_split(p_u, p_bu, p_bw, p_w) {
                tris.push([w, u, bw]);
                tris.push([u, bu, bw]);
            } else {
                tris.push([w, u, bu]);
                tris.push([w, bu, bw]);
            }
        } else {
            if bu != u {
                tris.push([w, u, bu]);
            }
            if bw != w && bw != bu {
                tris.push([w, bu, bw]);
            }
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

/// Unit surface normal at cut vertex `v` over all its copies: a lip copy's own surface fan is
/// one side of the cut, whose normal leans to that side (to either side from one path vertex to
/// the next, which made the floor swing). Zero when degenerate.
pub fn whole_normal(mesh: &DynMesh, v: u32) -> DVec3 {
    let mut scratch = Vec::new();
    let mut n = mesh.surface_normal(v, &mut scratch);
    for c in mesh.copies(v) {
        n += mesh.surface_normal(c, &mut scratch);
    }
    n.normalize_or_zero()
}

/// Which diagonal splits the wall quad `u, bu, bw, w` (lip edge `u w`, floor edge `bu bw`) into
/// better triangles: `true` for `u bw`, `false` for `w bu`. The better one has the larger
/// smallest angle (a tall quad split along its long diagonal leaves two slivers).
pub fn quad_split(u: DVec3, bu: DVec3, bw: DVec3, w: DVec3) -> bool {
    let along_u_bw = min_angle(w, u, bw).min(min_angle(u, bu, bw));
    let along_w_bu = min_angle(w, u, bu).min(min_angle(w, bu, bw));
    along_u_bw > along_w_bu
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
