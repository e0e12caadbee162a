//! Shared helpers of the boolean tests: cutter generators and the invariant checks.
#![allow(dead_code)]

use std::collections::HashMap;

use csg::{CutOptions, CutResult, DVec3, Mesh, TargetIndex, VertexSource};

pub use csg::cutcheck::volume;

pub fn area(m: &Mesh) -> f64 {
    m.area()
}

/// Welds bit-identical positions (so parts from different meshes share contour vertices).
pub fn weld(m: &Mesh) -> Mesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut remap = Vec::with_capacity(m.positions.len());
    for p in &m.positions {
        let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let id = *map.entry(key).or_insert_with(|| {
            positions.push(*p);
            (positions.len() - 1) as u32
        });
        remap.push(id);
    }
    Mesh {
        positions,
        triangles: m
            .triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .collect(),
    }
}

/// `Err` naming the first problem unless every edge has exactly two faces traversing it in
/// opposite directions and no triangle repeats an index (after welding by position).
pub fn check_closed_oriented(m: &Mesh) -> Result<(), String> {
    check_closed_by_source(&weld(m).triangles)
}

pub fn concat(a: &Mesh, b: &Mesh) -> Mesh {
    let mut m = a.clone();
    m.append(b);
    m
}

// The measure identities (area partition, volume identity, exact vertices) are the fuzz body's.
pub use csg::cutcheck::check_measures;

// The closedness-by-identity check and the face lists are the fuzz body's (one definition).
pub use csg::cutcheck::{closed_by_identity as check_closed_by_source, part_faces};

/// Checks every invariant of the robustness contract for a closed target on a result computed
/// with `merge_coincident = false` (closedness by symbolic identity) and the measures.
pub fn check_cut(target: &Mesh, result: &CutResult) -> Result<(), String> {
    check_measures(target, result)?;
    let n = target.positions.len() as u32;
    let (kept, _) = result.materialize_with_provenance(target);
    let src = |i: u32| {
        if i < n {
            VertexSource::Target(i)
        } else {
            VertexSource::New(i - n)
        }
    };
    let kept_faces: Vec<[VertexSource; 3]> = kept.triangles.iter().map(|t| t.map(src)).collect();
    let mut kw = kept_faces.clone();
    kw.extend(part_faces(&result.walls, false));
    check_closed_by_source(&kw).map_err(|e| format!("kept + walls: {e}"))?;
    let mut rw = part_faces(&result.removed, false);
    rw.extend(part_faces(&result.walls, true));
    check_closed_by_source(&rw).map_err(|e| format!("removed + reversed walls: {e}"))?;
    if result.walls.provenance.len() != result.walls.mesh.triangles.len()
        || result.removed.provenance.len() != result.removed.mesh.triangles.len()
        || result.kept_new_provenance.len() != result.kept_new_faces.len()
    {
        return Err("provenance length mismatch".into());
    }
    for c in &result.contours {
        if !c.closed {
            return Err("open contour on a closed target".into());
        }
    }
    if result.stats.status_fallbacks != 0 {
        return Err(format!(
            "{} status fallbacks",
            result.stats.status_fallbacks
        ));
    }
    if result.stats.triangulation_fallbacks != 0 {
        return Err(format!(
            "{} triangulation fallbacks",
            result.stats.triangulation_fallbacks
        ));
    }
    Ok(())
}

/// Checks the merged output (the default) by position: closed and oriented after welding.
pub fn check_cut_welded(target: &Mesh, result: &CutResult) -> Result<(), String> {
    check_measures(target, result)?;
    let kept = result.materialize(target);
    let kw = concat(&kept, &result.walls.mesh);
    check_closed_oriented(&kw).map_err(|e| format!("kept + walls: {e}"))?;
    let rw = concat(&result.removed.mesh, &result.walls.mesh.reversed());
    check_closed_oriented(&rw).map_err(|e| format!("removed + reversed walls: {e}"))?;
    Ok(())
}

/// Sample points of the membership check per cut (see [`check_membership`]).
pub const MEMBERSHIP_SAMPLES: usize = 160;

/// Cuts without merging coincident vertices and checks the contract; then cuts with the
/// default options and checks the measures and, by ray parity against the inputs, that sample
/// points land in kept or removed as they should ([`check_membership`]). Returns the default
/// result.
pub fn cut_checked(index: &TargetIndex, target: &Mesh, cutter: &Mesh) -> Result<CutResult, String> {
    let symbolic = csg::subtract_with(
        index,
        &[cutter],
        &CutOptions::default().with_merge_coincident(false),
    )
    .map_err(|e| format!("cut failed: {e}"))?;
    check_cut(target, &symbolic)?;
    let merged = csg::subtract(index, cutter).map_err(|e| format!("cut failed: {e}"))?;
    check_measures(target, &merged)?;
    check_membership(target, cutter, &merged, MEMBERSHIP_SAMPLES)?;
    Ok(merged)
}

/// A closed strip: a rectangle (`width` along `side`, `height` along `up`) swept along `path`,
/// as triangles; ends capped. Outward oriented when the path turns gently.
pub fn strip(path: &[DVec3], up: DVec3, width: f64, height: f64) -> Mesh {
    let n = path.len();
    let mut positions = Vec::new();
    for i in 0..n {
        let tangent = if i + 1 < n {
            path[i + 1] - path[i]
        } else {
            path[i] - path[i - 1]
        };
        let side = tangent.cross(up).normalize() * (width * 0.5);
        let u = up.normalize() * (height * 0.5);
        let c = path[i];
        // 0: -side -up, 1: +side -up, 2: +side +up, 3: -side +up
        positions.extend([c - side - u, c + side - u, c + side + u, c - side + u]);
    }
    let mut quads: Vec<[u32; 4]> = Vec::new();
    for i in 0..n as u32 - 1 {
        let (a, b) = (4 * i, 4 * (i + 1));
        for k in 0..4u32 {
            let k1 = (k + 1) % 4;
            quads.push([a + k, a + k1, b + k1, b + k]);
        }
    }
    let last = 4 * (n as u32 - 1);
    quads.push([0, 3, 2, 1]);
    quads.push([last, last + 1, last + 2, last + 3]);
    let mut triangles = Vec::new();
    for [a, b, c, d] in quads {
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    }
    let mut m = Mesh {
        positions,
        triangles,
    };
    if volume(&m) < 0.0 {
        m = m.reversed();
    }
    m
}

/// Snaps every coordinate to a multiple of `step`.
pub fn snapped(m: &Mesh, step: f64) -> Mesh {
    Mesh {
        positions: m
            .positions
            .iter()
            .map(|p| (*p / step).round() * step)
            .collect(),
        triangles: m.triangles.clone(),
    }
}

/// Cuts and checks (see [`cut_checked`]); panics with the problem.
pub fn cut_and_check(target: &Mesh, cutter: &Mesh) -> CutResult {
    let index = TargetIndex::build(target.clone()).expect("target index");
    cut_checked(&index, target, cutter).unwrap_or_else(|e| panic!("{e}"))
}

/// The volume a cut removes: the removed faces closed by the reversed walls.
pub fn removed_volume(result: &CutResult) -> f64 {
    volume(&concat(&result.removed.mesh, &result.walls.mesh.reversed()))
}

/// Panics unless the cut removed `expected` (a closed form of the placement) up to the placing
/// of the new vertices: they are exact on the boolean's lattice (steps of about 2⁻²⁷ of the
/// target's size), so a cutter face at a coordinate off the lattice (z = 1.9) moves by up to a
/// step (measured: 1.5e-9 of 0.05). Far below any wrong or missing piece.
pub fn assert_removes(result: &CutResult, expected: f64, what: &str) {
    let got = removed_volume(result);
    assert!(
        (got - expected).abs() <= 1e-7 * expected.abs().max(1.0),
        "{what}: removed volume {got}, expected {expected}"
    );
}

/// The volume of the tetrahedron `a b c d` (|det| / 6), for closed forms.
pub fn tetra_volume(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    (b - a).dot((c - a).cross(d - a)).abs() / 6.0
}

/// Directions of the parity rays: far from the axes and from each other, so grid-aligned meshes
/// rarely put an edge or a vertex on them.
const RAY_DIRECTIONS: [[f64; 3]; 6] = [
    [0.537_7, 0.284_3, 0.794_1],
    [-0.314_1, 0.827_1, 0.466_3],
    [0.712_9, -0.618_3, 0.331_7],
    [-0.261_8, -0.433_9, -0.862_0],
    [0.901_3, 0.123_7, -0.415_3],
    [-0.577_2, 0.158_3, -0.801_1],
];

/// Whether the ray from `p` along `dir` crosses the triangles of `m` an odd number of times
/// (Möller–Trumbore in `f64`, the triangles as a soup: orientation and welding play no part);
/// `None` when a crossing is too close to an edge or to `p` to trust.
fn ray_parity(m: &Mesh, p: DVec3, dir: DVec3, eps: f64) -> Option<bool> {
    let mut odd = false;
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let (e1, e2) = (b - a, c - a);
        let q = dir.cross(e2);
        let det = e1.dot(q);
        let scale = e1.length() * e2.length();
        if det.abs() <= 1e-12 * scale {
            // The ray runs (nearly) in the triangle's plane: trust it only when it is far from it.
            let n = e1.cross(e2);
            if n.length() > 0.0 && ((p - a).dot(n) / n.length()).abs() <= eps {
                return None;
            }
            continue;
        }
        let s = p - a;
        let u = s.dot(q) / det;
        let r = s.cross(e1);
        let v = dir.dot(r) / det;
        let t_hit = e2.dot(r) / det;
        let w = 1.0 - u - v;
        let margin = 1e-9;
        if u < -margin || v < -margin || w < -margin {
            continue;
        }
        if u <= margin || v <= margin || w <= margin || t_hit.abs() <= eps {
            return None;
        }
        if t_hit > 0.0 {
            odd = !odd;
        }
    }
    Some(odd)
}

/// Inside by ray parity (independent of the boolean): the first of [`RAY_DIRECTIONS`] whose ray
/// passes clear of every edge decides; `None` when none does.
pub fn inside_by_parity(m: &Mesh, p: DVec3, eps: f64) -> Option<bool> {
    RAY_DIRECTIONS
        .iter()
        .find_map(|d| ray_parity(m, p, DVec3::from(*d).normalize(), eps))
}

/// The distance from `p` to the triangle `a b c` (closest point by regions).
fn point_triangle_distance(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).length();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (a + ab * v + ac * w)).length()
}

fn near_surface(m: &Mesh, p: DVec3, eps: f64) -> bool {
    m.triangles.iter().any(|t| {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        point_triangle_distance(p, a, b, c) <= eps
    })
}

/// How many sample points [`check_membership`] classified, by where they belong.
#[derive(Clone, Copy, Debug, Default)]
pub struct Membership {
    /// Inside the target and the cutter: must be in removed + reversed walls only.
    pub removed: usize,
    /// Inside the target, outside the cutter: must be in kept + walls only.
    pub kept: usize,
    /// Outside the target: in neither.
    pub outside: usize,
}

/// The membership check, independent of the boolean's own bookkeeping: `samples` points, half
/// in the box where target and cutter overlap and half in the target's box, are classified by
/// ray parity against the *input* meshes (points within a small distance of either surface are
/// left out), and each must lie in the output solid it belongs to, again by ray parity: inside
/// target and cutter → inside removed + reversed walls and outside kept + walls; inside the
/// target only → the other way round; outside the target → outside both. A cut that removes
/// nothing, or the wrong piece, fails here even when every identity of the contract holds.
pub fn check_membership(
    target: &Mesh,
    cutter: &Mesh,
    result: &CutResult,
    samples: usize,
) -> Result<Membership, String> {
    let (tb, cb) = (bounds(target), bounds(cutter));
    let size = (tb.1 - tb.0).max_element();
    let eps = 1e-7 * size;
    let kept = concat(&result.materialize(target), &result.walls.mesh);
    let removed = concat(&result.removed.mesh, &result.walls.mesh.reversed());
    let (lo, hi) = (tb.0.max(cb.0), tb.1.min(cb.1));
    let overlap = (hi - lo).min_element() > 0.0;
    // A fixed seed drawn from the cutter, so a failure repeats.
    let mut seed = cutter
        .positions
        .iter()
        .fold(0x9e37_79b9_7f4a_7c15u64, |h, p| {
            (h ^ p.x.to_bits() ^ p.y.to_bits().rotate_left(21) ^ p.z.to_bits().rotate_left(42))
                .wrapping_mul(0x2545_f491_4f6c_dd1d)
        })
        | 1;
    let mut unit = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut counts = Membership::default();
    for k in 0..samples {
        let (a, b) = if overlap && k % 2 == 0 {
            (lo, hi)
        } else {
            (tb.0, tb.1)
        };
        let p = a + (b - a) * DVec3::new(unit(), unit(), unit());
        if near_surface(target, p, eps) || near_surface(cutter, p, eps) {
            continue;
        }
        let (Some(in_target), Some(in_cutter)) = (
            inside_by_parity(target, p, eps),
            inside_by_parity(cutter, p, eps),
        ) else {
            continue;
        };
        let (Some(in_kept), Some(in_removed)) = (
            inside_by_parity(&kept, p, eps),
            inside_by_parity(&removed, p, eps),
        ) else {
            continue;
        };
        let want_removed = in_target && in_cutter;
        let want_kept = in_target && !in_cutter;
        if in_removed != want_removed || in_kept != want_kept {
            return Err(format!(
                "point {p}: in target {in_target}, in cutter {in_cutter}, but in kept + walls \
                 {in_kept}, in removed + reversed walls {in_removed}"
            ));
        }
        if want_removed {
            counts.removed += 1;
        } else if want_kept {
            counts.kept += 1;
        } else {
            counts.outside += 1;
        }
    }
    Ok(counts)
}

fn bounds(m: &Mesh) -> (DVec3, DVec3) {
    m.positions.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}
