//! Groove walls: a cut with depth on a closed surface stays closed.
//!
//! The slit of a path `p0 … pk` has two lips; each interior path vertex `pi` gets a bottom vertex
//! `bi = pi - depth · n(pi)` and each path segment two wall quads, `(y, x, bx, by)` on one lip and
//! the mirror on the other, so the walls meet along the bottom polyline (a V groove, T4 of the
//! notes). Consecutive path vertices share a bottom while the path runs straight and near
//! ([`Groove::make_bottom`]): a quad whose two bottoms are one vertex is one triangle, so a
//! segment usually costs 2 wall triangles instead of 4. At a crack tip the bottom is the tip
//! itself and the quad degenerates to one triangle, so the groove ends in a point and the
//! surface is closed; floor vertices near either end are shallower, so that the groove deepens
//! gradually from its tips ([`super::taper`]).
//!
//! ## Wall shape
//! A floor vertex shared by the path vertices above a stretch of floor makes a fan of wall
//! triangles from it; the farther the fan reaches along the path, the thinner its triangles
//! (one whose lip edge is `s` along the path from the floor vertex, at depth `d`, has angles of
//! about `L·d / (s² + d²)` radians for a lip edge of length `L`). A reach of about one blade
//! depth ([`FLOOR_REACH`]) keeps them within a factor two of a strip with a floor vertex under
//! every path vertex (angles about `L / d`), and the floor triangles between floor changes at
//! about 45°, while the floor changes no more often than the element budget allows (walls
//! shared over six depths made fans of sliver triangles that showed as a torn incision once
//! it opened).
//!
//! ## Element budget
//! A groove adds at most 4 new triangles in one triangle the cut crosses (counted as in
//! [`super::survey::element_budget`]: surface pieces minus one, plus the lip walls of the
//! segments cut through it, plus half of each floor triangle at either end of those segments).
//! A segment from an edge split to an edge split leaves 3 pieces and 2 lip walls: 4, no room. So
//! the floor changes only at a path vertex where a segment beside it has room ([`Groove::load`]
//! below 2: it ends on a vertex of the mesh), and the two floor triangles (one per lip) sit at
//! that vertex, one counted for each segment meeting there. When the floor is due and the anchor
//! split an edge, the walk snaps its next crossing to a vertex (`FLOOR_DUE_SNAP` in `step`); the
//! floor waits at most [`FLOOR_STRETCH`] times its reach. The rest of the budget is kept by the
//! walk: a groove never starts or ends inside a face (the start goes onto the nearest edge, the
//! tip to the nearer of the anchor and the crossing), never snaps back onto the edge its anchor
//! split, and splits an edge for good only once the sample is clearly past it.
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
    /// Per path vertex: the surface pieces the cut added for it in each triangle beside it, 0
    /// for a vertex of the mesh (the cut went through it), 1 for a point where it split an edge,
    /// 2 for a start inside a face. With `attached`, the element budget of each segment (see
    /// [`Groove::load`]).
    pub split: Vec<u8>,
    /// Per path vertex: floor changes whose floor triangles (one per lip) sit at this vertex.
    pub attached: Vec<u8>,
    /// Segments whose floor triangles sit at their first path vertex (the others' at their last).
    pub floor_at_start: Vec<usize>,
    /// The path points whose bottom reused the newest floor vertex since it was made (the floor
    /// runs straight under them, see [`FLOOR_SWAY`]).
    pub floor_run: Vec<DVec3>,
    /// Where the groove starts, while that start is a crack tip (not a trench it opens into):
    /// floor vertices near it are made shallower (`Groove::start_depth`).
    pub start_tip: Option<DVec3>,
}

/// A new floor vertex once the path is farther than this many blade depths (or segment
/// lengths, when longer) from where the current one was made (see "Wall shape").
pub const FLOOR_REACH: f64 = 1.0;
/// A new floor vertex once the path turns more than this from where the current one was made.
pub const FLOOR_TURN_DEG: f64 = 35.0;
/// At most about this many blade depths (plus a segment) between consecutive floor vertices,
/// even where the floor is waiting for room (see [`FLOOR_STRETCH`]): the floor triangle joining
/// them to a lip vertex one depth above the newer one has angles of about 1° or more (notes
/// Q0). Past it the floor changes anyway (5 new triangles in one crossed triangle): with a blade
/// much shallower than the triangles are wide, the element budget gives way to element quality.
pub const FLOOR_MAX_SPAN: f64 = 45.0;
/// A floor change waits for a path vertex with room for its floor triangles (see
/// [`Groove::make_bottom`]) up to this many times [`FLOOR_REACH`], or a turn of
/// [`FLOOR_FORCE_TURN_DEG`].
pub const FLOOR_STRETCH: f64 = 6.0;
/// See [`FLOOR_STRETCH`]. (The turn is measured from the one segment where the floor vertex was
/// made: zigzags of the path across the mesh make it noisy, so the limit is generous.)
pub const FLOOR_FORCE_TURN_DEG: f64 = 85.0;
/// A new floor vertex is due once a path point above the current stretch of floor is farther
/// than this many blade depths (or twice the segment length, when longer: the lips zigzag
/// around the drawn path by up to an edge snap) from the straight line the floor takes (from
/// where it was made to the path vertex now). A path curving along the surface otherwise leaves
/// the straight floor off to one side of it: under one lip, so that when the incision opens one
/// wall stands vertical or overhangs (hidden) and the other lies flat. Only a due change: it
/// waits for room like the others and never goes over the element budget.
pub const FLOOR_SWAY: f64 = 0.25;

/// Whether a path vertex at `p` (the one before at `prev`) is more than `k` times
/// [`FLOOR_REACH`] (never more than [`FLOOR_MAX_SPAN`] depths) from `top`, where the current
/// floor vertex was made going `dir`, or turned more than [`FLOOR_TURN_DEG`] from `dir` (for
/// `k > 1`, [`FLOOR_FORCE_TURN_DEG`]), or (for `k ≤ 1`) a point of `run` (the path above the
/// current floor) sways more than [`FLOOR_SWAY`] from the line `top → p`.
fn floor_far(
    depth: f64,
    (top, dir): (DVec3, DVec3),
    run: &[DVec3],
    p: DVec3,
    prev: DVec3,
    k: f64,
) -> bool {
    let d = p - top;
    let l2 = d.length_squared();
    // The lips zigzag around the drawn path by up to a snap of an edge: not a sway.
    let sway_limit = FLOOR_SWAY * depth.max(2.0 * p.distance(prev));
    let sway = k <= 1.0
        && run.iter().any(|&q| {
            let u = if l2 > 0.0 {
                ((q - top).dot(d) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            q.distance(top + d * u) > sway_limit
        });
    if sway {
        return true;
    }
    let reach = FLOOR_REACH * depth.max(p.distance(prev));
    let l = d.length() * dir.length();
    let turn = if k > 1.0 {
        FLOOR_FORCE_TURN_DEG
    } else {
        k * FLOOR_TURN_DEG
    };
    let turned = l > 0.0 && d.dot(dir) < l * turn.to_radians().cos();
    d.length() > (k * reach).min(FLOOR_MAX_SPAN * depth) || turned
}

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
    /// `split` and `attached` from `from - 1` on (a floor change may sit at the vertex before).
    split_tail: Vec<u8>,
    attached_tail: Vec<u8>,
    floor_at_start: Vec<usize>,
    floor_run: Vec<DVec3>,
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

    /// A groove starting at `start` (at `start_pos`), a vertex the cut made by splitting
    /// `start_split` pieces more into the triangles around it (see [`Groove::split`]).
    pub fn new(depth: f64, start: u32, start_pos: DVec3, start_split: u8) -> Groove {
        Groove {
            depth,
            bottoms: vec![start],
            walls_done: 0,
            frontier: Vec::new(),
            bottom_vertices: Vec::new(),
            junctions: Vec::new(),
            floor_top: None,
            split: vec![start_split],
            attached: vec![0],
            floor_at_start: Vec::new(),
            floor_run: Vec::new(),
            start_tip: Some(start_pos),
        }
    }

    /// Records how path vertex `index` was made (see [`Groove::split`]).
    pub fn set_split(&mut self, index: usize, pieces: u8) {
        if self.split.len() <= index {
            self.split.resize(index + 1, 0);
        }
        self.split[index] = pieces;
    }

    /// Inserts a path vertex at `index` (made by splitting an edge), shifting the later ones.
    pub fn insert_split(&mut self, index: usize) {
        if self.split.len() >= index {
            self.split.insert(index, 1);
        }
        if self.attached.len() >= index {
            self.attached.insert(index, 0);
        }
    }

    /// New triangles segment `s` (path vertices `s`, `s + 1`) adds to the triangle it crosses,
    /// beyond its two lip walls: the surface pieces of its ends plus one per floor change sitting
    /// at either end (two floor triangles, counted half for each segment at that vertex). Kept
    /// at most 2, so a crossed triangle gets at most 4 new ones (see
    /// `survey::element_budget`).
    pub fn load(&self, s: usize) -> u8 {
        let at = |v: &Vec<u8>, i: usize| v.get(i).copied().unwrap_or(0);
        at(&self.split, s)
            + at(&self.split, s + 1)
            + at(&self.attached, s)
            + at(&self.attached, s + 1)
    }

    fn attach(&mut self, index: usize) {
        if self.attached.len() <= index {
            self.attached.resize(index + 1, 0);
        }
        self.attached[index] += 1;
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

    /// Makes the bottom of path vertex `index` (at rest position `p`, previous path vertex at
    /// `prev`, normal `n`; [`Groove::split`] of `index + 1` already recorded). The floor is
    /// coarser than the lips: the bottom of the previous path vertex is reused while the path
    /// stays within [`FLOOR_REACH`] of where that floor vertex was made and turns less than
    /// [`FLOOR_TURN_DEG`] from the way it was going then, so each path segment costs one wall
    /// triangle per lip plus a share of the floor (notes T4).
    ///
    /// Where the floor changes (a new floor vertex after one of this groove's), each lip gets a
    /// floor triangle at a path vertex next to the change. It goes where the two segments
    /// meeting at that vertex have room ([`Groove::load`] below 2): at `index` or at
    /// `index - 1`. Where neither has room (both ends split an edge), the old floor vertex is
    /// kept a little longer, up to [`FLOOR_STRETCH`] times the reach (and one segment more when
    /// the next path vertex is a vertex of the mesh).
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
        if self.owns_floor(index)
            && let Some((top, dir)) = self.floor_top
        {
            let floor_depth = self.start_depth(top);
            let far = |k: f64| {
                // A floor vertex made shallower near the start reaches as far as it is deep
                // (its fan would be as thin as a deep one's reaching several times as far);
                // the wait for room counts in blade depths.
                let depth = if k <= 1.0 { floor_depth } else { self.depth };
                floor_far(depth, (top, dir), &self.floor_run, p, prev, k)
            };
            if !far(1.0) {
                self.bottoms[index] = self.bottoms[index - 1];
                self.floor_run.push(p);
                return;
            }
            if self.load(index - 1) <= 1 && self.load(index) <= 1 {
                self.attach(index);
            } else if index >= 2 && self.load(index - 2) <= 1 && self.load(index - 1) <= 1 {
                self.attach(index - 1);
                self.floor_at_start.push(index - 1);
            } else if !far(FLOOR_STRETCH) || self.load(index) <= 1 {
                // Waiting; past the stretch only while the next path vertex (known) is a vertex
                // of the mesh, where the floor can change with room.
                self.bottoms[index] = self.bottoms[index - 1];
                self.floor_run.push(p);
                return;
            } else {
                // Over the budget rather than a wall too long and thin.
                self.attach(index);
            }
        }
        let b = mesh.push_floor_vertex(p - n * self.start_depth(p));
        self.bottoms[index] = b;
        self.bottom_vertices.push(b);
        self.floor_top = Some((p, p - prev));
        self.floor_run.clear();
    }

    /// Whether the bottom of path vertex `index` would continue this groove's own floor (not a
    /// crack tip's or another trench's).
    fn owns_floor(&self, index: usize) -> bool {
        index >= 1 && self.bottom_vertices.last() == self.bottoms.get(index - 1)
    }

    /// Whether path vertex `index` (at `p`, the one before at `prev`) is past where the floor
    /// should get a new vertex (see [`Groove::make_bottom`]).
    pub fn floor_due(&self, index: usize, p: DVec3, prev: DVec3) -> bool {
        self.owns_floor(index)
            && self.floor_top.is_some_and(|top| {
                let depth = self.start_depth(top.0);
                floor_far(depth, top, &self.floor_run, p, prev, 1.0)
            })
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
            split_tail: self
                .split
                .get(from.saturating_sub(1)..)
                .map(<[u8]>::to_vec)
                .unwrap_or_default(),
            attached_tail: self
                .attached
                .get(from.saturating_sub(1)..)
                .map(<[u8]>::to_vec)
                .unwrap_or_default(),
            floor_at_start: self.floor_at_start.clone(),
            floor_run: self.floor_run.clone(),
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
        self.floor_top = backup.floor_top;
        let keep = backup.from.saturating_sub(1);
        self.split.truncate(keep);
        self.split.extend_from_slice(&backup.split_tail);
        self.attached.truncate(keep);
        self.attached.extend_from_slice(&backup.attached_tail);
        self.floor_at_start = backup.floor_at_start;
        self.floor_run = backup.floor_run;
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
            // Where this segment's floor triangles sit (see `make_bottom`): at its first or its
            // last vertex on both lips; next to a junction, each lip's at its own end.
            let floor_at_a = if self.junctions.contains(&i) || self.junctions.contains(&(i + 1)) {
                None
            } else {
                Some(self.floor_at_start.contains(&i))
            };
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
                self.wall(mesh, lip_ab, ba, bb, floor_at_a),
                self.wall(mesh, lip_ba, bb, ba, floor_at_a.map(|a| !a)),
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

    /// Wall under boundary half-edge `lip` (`u → w`) with bottoms `bu` (of `u`) and `bw`; when
    /// the bottoms differ, the floor triangle (two bottoms, one lip vertex) sits at `u` when
    /// `floor_at_u` is `Some(true)`, else at `w`.
    /// Returns whether triangles were made (`Option` for the callers' failure path; a wall that
    /// duplicates an existing edge, where a cut doubled back into a trench, is caught by the
    /// step's local validation, which refuses the step).
    fn wall(
        &mut self,
        mesh: &mut DynMesh,
        lip: u32,
        bu: u32,
        bw: u32,
        floor_at_u: Option<bool>,
    ) -> Option<bool> {
        let (u, w) = (mesh.origin(lip), mesh.dest(lip));
        let bu = if mesh.same_point(bu, u) { u } else { bu };
        let bw = if mesh.same_point(bw, w) { w } else { bw };
        let mut tris = Vec::with_capacity(2);
        if bu != u && bw != w && bw != bu && floor_at_u == Some(true) {
            tris.push([w, u, bw]);
            tris.push([u, bu, bw]);
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
