//! A mutable triangle mesh for progressive cutting, with half-edge adjacency kept up to date by
//! every local edit and a journal that makes every edit undoable.
//!
//! Notation: half-edge `h = 3 t + k` is the edge of triangle `t` from corner `k` to corner
//! `(k + 1) % 3`; `twin[h]` is the half-edge of the neighbouring triangle that runs the other way.
//! A vertex's *fan* is its triangles in counter-clockwise order (seen from outside).
//!
//! Why a second representation next to [`csg::Mesh`]: a cut step must touch only its
//! neighbourhood. Rebuilding [`csg::EdgeAdjacency`] after each split is O(N) (see
//! `notes/scalpel.md` §2: 162 ms per rebuild at 1M triangles), so the scalpel keeps the same
//! positions and triangles arrays as `csg::Mesh` plus twin links it patches locally. Triangles are
//! only ever overwritten in place or appended; vertices only appended. So undo is: replay the
//! journal backwards, then truncate the arrays.

use glam::DVec3;

mod journal;
mod twins;
use journal::Change;
pub use journal::Mark;

/// `twin` value of a boundary half-edge.
pub const NO_TWIN: u32 = u32::MAX;
/// `twin` value of a half-edge whose edge has more than two faces or inconsistent orientation in
/// the input. The scalpel refuses to split, open or cross such edges.
pub const NONMANIFOLD: u32 = u32::MAX - 1;

/// True for a `twin` value that names a real half-edge.
#[inline]
pub fn is_real(h: u32) -> bool {
    h < NONMANIFOLD
}

/// The next half-edge of the same triangle.
#[inline]
pub fn next(h: u32) -> u32 {
    if h % 3 == 2 { h - 2 } else { h + 1 }
}

/// The previous half-edge of the same triangle.
#[inline]
pub fn prev(h: u32) -> u32 {
    if h.is_multiple_of(3) { h + 2 } else { h - 1 }
}

/// The mesh being cut.
#[derive(Clone, Debug, Default)]
pub struct DynMesh {
    /// Rest-pose vertex positions (the opening deformation never writes here). Vertices the cut
    /// did not create keep their input coordinates bit for bit, except those it moved onto its
    /// path (`scalpel::relocate`, by at most the snap radius along an edge of their fan).
    pub(crate) positions: Vec<DVec3>,
    /// Counter-clockwise triangles. Every index `< positions.len()`.
    pub(crate) triangles: Vec<[u32; 3]>,
    /// Twin of every half-edge; length `3 * triangles.len()`. [`NO_TWIN`] on the boundary,
    /// [`NONMANIFOLD`] on edges the input made non-manifold. For a real twin `g` of `h`:
    /// `twin[g] == h`, and `g` runs between the same two vertices in the opposite direction.
    pub(crate) twin: Vec<u32>,
    /// One outgoing half-edge of each vertex (`NO_TWIN` for a vertex no triangle uses). Length
    /// `positions.len()`.
    pub(crate) vert_he: Vec<u32>,
    /// Circular list of the coincident copies a cut made of one vertex (`next_copy[v] == v` for a
    /// vertex never copied). Copies are the two lips of a slit; they share their rest position.
    pub(crate) next_copy: Vec<u32>,
    /// Input vertices whose triangles form more than one fan (bow-ties): never cut through.
    pub(crate) singular: Vec<bool>,
    /// Groove floor vertices (bottoms made by the blade, below the surface). A triangle with a
    /// floor vertex is a groove wall: the surface walk never crosses it (the cross-cutting
    /// paper's "groove triangle" flag). Length `positions.len()`.
    pub(crate) floor: Vec<bool>,
    /// Wall triangles (groove or through-cut walls, below the surface): the surface walk never
    /// crosses them. Length `triangles.len()`; a triangle split keeps its flag in all parts.
    pub(crate) wall_tri: Vec<bool>,
    /// Undo log: the old value of every write since the oldest live [`Mark`].
    journal: Vec<Change>,
    /// The vertices every write (and every rollback) changed something of: its position, its
    /// copies, its fan, its existence. Read by the live opening ([`super::live_opening`]), which
    /// recomputes only around them; see [`DynMesh::edits_since`].
    edits: Vec<u32>,
    /// How many entries were dropped from the front of `edits` (it is emptied when it grows
    /// past `journal::EDITS_KEPT`; a reader behind that recomputes everything).
    edits_dropped: usize,
}

impl DynMesh {
    /// Builds the half-edge structure of `mesh` (O(N), once per model).
    pub fn from_mesh(mesh: &csg::Mesh) -> DynMesh {
        let nt = mesh.triangles.len();
        let nv = mesh.positions.len();
        let mut twin = twins::twins(&mesh.triangles);
        // A degenerate triangle (repeated index) makes all its edges unusable.
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                for k in 0..3 {
                    let h = 3 * t + k;
                    let g = twin[h];
                    if is_real(g) {
                        twin[g as usize] = NONMANIFOLD;
                    }
                    twin[h] = NONMANIFOLD;
                }
            }
        }
        let mut vert_he = vec![NO_TWIN; nv];
        let mut corner_count = vec![0u32; nv];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                vert_he[tri[k] as usize] = (3 * t + k) as u32;
                corner_count[tri[k] as usize] += 1;
            }
        }
        let mut dm = DynMesh {
            positions: mesh.positions.clone(),
            triangles: mesh.triangles.clone(),
            twin,
            vert_he,
            next_copy: (0..nv as u32).collect(),
            singular: vec![false; nv],
            floor: vec![false; nv],
            wall_tri: vec![false; nt],
            journal: Vec::new(),
            edits: Vec::new(),
            edits_dropped: 0,
        };
        // A vertex whose fan does not reach all its corners is a bow-tie.
        let mut fan = Vec::new();
        for v in 0..nv as u32 {
            if corner_count[v as usize] == 0 {
                continue;
            }
            dm.fan_into(v, &mut fan);
            if fan.len() != corner_count[v as usize] as usize {
                dm.singular[v as usize] = true;
            }
        }
        dm
    }

    /// Reserves room for `triangles` more triangles and as many vertices, so that steps never
    /// reallocate (a reallocation of 1M-element arrays costs tens of ms: notes §2).
    pub fn reserve(&mut self, triangles: usize) {
        self.triangles.reserve(triangles);
        self.twin.reserve(3 * triangles);
        self.positions.reserve(triangles);
        self.vert_he.reserve(triangles);
        self.next_copy.reserve(triangles);
        self.singular.reserve(triangles);
        self.floor.reserve(triangles);
        self.wall_tri.reserve(triangles);
    }

    /// The mesh as a [`csg::Mesh`] (rest pose).
    pub fn to_mesh(&self) -> csg::Mesh {
        csg::Mesh {
            positions: self.positions.clone(),
            triangles: self.triangles.clone(),
        }
    }

    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Twin of half-edge `h` (see the field's invariant).
    #[inline]
    pub fn twin(&self, h: u32) -> u32 {
        self.twin[h as usize]
    }

    /// Origin vertex of half-edge `h`.
    #[inline]
    pub fn origin(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][(h % 3) as usize]
    }

    /// Destination vertex of half-edge `h`.
    #[inline]
    pub fn dest(&self, h: u32) -> u32 {
        self.origin(next(h))
    }

    #[inline]
    pub fn pos(&self, v: u32) -> DVec3 {
        self.positions[v as usize]
    }

    /// The coincident copies of `v` other than `v` (slit lips), in ring order.
    pub fn copies(&self, v: u32) -> Vec<u32> {
        let mut out = Vec::new();
        let mut c = self.next_copy[v as usize];
        while c != v && out.len() < 64 {
            out.push(c);
            c = self.next_copy[c as usize];
        }
        out
    }

    /// Whether a cut made coincident copies of `v` ([`DynMesh::copies`] is not empty), without
    /// listing them.
    #[inline]
    pub fn has_copies(&self, v: u32) -> bool {
        self.next_copy[v as usize] != v
    }

    /// True when `a` and `b` are the same vertex or coincident copies of one.
    pub fn same_point(&self, a: u32, b: u32) -> bool {
        a == b || self.copies(a).contains(&b)
    }

    /// Outgoing half-edges of `v` in counter-clockwise order, starting at the clockwise-most one
    /// when the fan is open (so that the first triangle follows a boundary edge). Returns whether
    /// the fan closes around `v`.
    pub fn fan_into(&self, v: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        let start = self.vert_he[v as usize];
        if start == NO_TWIN {
            return false;
        }
        self.fan_from(start, out)
    }

    /// The fan (as in [`DynMesh::fan_into`]) that contains outgoing half-edge `start`.
    pub fn fan_from(&self, start: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        // Counter-clockwise from `start` (ccw(h) = twin(prev(h))): most fans close, and that
        // one turn is the whole fan.
        let mut x = start;
        loop {
            out.push(x);
            let g = self.twin[prev(x) as usize];
            if g == start {
                return true;
            }
            if !is_real(g) || out.len() > 4096 {
                break;
            }
            x = g;
        }
        // Open: the half-edges clockwise of `start` (cw(h) = next(twin(h))) up to the boundary
        // come first.
        let ccw = out.len();
        let mut h = start;
        loop {
            let g = self.twin[h as usize];
            if !is_real(g) || out.len() > 8192 {
                break;
            }
            h = next(g);
            out.push(h);
        }
        out[..ccw].reverse();
        out.reverse();
        false
    }

    /// Area-weighted normal of `v`'s fan (zero vector when degenerate).
    pub fn vertex_normal(&self, v: u32, scratch: &mut Vec<u32>) -> DVec3 {
        self.fan_into(v, scratch);
        let mut n = DVec3::ZERO;
        for &h in scratch.iter() {
            n += self.face_normal_scaled(h / 3);
        }
        n.normalize_or_zero()
    }

    /// Twice-area normal of triangle `t`.
    pub fn face_normal_scaled(&self, t: u32) -> DVec3 {
        let [a, b, c] = self.triangles[t as usize];
        let (a, b, c) = (self.pos(a), self.pos(b), self.pos(c));
        (b - a).cross(c - a)
    }

    /// Longest edge of triangle `t`.
    pub fn longest_edge(&self, t: u32) -> f64 {
        let [a, b, c] = self.triangles[t as usize];
        let (a, b, c) = (self.pos(a), self.pos(b), self.pos(c));
        a.distance(b).max(b.distance(c)).max(c.distance(a))
    }

    /// A half-edge of the edge between `a` and `b` (either direction), if that edge is in `a`'s fan.
    pub fn edge_between(&self, a: u32, b: u32, scratch: &mut Vec<u32>) -> Option<u32> {
        self.fan_into(a, scratch);
        for &h in scratch.iter() {
            if self.dest(h) == b {
                return Some(h);
            }
            let p = prev(h);
            if self.origin(p) == b {
                return Some(p);
            }
        }
        None
    }

    /// Appends a vertex (its own single copy).
    pub(crate) fn push_vertex(&mut self, p: DVec3) -> u32 {
        let v = self.positions.len() as u32;
        self.positions.push(p);
        self.vert_he.push(NO_TWIN);
        self.next_copy.push(v);
        self.singular.push(false);
        self.floor.push(false);
        self.log_edits(&[v]);
        v
    }

    /// Appends a groove floor vertex.
    pub(crate) fn push_floor_vertex(&mut self, p: DVec3) -> u32 {
        let v = self.push_vertex(p);
        self.floor[v as usize] = true;
        v
    }

    /// Whether `v` is a groove floor vertex.
    #[inline]
    pub fn is_floor(&self, v: u32) -> bool {
        self.floor[v as usize]
    }

    /// Whether triangle `t` is a wall (of a groove or a through-cut).
    #[inline]
    pub fn is_wall(&self, t: u32) -> bool {
        self.wall_tri[t as usize]
    }

    /// The surface (non-wall) part of `v`'s fan in counter-clockwise order, starting right after
    /// a wall or boundary, so that its first and last edges are lip edges when `v` is on a lip.
    /// Returns false when `v` has no surface triangle.
    pub fn surface_fan_into(&self, v: u32, out: &mut Vec<u32>) -> bool {
        let closed = self.fan_into(v, out);
        if !out.iter().any(|&h| self.is_wall(h / 3)) {
            return !out.is_empty();
        }
        let n = out.len();
        // The first surface triangle that follows a wall (cyclically when the fan is closed).
        let start = (0..n).find(|&i| {
            !self.is_wall(out[i] / 3)
                && if i == 0 {
                    !closed || self.is_wall(out[n - 1] / 3)
                } else {
                    self.is_wall(out[i - 1] / 3)
                }
        });
        let Some(start) = start else {
            out.clear();
            return false;
        };
        // The run from `start` to the next wall (around the end when the fan is closed), in
        // place.
        if closed {
            out.rotate_left(start);
        } else {
            out.drain(..start);
        }
        let end = out
            .iter()
            .position(|&h| self.is_wall(h / 3))
            .unwrap_or(out.len());
        out.truncate(end);
        !out.is_empty()
    }

    /// Area-weighted normal of `v`'s surface (non-wall) triangles.
    pub fn surface_normal(&self, v: u32, scratch: &mut Vec<u32>) -> DVec3 {
        self.surface_fan_into(v, scratch);
        let mut n = DVec3::ZERO;
        for &h in scratch.iter() {
            n += self.face_normal_scaled(h / 3);
        }
        n.normalize_or_zero()
    }

    /// Appends a triangle with boundary twins; callers link them.
    pub(crate) fn push_tri(&mut self, tri: [u32; 3]) -> u32 {
        let t = self.triangles.len() as u32;
        self.log_edits(&tri);
        self.triangles.push(tri);
        self.wall_tri.push(false);
        self.twin.extend_from_slice(&[NO_TWIN; 3]);
        t
    }

    /// Appends a wall triangle (see [`DynMesh::is_wall`]).
    pub(crate) fn push_wall_tri(&mut self, tri: [u32; 3]) -> u32 {
        let t = self.push_tri(tri);
        self.wall_tri[t as usize] = true;
        t
    }

    /// Links `h` with `g` both ways (`g` may be [`NO_TWIN`] or [`NONMANIFOLD`]: then only `h` is set).
    pub(crate) fn link(&mut self, h: u32, g: u32) {
        self.set_twin(h, g);
        if is_real(g) {
            self.set_twin(g, h);
        }
    }

    /// Points every corner's vertex of triangle `t` at its outgoing half-edge in `t`.
    pub(crate) fn refresh_vert_he(&mut self, t: u32) {
        let tri = self.triangles[t as usize];
        for k in 0..3 {
            self.set_vert_he(tri[k], 3 * t + k as u32);
        }
    }

    /// Adds `n` to the copy ring of `v`.
    pub(crate) fn join_copies(&mut self, v: u32, n: u32) {
        let after = self.next_copy[v as usize];
        self.set_next_copy(n, after);
        self.set_next_copy(v, n);
    }

    // ---------------------------------------------------------------------------------------
    // Local edits. Each keeps every invariant written on the fields.

    /// Splits the edge of half-edge `h` at `p` (both faces when the edge is interior). Returns the
    /// new vertex. Triangle count grows by 1 or 2; the old triangles are overwritten in place.
    pub(crate) fn split_edge(&mut self, h: u32, p: DVec3) -> u32 {
        let x = self.push_vertex(p);
        let g = self.twin[h as usize];
        let t = h / 3;
        let (a, b, c) = (self.origin(h), self.dest(h), self.origin(prev(h)));
        let e_bc = self.twin[next(h) as usize];
        let e_ca = self.twin[prev(h) as usize];
        // t = [a, x, c]; t2 = [x, b, c].
        self.set_tri(t, [a, x, c]);
        let t2 = self.push_tri([x, b, c]);
        self.wall_tri[t2 as usize] = self.wall_tri[t as usize];
        self.link(3 * t2 + 1, e_bc);
        self.link(3 * t + 2, e_ca);
        self.link(3 * t + 1, 3 * t2 + 2);
        if is_real(g) {
            let u = g / 3;
            let d = self.origin(prev(g));
            let e_ad = self.twin[next(g) as usize];
            let e_db = self.twin[prev(g) as usize];
            // u = [b, x, d]; u2 = [x, a, d].
            self.set_tri(u, [b, x, d]);
            let u2 = self.push_tri([x, a, d]);
            self.wall_tri[u2 as usize] = self.wall_tri[u as usize];
            self.link(3 * u2 + 1, e_ad);
            self.link(3 * u + 2, e_db);
            self.link(3 * u + 1, 3 * u2 + 2);
            self.link(3 * t, 3 * u2);
            self.link(3 * t2, 3 * u);
            self.refresh_vert_he(u);
            self.refresh_vert_he(u2);
        } else {
            self.set_twin(3 * t, NO_TWIN);
            self.set_twin(3 * t2, NO_TWIN);
        }
        self.refresh_vert_he(t);
        self.refresh_vert_he(t2);
        x
    }

    /// Splits triangle `t` at interior point `p` into three. Returns the new vertex.
    pub(crate) fn split_face(&mut self, t: u32, p: DVec3) -> u32 {
        let x = self.push_vertex(p);
        let [a, b, c] = self.triangles[t as usize];
        let e1 = self.twin[(3 * t + 1) as usize];
        let e2 = self.twin[(3 * t + 2) as usize];
        self.set_tri(t, [a, b, x]);
        let t2 = self.push_tri([b, c, x]);
        let t3 = self.push_tri([c, a, x]);
        self.wall_tri[t2 as usize] = self.wall_tri[t as usize];
        self.wall_tri[t3 as usize] = self.wall_tri[t as usize];
        self.link(3 * t2, e1);
        self.link(3 * t3, e2);
        self.link(3 * t + 1, 3 * t2 + 2);
        self.link(3 * t2 + 1, 3 * t3 + 2);
        self.link(3 * t3 + 1, 3 * t + 2);
        self.refresh_vert_he(t);
        self.refresh_vert_he(t2);
        self.refresh_vert_he(t3);
        x
    }

    /// Disconnects the two faces of interior edge `h` (a slit along it), then gives each vertex
    /// whose fan fell apart one copy per extra fan. Returns the vertices created.
    pub(crate) fn open_edge(&mut self, h: u32, created: &mut Vec<u32>) {
        let g = self.twin[h as usize];
        if !is_real(g) {
            return;
        }
        self.set_twin(h, NO_TWIN);
        self.set_twin(g, NO_TWIN);
        // At origin(h): the fans through h and through next(g). At origin(g): through g and next(h).
        self.separate_fans(h, next(g), created);
        self.separate_fans(g, next(h), created);
    }

    /// If outgoing half-edges `keep` and `other` (same origin vertex) are no longer in one fan,
    /// moves the fan of `other` to a new coincident copy of the vertex.
    fn separate_fans(&mut self, keep: u32, other: u32, created: &mut Vec<u32>) {
        let v = self.origin(keep);
        let mut fan = Vec::new();
        self.fan_from(keep, &mut fan);
        if fan.contains(&other) {
            return;
        }
        let mut other_fan = Vec::new();
        self.fan_from(other, &mut other_fan);
        let copy = self.push_vertex(self.positions[v as usize]);
        self.floor[copy as usize] = self.floor[v as usize];
        for &h in &other_fan {
            let t = h / 3;
            let mut tri = self.triangles[t as usize];
            tri[(h % 3) as usize] = copy;
            self.set_tri(t, tri);
        }
        self.set_vert_he(copy, other_fan[0]);
        self.set_vert_he(v, fan[0]);
        self.join_copies(v, copy);
        created.push(copy);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> csg::Mesh {
        csg::Mesh {
            positions: vec![
                DVec3::new(0., 0., 0.),
                DVec3::new(1., 0., 0.),
                DVec3::new(1., 1., 0.),
                DVec3::new(0., 1., 0.),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn twins_and_fans_of_a_quad() {
        let m = DynMesh::from_mesh(&quad());
        // Edge 0-2 is shared: half-edge 1 of tri 0 is 1->2, half-edge 2 is 2->0; tri 1 half-edge 0 is 0->2.
        assert_eq!(m.twin(2), 3);
        assert_eq!(m.twin(3), 2);
        assert_eq!(m.twin(0), NO_TWIN);
        let mut fan = Vec::new();
        let closed = m.fan_into(0, &mut fan);
        assert!(!closed);
        assert_eq!(fan.len(), 2);
        // Starts at the clockwise-most triangle: 0 -> 1 is a boundary edge at the start.
        assert_eq!(m.dest(fan[0]), 1);
    }

    /// Checks every fan of `m` against its definition: the half-edges leaving the vertex,
    /// each once, counter-clockwise; an open fan runs from boundary edge to boundary edge, a
    /// closed one starts at the half-edge asked for.
    fn check_fans(m: &DynMesh) {
        let mut fan = Vec::new();
        for h in 0..3 * m.triangles.len() as u32 {
            let v = m.origin(h);
            let closed = m.fan_from(h, &mut fan);
            assert!(fan.contains(&h), "half-edge {h}");
            assert!(fan.iter().all(|&g| m.origin(g) == v));
            let mut sorted = fan.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), fan.len(), "a half-edge twice around {v}");
            for w in fan.windows(2) {
                assert_eq!(m.twin[prev(w[0]) as usize], w[1], "not counter-clockwise");
            }
            let (first, last) = (fan[0], fan[fan.len() - 1]);
            if closed {
                assert_eq!(fan[0], h);
                assert_eq!(m.twin[prev(last) as usize], first);
            } else {
                assert!(!is_real(m.twin[first as usize]), "open fan starts inside");
                assert!(
                    !is_real(m.twin[prev(last) as usize]),
                    "open fan ends inside"
                );
            }
        }
    }

    #[test]
    fn fans_are_whole_ordered_and_start_at_the_boundary() {
        // Closed fans (a sphere), open ones (a grid's border), a vertex with two fans.
        check_fans(&DynMesh::from_mesh(&csg::testkit::geodesic_sphere(4, 1.0)));
        let n = 4u32;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| DVec3::new(i as f64, j as f64, 0.0)))
            .collect();
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let triangles = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                [[a, b, c], [a, c, d]]
            })
            .collect();
        let grid = DynMesh::from_mesh(&csg::Mesh {
            positions,
            triangles,
        });
        check_fans(&grid);
        let mut fan = Vec::new();
        assert!(grid.fan_into(id(2, 2), &mut fan) && fan.len() == 6);
        assert!(!grid.fan_into(id(2, 0), &mut fan) && fan.len() == 3);
        check_fans(&DynMesh::from_mesh(&bow_tie()));
    }

    #[test]
    fn split_and_rollback_restore_everything() {
        let mut m = DynMesh::from_mesh(&quad());
        let before = (
            m.positions.clone(),
            m.triangles.clone(),
            m.twin.clone(),
            m.vert_he.clone(),
        );
        let mark = m.mark();
        m.split_edge(2, DVec3::new(0.5, 0.5, 0.));
        m.split_face(0, DVec3::new(0.4, 0.2, 0.));
        assert_eq!(m.triangles.len(), 6);
        m.rollback(mark);
        assert_eq!(
            before,
            (
                m.positions.clone(),
                m.triangles.clone(),
                m.twin.clone(),
                m.vert_he.clone()
            )
        );
    }

    #[test]
    fn local_check_sees_what_a_step_broke() {
        let mut m = DynMesh::from_mesh(&quad());
        let mark = m.mark();
        m.split_edge(2, DVec3::new(0.5, 0.5, 0.));
        let touched = m.touched_since(mark);
        assert_eq!(touched, vec![0, 1, 2, 3]);
        assert!(m.local_check(&touched, false));
        // The quad has a boundary: not closed.
        assert!(!m.local_check(&touched, true));
        // A one-sided twin link is caught.
        let g = m.twin[1];
        m.twin[1] = NO_TWIN;
        assert!(is_real(g));
        assert!(m.local_problem(&touched, false).is_some());
        m.twin[1] = g;
        assert!(m.local_check(&touched, false));
        // So is a directed edge used twice.
        m.triangles[3] = m.triangles[0];
        assert!(m.local_problem(&touched, false).is_some());
    }

    /// Two triangles meeting only at vertex 0.
    fn bow_tie() -> csg::Mesh {
        csg::Mesh {
            positions: vec![
                DVec3::new(0., 0., 0.),
                DVec3::new(1., 0., 0.),
                DVec3::new(1., 1., 0.),
                DVec3::new(-1., 0., 0.),
                DVec3::new(-1., -1., 0.),
            ],
            triangles: vec![[0, 1, 2], [0, 3, 4]],
        }
    }

    #[test]
    fn bow_tie_is_singular() {
        let m = DynMesh::from_mesh(&bow_tie());
        assert!(m.singular[0]);
        assert!(!m.singular[1]);
    }
}
