//! Quadric edge-collapse decimation of one closed label surface.
//!
//! A label surface has about two triangles per boundary voxel; a viewer or a cut often needs far
//! fewer. Each edge collapse merges its two vertices into one placed where the sum of their
//! quadrics (squared distances to the planes of the triangles around them, Garland & Heckbert)
//! is least, cheapest collapse first, until the asked fraction of the triangles is left.
//!
//! Why the result stays a closed, edge-manifold, outward surface: a collapse is made only when
//! - the two vertices share exactly the two neighbours opposite their edge (the link
//!   condition), so no edge gets a third triangle and no vertex a pinched fan, and each vertex
//!   keeps at least three neighbours;
//! - no triangle around the merged vertex turns over (its normal keeps pointing within about 37° of
//!   where it pointed before) or becomes a sliver.
//!
//! These checks are local; two distant sheets of a thin structure could still be pushed into each
//! other. So [`decimate_checked`] validates the decimated surface with the boolean's exact cutter
//! check, decimates less when it fails, and refuses in the end.

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

use glam::{DMat3, DVec3};

use crate::mesh::Mesh;

/// A triangle around the merged vertex must keep its normal within this cosine (about 37°) of
/// where it was.
const MIN_NORMAL_COSINE: f64 = 0.8;
/// A triangle whose area is less than this fraction of its longest side squared is a sliver.
const MIN_AREA_RATIO: f64 = 1e-3;

/// Symmetric 4×4 quadric `[A b; bᵀ c]`: the error at `p` is `pᵀAp + 2bᵀp + c`.
#[derive(Clone, Copy, Default)]
struct Quadric {
    a: DMat3,
    b: DVec3,
    c: f64,
}

impl Quadric {
    /// The squared distance to the plane through `p` with unit normal `n`, times `weight`.
    fn plane(n: DVec3, p: DVec3, weight: f64) -> Quadric {
        let d = -n.dot(p);
        Quadric {
            a: DMat3::from_cols(n * n.x, n * n.y, n * n.z) * weight,
            b: n * (d * weight),
            c: d * d * weight,
        }
    }

    fn add(&self, o: &Quadric) -> Quadric {
        Quadric {
            a: self.a + o.a,
            b: self.b + o.b,
            c: self.c + o.c,
        }
    }

    fn error(&self, p: DVec3) -> f64 {
        p.dot(self.a * p) + 2.0 * self.b.dot(p) + self.c
    }

    /// Where the error is least, when that point is well defined; else the best of the two ends
    /// and the midpoint.
    fn best(&self, pa: DVec3, pb: DVec3) -> (DVec3, f64) {
        let det = self.a.determinant();
        let scale = self.a.x_axis.length() + self.a.y_axis.length() + self.a.z_axis.length();
        if det.abs() > 1e-9 * scale.powi(3) {
            let p = -(self.a.inverse() * self.b);
            // The optimum of an almost flat neighbourhood can lie far away; keep to the edge's
            // surroundings.
            let reach = pa.distance(pb) * 2.0;
            if p.is_finite() && p.distance((pa + pb) * 0.5) <= reach {
                return (p, self.error(p));
            }
        }
        [pa, pb, (pa + pb) * 0.5]
            .into_iter()
            .map(|p| (p, self.error(p)))
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .expect("three candidates")
    }
}

/// A candidate collapse in the queue; stale when either vertex changed since it was queued.
struct Candidate {
    cost: f64,
    a: u32,
    b: u32,
    stamp: (u32, u32),
}

impl PartialEq for Candidate {
    fn eq(&self, o: &Candidate) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Candidate {}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Candidate) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Candidate {
    /// Cheapest first in a max-heap; ties by vertex ids so the order is deterministic.
    fn cmp(&self, o: &Candidate) -> Ordering {
        o.cost
            .total_cmp(&self.cost)
            .then_with(|| (o.a, o.b).cmp(&(self.a, self.b)))
    }
}

/// The mesh being decimated: positions, triangles (dead ones marked) and each vertex's
/// incident triangles.
struct Work {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    alive: Vec<bool>,
    around: Vec<Vec<u32>>,
    quadrics: Vec<Quadric>,
    stamp: Vec<u32>,
    live: usize,
    cells: Cells,
    /// Gap kept between triangles that share no vertex (a thousandth of the mean edge).
    margin: f64,
}

/// Triangles by the grid cells their boxes overlap, to find the triangles near a collapse.
/// Entries are added when a triangle moves and never removed: a query checks the triangles it
/// finds against their current corners, so a stale entry only costs a test.
struct Cells {
    size: f64,
    map: HashMap<[i32; 3], Vec<u32>>,
}

impl Cells {
    fn range(&self, lo: DVec3, hi: DVec3) -> ([i32; 3], [i32; 3]) {
        let cell = |p: DVec3| (p / self.size).floor().as_ivec3().to_array();
        (cell(lo), cell(hi))
    }

    fn insert(&mut self, t: u32, corners: [DVec3; 3]) {
        let (lo, hi) = bounds(corners, 0.0);
        let (a, b) = self.range(lo, hi);
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    self.map.entry([x, y, z]).or_default().push(t);
                }
            }
        }
    }

    /// Every triangle entered in a cell that the box `lo..hi` overlaps (some more than once).
    fn near(&self, lo: DVec3, hi: DVec3, out: &mut Vec<u32>) {
        let (a, b) = self.range(lo, hi);
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    if let Some(ts) = self.map.get(&[x, y, z]) {
                        out.extend_from_slice(ts);
                    }
                }
            }
        }
    }
}

/// The box of `corners` widened by `margin`.
fn bounds(corners: [DVec3; 3], margin: f64) -> (DVec3, DVec3) {
    let lo = corners[0].min(corners[1]).min(corners[2]);
    let hi = corners[0].max(corners[1]).max(corners[2]);
    (lo - margin, hi + margin)
}

/// Whether triangles `p` and `q` come within `margin` of each other (separating axis test:
/// both normals and the nine edge-pair directions; an axis that separates them by more than
/// `margin` proves them apart). Conservative: near-parallel edge pairs are skipped as axes, so it
/// may report a near miss as a touch, never a touch as a miss beyond rounding.
fn triangles_touch(p: [DVec3; 3], q: [DVec3; 3], margin: f64) -> bool {
    let edges = |t: [DVec3; 3]| [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let (ep, eq) = (edges(p), edges(q));
    let separated = |axis: DVec3| {
        let len = axis.length();
        if len < 1e-12 {
            return false;
        }
        let project = |t: [DVec3; 3]| {
            let d = t.map(|v| v.dot(axis) / len);
            (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
        };
        let ((p0, p1), (q0, q1)) = (project(p), project(q));
        p1 + margin < q0 || q1 + margin < p0
    };
    if separated(ep[0].cross(ep[1])) || separated(eq[0].cross(eq[1])) {
        return false;
    }
    for a in ep {
        for b in eq {
            if separated(a.cross(b)) {
                return false;
            }
        }
    }
    true
}

impl Work {
    fn new(mesh: &Mesh) -> Work {
        let n = mesh.positions.len();
        let mut around = vec![Vec::new(); n];
        let mut quadrics = vec![Quadric::default(); n];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
            let scaled = (b - a).cross(c - a);
            let area = scaled.length() * 0.5;
            let q = if area > 0.0 {
                Quadric::plane(scaled / (2.0 * area), a, area)
            } else {
                Quadric::default()
            };
            for &v in tri {
                around[v as usize].push(t as u32);
                quadrics[v as usize] = quadrics[v as usize].add(&q);
            }
        }
        let edge_sum: f64 = mesh
            .triangles
            .iter()
            .map(|t| mesh.positions[t[0] as usize].distance(mesh.positions[t[1] as usize]))
            .sum();
        let mean_edge = edge_sum / mesh.triangles.len().max(1) as f64;
        let mut cells = Cells {
            size: (mean_edge * 2.0).max(f64::MIN_POSITIVE),
            map: HashMap::new(),
        };
        for (t, tri) in mesh.triangles.iter().enumerate() {
            cells.insert(t as u32, tri.map(|v| mesh.positions[v as usize]));
        }
        Work {
            cells,
            margin: mean_edge * 1e-3,
            positions: mesh.positions.clone(),
            triangles: mesh.triangles.clone(),
            alive: vec![true; mesh.triangles.len()],
            around,
            quadrics,
            stamp: vec![0; n],
            live: mesh.triangles.len(),
        }
    }

    /// The other vertices of `v`'s triangles (each once).
    fn neighbours(&self, v: u32) -> Vec<u32> {
        let mut out: Vec<u32> = self.around[v as usize]
            .iter()
            .flat_map(|&t| self.triangles[t as usize])
            .filter(|&w| w != v)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    fn candidate(&self, a: u32, b: u32) -> Candidate {
        let (a, b) = (a.min(b), a.max(b));
        let q = self.quadrics[a as usize].add(&self.quadrics[b as usize]);
        let (_, cost) = q.best(self.positions[a as usize], self.positions[b as usize]);
        Candidate {
            cost,
            a,
            b,
            stamp: (self.stamp[a as usize], self.stamp[b as usize]),
        }
    }

    /// Collapses edge `a`–`b` into `a` at its best point, if the checks allow it.
    fn collapse(&mut self, a: u32, b: u32) -> bool {
        let (na, nb) = (self.neighbours(a), self.neighbours(b));
        let shared = na.iter().filter(|v| nb.binary_search(v).is_ok()).count();
        // Link condition; and neither end may drop below three neighbours.
        if shared != 2 || na.len() < 4 || nb.len() < 4 {
            return false;
        }
        let q = self.quadrics[a as usize].add(&self.quadrics[b as usize]);
        let (p, _) = q.best(self.positions[a as usize], self.positions[b as usize]);
        // Every triangle that stays must keep its orientation and shape.
        for &v in [a, b].iter() {
            for &t in &self.around[v as usize] {
                let tri = self.triangles[t as usize];
                if tri.contains(&a) && tri.contains(&b) {
                    continue;
                }
                let old = tri.map(|w| self.positions[w as usize]);
                let new = tri.map(|w| {
                    if w == a || w == b {
                        p
                    } else {
                        self.positions[w as usize]
                    }
                });
                let n_old = (old[1] - old[0]).cross(old[2] - old[0]);
                let n_new = (new[1] - new[0]).cross(new[2] - new[0]);
                let longest = (new[1] - new[0])
                    .length_squared()
                    .max((new[2] - new[1]).length_squared())
                    .max((new[0] - new[2]).length_squared());
                if n_new.length() * 0.5 < MIN_AREA_RATIO * longest
                    || n_new.dot(n_old) < MIN_NORMAL_COSINE * n_new.length() * n_old.length()
                {
                    return false;
                }
            }
        }
        if self.would_touch(a, b, p) {
            return false;
        }
        let from_b = std::mem::take(&mut self.around[b as usize]);
        for &t in &from_b {
            let tri = &mut self.triangles[t as usize];
            if tri.contains(&a) {
                self.alive[t as usize] = false;
                self.live -= 1;
                for &w in tri.iter() {
                    if w != b {
                        self.around[w as usize].retain(|&u| u != t);
                    }
                }
            } else {
                for w in tri.iter_mut() {
                    if *w == b {
                        *w = a;
                    }
                }
                self.around[a as usize].push(t);
            }
        }
        self.positions[a as usize] = p;
        self.quadrics[a as usize] = q;
        for k in 0..self.around[a as usize].len() {
            let t = self.around[a as usize][k];
            let corners = self.corners(t);
            self.cells.insert(t, corners);
        }
        self.stamp[a as usize] += 1;
        self.stamp[b as usize] += 1;
        true
    }

    fn corners(&self, t: u32) -> [DVec3; 3] {
        self.triangles[t as usize].map(|v| self.positions[v as usize])
    }

    /// Whether a triangle around the merged vertex at `p` would touch another triangle anywhere
    /// but along what they share: a triangle sharing no vertex must stay [`Work::margin`] away;
    /// of two sharing one vertex, neither may reach the other with its opposite side (two
    /// triangles sharing a side are left to the normal check).
    fn would_touch(&self, a: u32, b: u32, p: DVec3) -> bool {
        let merged = |w: u32| if w == b { a } else { w };
        let at = |w: u32| {
            if w == a {
                p
            } else {
                self.positions[w as usize]
            }
        };
        // The triangles that stay around the merged vertex, after the collapse.
        let mut fan: Vec<(u32, [u32; 3], [DVec3; 3])> = Vec::new();
        for &v in &[a, b] {
            for &t in &self.around[v as usize] {
                let tri = self.triangles[t as usize];
                if tri.contains(&a) && tri.contains(&b) {
                    continue;
                }
                let ids = tri.map(merged);
                fan.push((t, ids, ids.map(at)));
            }
        }
        let mut near = Vec::new();
        for (k, &(_, ids, corners)) in fan.iter().enumerate() {
            for &(_, other_ids, other) in &fan[k + 1..] {
                if self.pair_touches((ids, corners), (other_ids, other)) {
                    return true;
                }
            }
            let (lo, hi) = bounds(corners, self.margin);
            near.clear();
            self.cells.near(lo, hi, &mut near);
            for &u in &near {
                let tri = self.triangles[u as usize];
                if !self.alive[u as usize] || tri.contains(&a) || tri.contains(&b) {
                    continue;
                }
                if self.pair_touches((ids, corners), (tri, self.corners(u))) {
                    return true;
                }
            }
        }
        false
    }

    /// Whether two triangles (vertex ids and corners) touch beyond what they share.
    fn pair_touches(
        &self,
        (pi, p): ([u32; 3], [DVec3; 3]),
        (qi, q): ([u32; 3], [DVec3; 3]),
    ) -> bool {
        let shared: Vec<usize> = (0..3).filter(|&k| qi.contains(&pi[k])).collect();
        match shared[..] {
            [] => triangles_touch(p, q, self.margin),
            [k] => {
                let w = pi[k];
                let opposite = |ids: [u32; 3], c: [DVec3; 3]| {
                    let j = ids.iter().position(|&x| x == w).expect("shared vertex");
                    let (x, y) = (c[(j + 1) % 3], c[(j + 2) % 3]);
                    [x, y, y]
                };
                triangles_touch(opposite(pi, p), q, self.margin)
                    || triangles_touch(opposite(qi, q), p, self.margin)
            }
            _ => false,
        }
    }

    fn into_mesh(self) -> Mesh {
        let mut index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let mut triangles = Vec::with_capacity(self.live);
        for (t, tri) in self.triangles.iter().enumerate() {
            if !self.alive[t] {
                continue;
            }
            triangles.push(tri.map(|v| {
                let slot = &mut index[v as usize];
                if *slot == u32::MAX {
                    *slot = positions.len() as u32;
                    positions.push(self.positions[v as usize]);
                }
                *slot
            }));
        }
        Mesh {
            positions,
            triangles,
        }
    }
}

/// Tries of [`decimate_checked`]: each keeps half of what the previous one removed.
const TRIES: usize = 4;

/// [`decimate`], checked with the boolean's exact cutter check (closed, oriented, free of
/// self-intersection). When the check fails, decimates less (half of what was removed) and
/// checks again, [`TRIES`] times in all; then the last failure is the error.
pub fn decimate_checked(mesh: &Mesh, fraction: f64) -> Result<Mesh, String> {
    let mut keep = fraction;
    let mut failure = String::new();
    for _ in 0..TRIES {
        let out = decimate(mesh, keep);
        match crate::check_cutter(&out) {
            Ok(()) => return Ok(out),
            Err(e) => failure = e.to_string(),
        }
        keep = (1.0 + keep) * 0.5;
    }
    Err(failure)
}

/// `mesh` (closed, edge-manifold) with about `fraction` of its triangles kept (0 < fraction ≤ 1),
/// still closed and edge-manifold with its orientation; fewer collapses are made when the checks
/// refuse them.
pub fn decimate(mesh: &Mesh, fraction: f64) -> Mesh {
    let target = ((mesh.triangles.len() as f64 * fraction).ceil() as usize).max(4);
    if target >= mesh.triangles.len() {
        return mesh.clone();
    }
    let mut work = Work::new(mesh);
    let mut queue = BinaryHeap::with_capacity(mesh.triangles.len() * 3 / 2);
    for tri in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            // Each edge once: from the side where it runs upward.
            if a < b {
                queue.push(work.candidate(a, b));
            }
        }
    }
    while work.live > target {
        let Some(c) = queue.pop() else { break };
        if c.stamp != (work.stamp[c.a as usize], work.stamp[c.b as usize]) {
            continue;
        }
        if work.around[c.a as usize].is_empty() || work.around[c.b as usize].is_empty() {
            continue;
        }
        if !work.collapse(c.a, c.b) {
            continue;
        }
        // Only the edges at the merged vertex changed cost (its stamp moved on, so their old
        // entries are stale).
        for w in work.neighbours(c.a) {
            queue.push(work.candidate(c.a, w));
        }
    }
    work.into_mesh()
}
