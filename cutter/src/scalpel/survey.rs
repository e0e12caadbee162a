//! Refusal survey: many random strokes on a mesh, counting the steps the scalpel refuses (the
//! element budget of a cut, [`element_budget`], lives in [`super::budget`]).
//!
//! A refused step (an error other than the blade being off the mesh) leaves the mesh unchanged
//! and the cut where it was: the user sees the blade lag until a later sample goes through. This
//! module measures how often that happens on random strokes so that tests can bound it and the
//! bench can print it. Strokes are deterministic (a fixed-seed generator): a sample path starts
//! at a random point of a random triangle, heads in a random tangent direction, turns by up to
//! ±25° per sample and advances 0.3–2 mean edge lengths per sample, each sample projected onto
//! the original surface (`csg::SpatialIndex`); a stroke is 8–40 samples long.

use std::collections::BTreeMap;

use glam::DVec3;

pub use super::budget::{ElementBudget, element_budget};
use super::{Scalpel, ScalpelError, ScalpelOptions};

/// What a survey counted.
#[derive(Clone, Debug, Default)]
pub struct RefusalSurvey {
    /// Strokes started (a refused `begin_stroke` counts as a stroke and a refused step).
    pub strokes: usize,
    /// Steps attempted (`begin_stroke` and `step` calls).
    pub steps: usize,
    /// Steps refused for a reason other than the blade being off the mesh.
    pub refused: usize,
    /// Steps refused because the sample was off the mesh (not counted in `refused`). Survey
    /// samples lie on the original surface, so these are steps where the tip could not follow
    /// the sample (it waits on a trench's lip, or the cut is stuck) until it was too far.
    pub off_mesh: usize,
    /// `refused` by cause ([`Scalpel::last_refusal`]).
    pub causes: BTreeMap<&'static str, usize>,
}

impl RefusalSurvey {
    /// Refused steps over attempted steps.
    pub fn rate(&self) -> f64 {
        self.refused as f64 / self.steps.max(1) as f64
    }

    /// Causes, most frequent first.
    pub fn top_causes(&self) -> Vec<(&'static str, usize)> {
        let mut v: Vec<_> = self.causes.iter().map(|(k, n)| (*k, *n)).collect();
        v.sort_by_key(|c| std::cmp::Reverse(c.1));
        v
    }
}

/// A small deterministic generator (xorshift64*), so that surveys repeat exactly.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Mean edge length of (up to the first 10,000 triangles of) `mesh`.
pub fn mean_edge(mesh: &csg::Mesh) -> f64 {
    let n = mesh.triangles.len().min(10_000);
    let mut sum = 0.0;
    for t in &mesh.triangles[..n] {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        sum += a.distance(b) + b.distance(c) + c.distance(a);
    }
    sum / (3 * n.max(1)) as f64
}

/// `count` random sample paths on `mesh` (see the module doc), with seed `seed`.
pub fn random_strokes(mesh: &csg::Mesh, count: usize, seed: u64) -> Vec<Vec<DVec3>> {
    if mesh.triangles.is_empty() {
        return Vec::new();
    }
    let index = csg::SpatialIndex::build(mesh);
    let h = mean_edge(mesh);
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let normal = |face: u32| {
        let [a, b, c] = mesh.triangles[face as usize].map(|i| mesh.positions[i as usize]);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let t = (rng.next() % mesh.triangles.len() as u64) as u32;
        let [a, b, c] = mesh.triangles[t as usize].map(|i| mesh.positions[i as usize]);
        let (mut u, mut v) = (rng.unit(), rng.unit());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        let mut p = a + (b - a) * u + (c - a) * v;
        let mut n = normal(t);
        if n == DVec3::ZERO {
            continue;
        }
        let (e1, e2) = (n.any_orthonormal_pair().0, n.any_orthonormal_pair().1);
        let angle = rng.range(0.0, std::f64::consts::TAU);
        let mut dir = e1 * angle.cos() + e2 * angle.sin();
        let len = 8 + (rng.next() % 33) as usize;
        let mut path = vec![p];
        while path.len() < len {
            let turn = rng.range(-25f64, 25.0).to_radians();
            dir = rotate(dir, n, turn);
            let target = p + dir * h * rng.range(0.3, 2.0);
            let Some(cp) = index.closest_point(mesh, target) else {
                break;
            };
            let moved = cp.point - p;
            n = normal(cp.face);
            // Keep heading along the surface (the new tangent part of the old direction).
            let tangent = (dir - n * dir.dot(n)).normalize_or_zero();
            if tangent == DVec3::ZERO || moved.length() < 1e-6 * h {
                break;
            }
            dir = tangent;
            p = cp.point;
            path.push(p);
        }
        if path.len() >= 2 {
            out.push(path);
        }
    }
    out
}

/// `v` rotated by `angle` about the unit axis `n` (Rodrigues).
fn rotate(v: DVec3, n: DVec3, angle: f64) -> DVec3 {
    let (s, c) = angle.sin_cos();
    v * c + n.cross(v) * s + n * n.dot(v) * (1.0 - c)
}

/// Cuts `strokes` into a fresh scalpel on `mesh` with `options` (one after the other, each
/// stroke ended before the next) and counts refused steps. Returns the scalpel for further
/// checks, or the error of [`Scalpel::new`].
pub fn survey(
    mesh: &csg::Mesh,
    options: ScalpelOptions,
    strokes: &[Vec<DVec3>],
) -> Result<(RefusalSurvey, Scalpel), ScalpelError> {
    let mut s = Scalpel::new(mesh, options)?;
    let mut r = RefusalSurvey::default();
    let count = |r: &mut RefusalSurvey, s: &Scalpel, res: Result<(), ScalpelError>| {
        r.steps += 1;
        match res {
            Ok(()) => {}
            Err(ScalpelError::OffMesh { .. }) => r.off_mesh += 1,
            Err(_) => {
                r.refused += 1;
                *r.causes.entry(s.last_refusal()).or_default() += 1;
            }
        }
    };
    for stroke in strokes {
        r.strokes += 1;
        let res = s.begin_stroke(stroke[0]).map(|_| ());
        let began = res.is_ok();
        count(&mut r, &s, res);
        if !began {
            continue;
        }
        for &q in &stroke[1..] {
            let res = s.step(q).map(|_| ());
            count(&mut r, &s, res);
        }
        if s.end_stroke().is_err() {
            // A loop that did not close: give up the stroke.
            s.undo_stroke();
        }
    }
    Ok((r, s))
}
