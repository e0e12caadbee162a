//! Opening the incision: a discontinuous free-form deformation (Sela, Schein, Elber 2004).
//!
//! The DFFD paper inserts a C⁻¹ knot along the incision so that a smooth displacement field
//! jumps across it. Here the field is evaluated directly at the vertices: a vertex at distance
//! `dist < r` from the cut (nearest point `c` on a cut segment, lateral direction
//! `l = n × tangent`) moves by `σ · (w / 2) · ramp · taper · φ(dist / r) · l`, where
//! - `σ = ±1` is the side of the cut the vertex is on (the discontinuity; a lip vertex takes the
//!   side of its own triangles, so the two lips of one slit move apart);
//! - `ramp = clamp((now - t_cut) / window, 0, 1)`: the trailing time window over which a freshly
//!   cut segment opens to its full width;
//! - `taper` goes from 0 at a crack tip to 1 one width away, so the lips meet at the tips;
//! - `φ(s) = (1 - s²)²` and `r = 3 w` (the support).
//!
//! Vertices outside the support, and groove bottoms, are never written: their display position
//! is their rest position bit for bit. The rest pose itself is never changed (cutting continues
//! in the rest pose).

use std::collections::{HashMap, HashSet, VecDeque};

use glam::DVec3;

use super::step::{CutSegment, Scalpel};

/// How the incision opens.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenOptions {
    /// Final gap between the lips (model units). Default `0` (closed).
    pub width: f64,
    /// Seconds over which a freshly cut segment opens to full width. Default `0.5`.
    pub window: f64,
}

impl Default for OpenOptions {
    fn default() -> Self {
        OpenOptions {
            width: 0.0,
            window: 0.5,
        }
    }
}

/// Support radius as a multiple of the width.
const SUPPORT: f64 = 3.0;

/// Display positions of `scalpel`'s mesh opened at tool time `now` (seconds): the rest
/// positions with [`open_displacements`] applied.
pub fn open_positions(scalpel: &Scalpel, options: &OpenOptions, now: f64) -> Vec<DVec3> {
    let mut out = scalpel.dyn_mesh().positions().to_vec();
    for (v, p) in open_displacements(scalpel, options, now) {
        out[v as usize] = p;
    }
    out
}

/// The vertices the opening moves at tool time `now`, with their display positions (sparse:
/// only vertices inside the support; cost proportional to them, not to the mesh).
pub fn open_displacements(scalpel: &Scalpel, options: &OpenOptions, now: f64) -> Vec<(u32, DVec3)> {
    let mesh = scalpel.dyn_mesh();
    let mut out = Vec::new();
    let w = options.width;
    let segments = scalpel.segments();
    if w.is_nan() || w <= 0.0 || segments.is_empty() {
        return out;
    }
    let r = SUPPORT * w;
    let nv = mesh.vertex_count() as u32;
    // Segment grid with cell size r.
    let cell = |p: DVec3| {
        let c = (p / r).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, s) in segments.iter().enumerate() {
        if s.a >= nv || s.b >= nv {
            continue;
        }
        let (lo, hi) = (cell(s.pa.min(s.pb)), cell(s.pa.max(s.pb)));
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    grid.entry((x, y, z)).or_default().push(i);
                }
            }
        }
    }
    // Crack tips: segment ends whose vertex was never copied.
    let mut tips: Vec<DVec3> = Vec::new();
    for s in segments {
        for (v, p) in [(s.a, s.pa), (s.b, s.pb)] {
            if v < nv && mesh.copies(v).is_empty() && !tips.contains(&p) {
                tips.push(p);
            }
        }
    }
    let fixed: HashSet<u32> = scalpel.fixed.iter().copied().collect();
    let nearest = |p: DVec3| -> Option<(f64, DVec3, &CutSegment)> {
        let c0 = cell(p);
        let mut best: Option<(f64, DVec3, &CutSegment)> = None;
        for x in c0.0 - 1..=c0.0 + 1 {
            for y in c0.1 - 1..=c0.1 + 1 {
                for z in c0.2 - 1..=c0.2 + 1 {
                    for &i in grid.get(&(x, y, z)).map(|v| v.as_slice()).unwrap_or(&[]) {
                        let s = &segments[i];
                        let ab = s.pb - s.pa;
                        let l2 = ab.length_squared();
                        let u = if l2 > 0.0 {
                            ((p - s.pa).dot(ab) / l2).clamp(0.0, 1.0)
                        } else {
                            0.0
                        };
                        let c = s.pa + ab * u;
                        let d = c.distance(p);
                        if best.is_none_or(|b| d < b.0) {
                            best = Some((d, c, s));
                        }
                    }
                }
            }
        }
        best
    };
    // Breadth-first over vertices from the cut's own vertices, within the support.
    let mut seen: HashSet<u32> = HashSet::new();
    let mut queue: VecDeque<u32> = VecDeque::new();
    for s in segments {
        for v in [s.a, s.b] {
            if v < nv {
                for c in std::iter::once(v).chain(mesh.copies(v)) {
                    if seen.insert(c) {
                        queue.push_back(c);
                    }
                }
            }
        }
    }
    let mut fan = Vec::new();
    while let Some(v) = queue.pop_front() {
        let p = mesh.pos(v);
        let Some((dist, c, s)) = nearest(p) else {
            continue;
        };
        if dist >= r {
            continue;
        }
        mesh.fan_into(v, &mut fan);
        let neighbours: Vec<u32> = fan
            .iter()
            .flat_map(|&h| [mesh.dest(h), mesh.origin(super::dyn_mesh::prev(h))])
            .collect();
        if !fixed.contains(&v) {
            let tangent = s.pb - s.pa;
            let lateral = s.normal.cross(tangent).normalize_or_zero();
            let mut off = (p - c).dot(lateral);
            if off.abs() <= 1e-9 * r {
                // On the cut: the side of the vertex's own triangles.
                let centroid: DVec3 = fan
                    .iter()
                    .map(|&h| {
                        let [a, b, cc] = mesh.triangles()[(h / 3) as usize].map(|x| mesh.pos(x));
                        (a + b + cc) / 3.0
                    })
                    .sum::<DVec3>()
                    / (fan.len().max(1) as f64);
                off = (centroid - c).dot(lateral);
            }
            let sigma = if off > 0.0 {
                1.0
            } else if off < 0.0 {
                -1.0
            } else {
                0.0
            };
            let ramp = if options.window > 0.0 {
                ((now - s.time) / options.window).clamp(0.0, 1.0)
            } else {
                1.0
            };
            let tip_dist = tips
                .iter()
                .map(|t| t.distance(c))
                .fold(f64::INFINITY, f64::min);
            let x = (tip_dist / w).min(1.0);
            let taper = x * x * (3.0 - 2.0 * x);
            let falloff = {
                let s2 = (dist / r) * (dist / r);
                (1.0 - s2) * (1.0 - s2)
            };
            let amount = sigma * 0.5 * w * ramp * taper * falloff;
            if amount != 0.0 {
                out.push((v, p + lateral * amount));
            }
        }
        for n in neighbours {
            if seen.insert(n) {
                queue.push_back(n);
            }
        }
    }
    out
}
