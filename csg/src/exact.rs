//! Every exact predicate of the boolean, and its one tie-break rule.
//!
//! This is the only module that compares coordinates to decide topology. Everything else in the
//! boolean works on the signs returned here.
//!
//! # Notation
//! - `p, q, u, v, w`: target points (lattice coordinates, [`LPoint`]); never perturbed.
//! - `a, b, c`: cutter points; symbolically perturbed: `a' = a + δ`.
//! - `δ = (ε, ε², ε³)` for an infinitesimal `ε > 0`: **the whole cutter is translated by δ**.
//! - `orient3d(a, b, c, d) = det[b − a, c − a, d − a] = ((b − a) × (c − a)) · (d − a)`: positive
//!   when `d` lies on the side the normal of the counter-clockwise triangle `abc` points to.
//! - EF point: target edge `pq` ∩ plane of cutter face `abc`. FE point: cutter edge `ab` ∩ plane
//!   of target face `uvw`. Both are kept as homogeneous points whose coordinates are polynomials
//!   in ε ([`HPoint`]); they are never rounded before output.
//!
//! # The tie-break rule (Simulation of Simplicity on the cutter)
//! Every predicate is evaluated on the configuration where the cutter is translated by δ. Each
//! predicate value is a polynomial in ε; its sign is the sign of the first non-zero coefficient
//! (the unperturbed value first). For small enough ε the translated configuration is a real one,
//! so all signs are mutually consistent, and it is generic: no cutter vertex lies on the target,
//! no cutter edge meets a target edge, no cutter face is coplanar with a target face (δ · n ≠ 0
//! for every non-zero integer vector n). Consequences, all deterministic:
//! - a target vertex exactly on a cutter face counts as lying on the side `−n_f · δ` points to;
//! - coplanar faces separate along the sign of `n · δ`, i.e. of the first non-zero component of
//!   the normal (x first, then y, then z);
//! - a zero-area face (zero normal) is never crossed through its interior; its edges still are.
//!
//! Exact arithmetic: lattice coordinates have at most [`crate::lattice::LATTICE_BITS`] bits, so
//! `orient3d` fits `i128` (≤ 2⁹⁰), homogeneous coordinates fit `i128` (≤ 2¹²¹), and the 2-D
//! predicates on homogeneous points fit 512-bit integers (≤ 2³⁴⁰, `bnum`). A floating-point
//! filter answers first; the exact path runs only when the filter cannot decide.

use std::cmp::Ordering;

use bnum::cast::As;
use bnum::types::I512;

/// A point on the integer lattice (see [`crate::lattice`]).
pub type LPoint = [i64; 3];

/// A sign: −1, 0 or +1.
pub type Sign = i8;

/// `orient3d(a, b, c, d) = det[b − a, c − a, d − a]`, exact (lattice inputs).
#[inline]
pub fn orient3d(a: &LPoint, b: &LPoint, c: &LPoint, d: &LPoint) -> i128 {
    let ba = sub(b, a);
    let ca = sub(c, a);
    let da = sub(d, a);
    let n = cross(&ba, &ca);
    n[0] * da[0] + n[1] * da[1] + n[2] * da[2]
}

/// Exact unnormalized normal `(b − a) × (c − a)` of a triangle (zero for a degenerate one).
#[inline]
pub fn normal(a: &LPoint, b: &LPoint, c: &LPoint) -> [i128; 3] {
    cross(&sub(b, a), &sub(c, a))
}

#[inline]
fn sub(a: &LPoint, b: &LPoint) -> [i128; 3] {
    [
        (a[0] - b[0]) as i128,
        (a[1] - b[1]) as i128,
        (a[2] - b[2]) as i128,
    ]
}

#[inline]
fn cross(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn sign_i128(x: i128) -> Sign {
    x.signum() as Sign
}

/// `orient3d` of four points of which those flagged in `cutter` are translated by δ, as the
/// polynomial `[value, coefficient of ε, of ε², of ε³]`.
///
/// The value is affine in δ (two translated columns never multiply each other), so the
/// coefficient of `δ_k` is the value with the cutter points moved by the unit vector `e_k`
/// minus the unperturbed value: exact and obviously right.
pub fn orient3d_poly(pts: [&LPoint; 4], cutter: [bool; 4]) -> [i128; 4] {
    let d0 = orient3d(pts[0], pts[1], pts[2], pts[3]);
    let mut out = [d0, 0, 0, 0];
    for k in 0..3 {
        let moved: [LPoint; 4] = std::array::from_fn(|i| {
            let mut p = *pts[i];
            if cutter[i] {
                p[k] += 1;
            }
            p
        });
        out[k + 1] = orient3d(&moved[0], &moved[1], &moved[2], &moved[3]) - d0;
    }
    out
}

/// Sign of `orient3d` under the tie-break rule (cutter points flagged in `cutter` translated by
/// δ). Zero only when the polynomial vanishes identically (e.g. a zero-area cutter face as the
/// plane, or all four points from one mesh and coplanar).
pub fn orient3d_sos(pts: [&LPoint; 4], cutter: [bool; 4]) -> Sign {
    let d0 = orient3d(pts[0], pts[1], pts[2], pts[3]);
    if d0 != 0 {
        return sign_i128(d0);
    }
    let poly = orient3d_poly(pts, cutter);
    poly.iter()
        .map(|&c| sign_i128(c))
        .find(|&s| s != 0)
        .unwrap_or(0)
}

/// Side of target point `p` relative to the perturbed plane of cutter face `abc`: +1 above
/// (where the face normal points: outside a closed outward cutter), −1 below.
#[inline]
pub fn target_point_vs_cutter_plane(a: &LPoint, b: &LPoint, c: &LPoint, p: &LPoint) -> Sign {
    orient3d_sos([a, b, c, p], [true, true, true, false])
}

/// Side of perturbed cutter point `a'` relative to the plane of target face `uvw`.
#[inline]
pub fn cutter_point_vs_target_plane(u: &LPoint, v: &LPoint, w: &LPoint, a: &LPoint) -> Sign {
    orient3d_sos([u, v, w, a], [false, false, false, true])
}

/// Sign of `orient3d(p, q, a', b')` for target edge `pq` and perturbed cutter edge `a'b'`.
/// The same polynomial decides "EF" and "FE" crossings, which is why they always agree.
#[inline]
pub fn target_edge_vs_cutter_edge(p: &LPoint, q: &LPoint, a: &LPoint, b: &LPoint) -> Sign {
    orient3d_sos([p, q, a, b], [false, false, true, true])
}

/// The plane of a cutter face, precomputed for the broad phase: `value(p) = n · (p − a)`, which
/// is exactly `orient3d(a, b, c, p)` (unperturbed).
#[derive(Clone, Copy, Debug)]
pub struct CutterPlane {
    n: [i128; 3],
    d: i128,
}

impl CutterPlane {
    /// The plane of cutter face `abc`.
    pub fn new(a: &LPoint, b: &LPoint, c: &LPoint) -> CutterPlane {
        let n = normal(a, b, c);
        let d = n[0] * a[0] as i128 + n[1] * a[1] as i128 + n[2] * a[2] as i128;
        CutterPlane { n, d }
    }

    /// Side of target point `p` under the tie-break rule: the same sign as
    /// [`target_point_vs_cutter_plane`], cheaper when the point is off the plane.
    #[inline]
    pub fn side(&self, a: &LPoint, b: &LPoint, c: &LPoint, p: &LPoint) -> Sign {
        let v =
            self.n[0] * p[0] as i128 + self.n[1] * p[1] as i128 + self.n[2] * p[2] as i128 - self.d;
        if v != 0 {
            sign_i128(v)
        } else {
            target_point_vs_cutter_plane(a, b, c, p)
        }
    }
}

/// Does target segment `pq` cross the interior of perturbed cutter triangle `abc`? Returns the
/// side of `p` (+1 above, −1 below the cutter face) when it does.
pub fn target_edge_crosses_cutter_face(
    p: &LPoint,
    q: &LPoint,
    a: &LPoint,
    b: &LPoint,
    c: &LPoint,
) -> Option<Sign> {
    let sp = target_point_vs_cutter_plane(a, b, c, p);
    let sq = target_point_vs_cutter_plane(a, b, c, q);
    if sp == 0 || sq == 0 || sp == sq {
        return None;
    }
    let e1 = target_edge_vs_cutter_edge(p, q, a, b);
    if e1 == 0 {
        return None;
    }
    let e2 = target_edge_vs_cutter_edge(p, q, b, c);
    if e2 != e1 {
        return None;
    }
    let e3 = target_edge_vs_cutter_edge(p, q, c, a);
    if e3 != e1 {
        return None;
    }
    Some(sp)
}

/// Does perturbed cutter segment `a'b'` cross the interior of target triangle `uvw`? Returns the
/// side of `a'` (+1 above, −1 below the target face) when it does.
pub fn cutter_edge_crosses_target_face(
    a: &LPoint,
    b: &LPoint,
    u: &LPoint,
    v: &LPoint,
    w: &LPoint,
) -> Option<Sign> {
    let sa = cutter_point_vs_target_plane(u, v, w, a);
    let sb = cutter_point_vs_target_plane(u, v, w, b);
    if sa == 0 || sb == 0 || sa == sb {
        return None;
    }
    // orient3d(u, v, a', b') has the sign of orient3d(a', b', u, v) (even permutation).
    let e1 = target_edge_vs_cutter_edge(u, v, a, b);
    if e1 == 0 {
        return None;
    }
    let e2 = target_edge_vs_cutter_edge(v, w, a, b);
    if e2 != e1 {
        return None;
    }
    let e3 = target_edge_vs_cutter_edge(w, u, a, b);
    if e3 != e1 {
        return None;
    }
    Some(sa)
}

/// Does an unperturbed segment `pq` cross the interior of perturbed cutter triangle `abc`
/// (used for the ray-parity inside test of a target point; same predicate as EF)?
#[inline]
pub fn segment_crosses_cutter_face(
    p: &LPoint,
    q: &LPoint,
    a: &LPoint,
    b: &LPoint,
    c: &LPoint,
) -> bool {
    target_edge_crosses_cutter_face(p, q, a, b, c).is_some()
}

/// Does point `p` lie on the closed triangle `abc` (exact, unperturbed)? A zero-area triangle
/// holds no point here (its points lie on the neighbouring faces of a closed surface).
pub fn point_on_triangle(p: &LPoint, a: &LPoint, b: &LPoint, c: &LPoint) -> bool {
    if orient3d(a, b, c, p) != 0 {
        return false;
    }
    let Some((axis, _)) = projection(&normal(a, b, c)) else {
        return false;
    };
    let (i, j) = plane_axes(axis);
    let pr = |q: &LPoint| [q[i] as i128, q[j] as i128];
    let (pp, pa, pb, pc) = (pr(p), pr(a), pr(b), pr(c));
    let s = [
        orient2d_int(pa, pb, pp).signum(),
        orient2d_int(pb, pc, pp).signum(),
        orient2d_int(pc, pa, pp).signum(),
    ];
    !(s.contains(&1) && s.contains(&-1))
}

/// 2-D orientation of integer points (exact).
#[inline]
fn orient2d_int(a: [i128; 2], b: [i128; 2], c: [i128; 2]) -> i128 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Do the closed segment `pq` and the closed triangle `abc` share a point? Unperturbed (used to
/// validate the cutter, where touching counts as intersecting). A zero-area triangle meets
/// nothing.
pub fn segment_meets_triangle(p: &LPoint, q: &LPoint, a: &LPoint, b: &LPoint, c: &LPoint) -> bool {
    let sp = sign_i128(orient3d(a, b, c, p));
    let sq = sign_i128(orient3d(a, b, c, q));
    if sp * sq > 0 {
        return false;
    }
    if sp == 0 && sq == 0 {
        // Coplanar: 2-D test in the dominant projection.
        let Some((axis, _)) = projection(&normal(a, b, c)) else {
            return false;
        };
        let (i, j) = plane_axes(axis);
        let pr = |x: &LPoint| [x[i] as i128, x[j] as i128];
        let (p2, q2) = (pr(p), pr(q));
        let tri = [pr(a), pr(b), pr(c)];
        let area = orient2d_int(tri[0], tri[1], tri[2]).signum();
        let inside = |x: [i128; 2]| {
            (0..3).all(|k| orient2d_int(tri[k], tri[(k + 1) % 3], x).signum() * area >= 0)
        };
        if inside(p2) || inside(q2) {
            return true;
        }
        return (0..3).any(|k| {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            let o1 = orient2d_int(p2, q2, u).signum();
            let o2 = orient2d_int(p2, q2, v).signum();
            let o3 = orient2d_int(u, v, p2).signum();
            let o4 = orient2d_int(u, v, q2).signum();
            o1 * o2 <= 0
                && o3 * o4 <= 0
                && !(o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0 && {
                    // Collinear: overlap along the line?
                    let k = if u[0] != v[0] { 0 } else { 1 };
                    let (lo, hi) = (u[k].min(v[k]), u[k].max(v[k]));
                    p2[k].max(q2[k]) < lo || p2[k].min(q2[k]) > hi
                })
        });
    }
    let s1 = sign_i128(orient3d(p, q, a, b));
    let s2 = sign_i128(orient3d(p, q, b, c));
    let s3 = sign_i128(orient3d(p, q, c, a));
    (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)
}

// ---------------------------------------------------------------------------------------------
// Homogeneous points with coordinates polynomial in ε.
// ---------------------------------------------------------------------------------------------

/// A polynomial `c0 + c1 ε + c2 ε² + c3 ε³` (affine in δ).
pub type EpsPoly = [i128; 4];

/// A point `x / w` whose homogeneous coordinates are polynomials in ε. Invariant: the leading
/// (first non-zero) coefficient of `w` is positive, so `w > 0` for small ε.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HPoint {
    /// Homogeneous coordinates x, y, z.
    pub x: [EpsPoly; 3],
    /// Homogeneous weight; positive for small ε.
    pub w: EpsPoly,
}

fn poly_sign(p: &[i128]) -> Sign {
    p.iter()
        .map(|&c| sign_i128(c))
        .find(|&s| s != 0)
        .unwrap_or(0)
}

impl HPoint {
    /// An (unperturbed) target vertex.
    pub fn target_vertex(p: &LPoint) -> HPoint {
        HPoint {
            x: std::array::from_fn(|i| [p[i] as i128, 0, 0, 0]),
            w: [1, 0, 0, 0],
        }
    }

    /// A cutter vertex, translated by δ.
    pub fn cutter_vertex(a: &LPoint) -> HPoint {
        HPoint {
            x: std::array::from_fn(|i| {
                let mut c = [a[i] as i128, 0, 0, 0];
                c[i + 1] = 1;
                c
            }),
            w: [1, 0, 0, 0],
        }
    }

    /// Target edge `pq` ∩ plane of perturbed cutter face `abc` (the caller has checked that the
    /// edge crosses the plane): `x = p·d_q − q·d_p`, `w = d_q − d_p`, `d = orient3d(a', b', c', ·)`.
    pub fn edge_face(p: &LPoint, q: &LPoint, a: &LPoint, b: &LPoint, c: &LPoint) -> HPoint {
        let dp = orient3d_poly([a, b, c, p], [true, true, true, false]);
        let dq = orient3d_poly([a, b, c, q], [true, true, true, false]);
        let x = std::array::from_fn(|i| {
            std::array::from_fn(|k| p[i] as i128 * dq[k] - q[i] as i128 * dp[k])
        });
        let w = std::array::from_fn(|k| dq[k] - dp[k]);
        HPoint { x, w }.normalized()
    }

    /// Perturbed cutter edge `a'b'` ∩ plane of target face `uvw` (the caller has checked that the
    /// edge crosses the plane): with `n = (v − u) × (w − u)` and `N = n · (b − a)`,
    /// `x = (a + δ) N + (b − a)(n · (u − a) − n · δ)`, `w = N`.
    pub fn face_edge(a: &LPoint, b: &LPoint, u: &LPoint, v: &LPoint, w: &LPoint) -> HPoint {
        let n = normal(u, v, w);
        let ba = sub(b, a);
        let ua = sub(u, a);
        let big_n = n[0] * ba[0] + n[1] * ba[1] + n[2] * ba[2];
        let s0 = n[0] * ua[0] + n[1] * ua[1] + n[2] * ua[2];
        let x = std::array::from_fn(|i| {
            let mut c = [a[i] as i128 * big_n + ba[i] * s0, 0, 0, 0];
            for j in 0..3 {
                c[j + 1] = if i == j { big_n } else { 0 } - ba[i] * n[j];
            }
            c
        });
        HPoint {
            x,
            w: [big_n, 0, 0, 0],
        }
        .normalized()
    }

    fn normalized(mut self) -> HPoint {
        if poly_sign(&self.w) < 0 {
            for c in self.x.iter_mut().chain(std::iter::once(&mut self.w)) {
                for k in c.iter_mut() {
                    *k = -*k;
                }
            }
        }
        self
    }

    /// The unperturbed homogeneous coordinates `(x_i, x_j, w)` of the projection dropping `axis`,
    /// rounded to `f64` (input of [`orient2d_filter`]).
    #[inline]
    pub fn approx(&self, axis: usize) -> [f64; 3] {
        let (i, j) = plane_axes(axis);
        [self.x[i][0] as f64, self.x[j][0] as f64, self.w[0] as f64]
    }

    /// The unperturbed point (ε → 0) when it is exactly a lattice point (a contact at an input
    /// vertex in a degenerate configuration), else `None`.
    pub fn limit_lattice_point(&self) -> Option<LPoint> {
        let k = self.w.iter().position(|&c| c != 0)?;
        let w = self.w[k];
        let mut out = [0i64; 3];
        for i in 0..3 {
            let x = self.x[i][k];
            if x % w != 0 {
                return None;
            }
            out[i] = i64::try_from(x / w).ok()?;
        }
        Some(out)
    }

    /// The unperturbed point (ε → 0) in lattice units, rounded once per coordinate. When the
    /// constant weight vanishes (an edge lying in the plane, resolved by the tie-break), the
    /// limit is taken at the first order whose weight is non-zero.
    pub fn limit(&self) -> [f64; 3] {
        let k = self.w.iter().position(|&c| c != 0).unwrap_or(0);
        let w = self.w[k] as f64;
        std::array::from_fn(|i| {
            // The coordinates vanish below order k as well (the point is finite).
            self.x[i][k] as f64 / w
        })
    }
}

/// The two in-plane axes of a projection that drops `axis` (cyclic, so orientation is kept
/// when the dropped normal component is positive).
#[inline]
pub fn plane_axes(axis: usize) -> (usize, usize) {
    ((axis + 1) % 3, (axis + 2) % 3)
}

/// The projection of a face with exact normal `n`: the dominant axis and the sign of that
/// normal component (multiply [`orient2d`] by it to get "counter-clockwise seen from the normal").
/// `None` for a zero normal.
pub fn projection(n: &[i128; 3]) -> Option<(usize, Sign)> {
    let abs = [n[0].abs(), n[1].abs(), n[2].abs()];
    let axis = if abs[0] >= abs[1] && abs[0] >= abs[2] {
        0
    } else if abs[1] >= abs[2] {
        1
    } else {
        2
    };
    if n[axis] == 0 {
        None
    } else {
        Some((axis, sign_i128(n[axis])))
    }
}

/// Zero (bnum 0.14 keeps its `ZERO` constant private).
const W0: I512 = I512::from_bytes([0; 64]);

#[inline]
fn wide(x: i128) -> I512 {
    x.as_::<I512>()
}

fn wide_poly_mul(a: &[I512], b: &[I512]) -> Vec<I512> {
    let mut out = vec![W0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        if *x == W0 {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            out[i + j] += *x * *y;
        }
    }
    out
}

fn wide_poly_add(acc: &mut Vec<I512>, b: &[I512], negate: bool) {
    if acc.len() < b.len() {
        acc.resize(b.len(), W0);
    }
    for (i, y) in b.iter().enumerate() {
        if negate {
            acc[i] -= *y;
        } else {
            acc[i] += *y;
        }
    }
}

fn wide_sign(p: &[I512]) -> Sign {
    for c in p {
        if *c > W0 {
            return 1;
        }
        if *c < W0 {
            return -1;
        }
    }
    0
}

fn to_wide(p: &EpsPoly) -> [I512; 4] {
    p.map(wide)
}

/// Relative error bound of the floating-point filters: generous (the true bound is about
/// 10·2⁻⁵³); a tighter bound would only save a few exact evaluations.
const FILTER_EPS: f64 = 1e-12;

/// 2-D orientation of three homogeneous points projected by dropping `axis`: the sign of
/// `det[[x_i, x_j, w] per point]` with `(i, j) = plane_axes(axis)`, under the tie-break rule.
/// Positive means counter-clockwise in the projection (multiply by the face's projection sign).
pub fn orient2d(p: &HPoint, q: &HPoint, r: &HPoint, axis: usize) -> Sign {
    // Stage 1: floating-point filter on the unperturbed values.
    if let Some(s) = orient2d_filter(&p.approx(axis), &q.approx(axis), &r.approx(axis)) {
        return s;
    }
    orient2d_exact(p, q, r, axis)
}

/// The floating-point filter of [`orient2d`] on [`HPoint::approx`] values: the sign when it is
/// certain, `None` when the exact evaluation is needed.
#[inline]
pub fn orient2d_filter(p: &[f64; 3], q: &[f64; 3], r: &[f64; 3]) -> Option<Sign> {
    let [x1, y1, w1] = *p;
    let [x2, y2, w2] = *q;
    let [x3, y3, w3] = *r;
    let t1 = x1 * (y2 * w3 - y3 * w2);
    let t2 = x2 * (y1 * w3 - y3 * w1);
    let t3 = x3 * (y1 * w2 - y2 * w1);
    let det = t1 - t2 + t3;
    let perm = x1.abs() * ((y2 * w3).abs() + (y3 * w2).abs())
        + x2.abs() * ((y1 * w3).abs() + (y3 * w1).abs())
        + x3.abs() * ((y1 * w2).abs() + (y2 * w1).abs());
    if det.abs() > perm * FILTER_EPS {
        Some(if det > 0.0 { 1 } else { -1 })
    } else {
        None
    }
}

/// [`orient2d`] without the filter (the exact stages only).
pub fn orient2d_exact(p: &HPoint, q: &HPoint, r: &HPoint, axis: usize) -> Sign {
    let (i, j) = plane_axes(axis);
    // Stage 2: exact unperturbed determinant.
    let c = |v: i128| wide(v);
    let d0 = c(p.x[i][0]) * (c(q.x[j][0]) * c(r.w[0]) - c(r.x[j][0]) * c(q.w[0]))
        - c(q.x[i][0]) * (c(p.x[j][0]) * c(r.w[0]) - c(r.x[j][0]) * c(p.w[0]))
        + c(r.x[i][0]) * (c(p.x[j][0]) * c(q.w[0]) - c(q.x[j][0]) * c(p.w[0]));
    if d0 != W0 {
        return if d0 > W0 { 1 } else { -1 };
    }
    // Stage 3: the full polynomial in ε (the tie-break).
    let rows = [p, q, r].map(|h| [to_wide(&h.x[i]), to_wide(&h.x[j]), to_wide(&h.w)]);
    let minor = |r1: &[[I512; 4]; 3], r2: &[[I512; 4]; 3]| {
        let mut m = wide_poly_mul(&r1[1], &r2[2]);
        wide_poly_add(&mut m, &wide_poly_mul(&r2[1], &r1[2]), true);
        m
    };
    let mut det = wide_poly_mul(&rows[0][0], &minor(&rows[1], &rows[2]));
    wide_poly_add(
        &mut det,
        &wide_poly_mul(&rows[1][0], &minor(&rows[0], &rows[2])),
        true,
    );
    wide_poly_add(
        &mut det,
        &wide_poly_mul(&rows[2][0], &minor(&rows[0], &rows[1])),
        false,
    );
    wide_sign(&det)
}

/// Compares `p · dir` with `q · dir` (i.e. orders two points along a direction), under the
/// tie-break rule. `Less` means `p` comes first.
pub fn cmp_along(p: &HPoint, q: &HPoint, dir: &[i128; 3]) -> Ordering {
    // p·dir / wp  vs  q·dir / wq  ⇔  (p·dir) wq vs (q·dir) wp (weights positive).
    let dotf = |h: &HPoint| {
        let mut s = 0.0;
        let mut a = 0.0;
        for k in 0..3 {
            let t = h.x[k][0] as f64 * dir[k] as f64;
            s += t;
            a += t.abs();
        }
        (s, a)
    };
    let (dp, ap) = dotf(p);
    let (dq, aq) = dotf(q);
    let (wp, wq) = (p.w[0] as f64, q.w[0] as f64);
    let diff = dp * wq - dq * wp;
    let bound = (ap * wq.abs() + aq * wp.abs()) * FILTER_EPS;
    if diff.abs() > bound {
        return if diff < 0.0 {
            Ordering::Less
        } else {
            Ordering::Greater
        };
    }
    let dot = |h: &HPoint| -> Vec<I512> {
        (0..4)
            .map(|k| (0..3).fold(W0, |acc, i| acc + wide(h.x[i][k]) * wide(dir[i])))
            .collect()
    };
    let mut d = wide_poly_mul(&dot(p), &to_wide(&q.w));
    wide_poly_add(&mut d, &wide_poly_mul(&dot(q), &to_wide(&p.w)), true);
    match wide_sign(&d) {
        s if s < 0 => Ordering::Less,
        s if s > 0 => Ordering::Greater,
        _ => Ordering::Equal,
    }
}

/// Compares coordinate `axis` of two points, under the tie-break rule.
pub fn cmp_coord(p: &HPoint, q: &HPoint, axis: usize) -> Ordering {
    let mut dir = [0i128; 3];
    dir[axis] = 1;
    cmp_along(p, q, &dir)
}

/// Sign of `orient3d(a, b, c, d)` for floating-point points, exact (Shewchuk's adaptive
/// predicate): `+1` when `d` lies on the side the normal of the counter-clockwise triangle `abc`
/// points to. For decisions taken on `f64` positions outside the lattice (the scalpel).
#[inline]
pub fn orient3d_f64(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Sign {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    // `robust` uses the opposite sign convention (positive below the plane).
    let o = robust::orient3d(p(a), p(b), p(c), p(d));
    -(o.partial_cmp(&0.0).map_or(0, |s| s as Sign))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orient3d_sign_convention() {
        let o = [0, 0, 0];
        let x = [1, 0, 0];
        let y = [0, 1, 0];
        assert!(orient3d(&o, &x, &y, &[0, 0, 1]) > 0);
        assert!(orient3d(&o, &x, &y, &[0, 0, -1]) < 0);
        assert_eq!(orient3d(&o, &x, &y, &[5, 7, 0]), 0);
    }

    #[test]
    fn sos_breaks_coplanar_ties_by_normal_x_first() {
        // Target point in the plane z = 0 of a cutter face with normal +z: the cutter moves by
        // δ whose z part is ε³ > 0, so the point ends up below the cutter plane.
        let (a, b, c) = ([0, 0, 0], [4, 0, 0], [0, 4, 0]);
        assert_eq!(target_point_vs_cutter_plane(&a, &b, &c, &[1, 1, 0]), -1);
        // A cutter face in the plane x = 0, normal +x: the ε term decides.
        let (a, b, c) = ([0, 0, 0], [0, 4, 0], [0, 0, 4]);
        assert_eq!(target_point_vs_cutter_plane(&a, &b, &c, &[0, 1, 1]), -1);
        // Opposite orientation flips it.
        assert_eq!(target_point_vs_cutter_plane(&a, &c, &b, &[0, 1, 1]), 1);
    }

    #[test]
    fn edge_crossing_through_cutter_vertex_is_counted_once() {
        // A target edge through the shared vertex of a fan of cutter triangles: exactly one
        // triangle of the fan is crossed under the perturbation.
        let centre = [0, 0, 0];
        let ring: Vec<LPoint> = vec![[4, 0, 0], [0, 4, 0], [-4, 0, 0], [0, -4, 0]];
        let (p, q) = ([0, 0, -3], [0, 0, 3]);
        let mut hits = 0;
        for k in 0..4 {
            let (b, c) = (&ring[k], &ring[(k + 1) % 4]);
            if target_edge_crosses_cutter_face(&p, &q, &centre, b, c).is_some() {
                hits += 1;
            }
        }
        assert_eq!(hits, 1);
    }

    #[test]
    fn hpoints_lie_where_expected() {
        let (a, b, c) = ([0, 0, 10], [10, 0, 10], [0, 10, 10]);
        let h = HPoint::edge_face(&[1, 1, 0], &[1, 1, 20], &a, &b, &c);
        assert_eq!(h.limit(), [1.0, 1.0, 10.0]);
        let h = HPoint::face_edge(
            &[2, 3, -5],
            &[2, 3, 5],
            &[0, 0, 0],
            &[10, 0, 0],
            &[0, 10, 0],
        );
        assert_eq!(h.limit(), [2.0, 3.0, 0.0]);
    }

    #[test]
    fn orient2d_breaks_ties_with_perturbation() {
        // Three points on a line in the limit: two target vertices and a cutter vertex; the
        // cutter vertex moves by (ε, ε²) in the xy projection, so it is off the line.
        let p = HPoint::target_vertex(&[0, 0, 0]);
        let q = HPoint::target_vertex(&[4, 4, 0]);
        let r = HPoint::cutter_vertex(&[2, 2, 0]);
        let s = orient2d(&p, &q, &r, 2);
        assert_ne!(s, 0);
        // Swapping two points flips the sign.
        assert_eq!(orient2d(&q, &p, &r, 2), -s);
        // Translation by (ε, ε²): ε moves x right, so r is below the line y = x: clockwise.
        assert_eq!(s, -1);
    }

    #[test]
    fn cmp_along_orders_and_breaks_ties() {
        let p = HPoint::target_vertex(&[0, 0, 0]);
        let q = HPoint::target_vertex(&[3, 0, 0]);
        assert_eq!(cmp_along(&p, &q, &[1, 0, 0]), Ordering::Less);
        let r = HPoint::cutter_vertex(&[0, 0, 0]);
        assert_eq!(cmp_along(&p, &r, &[1, 0, 0]), Ordering::Less);
        assert_eq!(cmp_along(&p, &p, &[1, 0, 0]), Ordering::Equal);
    }
}
