//! Initialising and extruding a cutter: the paint-roller metaphor of thesis 3.3.1–3.3.2.
//!
//! Notation (the thesis's figures 23, 27, 28): the previous plane is `ABCD` (A front-top, B
//! back-top, C back-bottom, D front-bottom); the leading plane being moved is `EFGH`. `Q` is the
//! midpoint of `AD`, `M` the mouse point projected on the front plane, `x` the intersection of the
//! lines `AD` and `E'H'`, δ the scene increment.
//!
//! Stages of one extrusion step ([`roll`]), in order:
//! 1. project the mouse ray onto the front plane (the plane of the leading box's front face) → M;
//!    Shift (straight) turns M about Q so that MQ ⟂ AD;
//! 2. E'H' ⟂ MQ through M with |E'H'| = |AD|;
//! 3. parallel correction: E''H'' is AD turned about x (isosceles triangle x A E''), so AE'' ∥
//!    DH''. When x falls inside (or too near) AD the turn would fold the box, so x is held at
//!    1.25·|AD|/2 from Q and the turn keeps the box width instead (our addition: the thesis does
//!    not say what happens then);
//! 4. iterative face rotation about DA in 2δ steps: outward while the front face AE''H''D crosses
//!    the surface, else inward until it does. The thesis then steps back out once, which leaves
//!    the face anywhere 0–2δ above the surface; we refine the bracketed contact by bisection and
//!    rest the leading edge [`REST_GAP`]·δ outside it, the middle of that range, so the gap does
//!    not depend on where the 2δ grid happens to fall. Capped at 45 steps outward or 60° inward;
//!    a face that finds no contact within 60° turns by the 60° when surface is still within the
//!    roller's reach (it falls away over an edge: the thesis keeps turning inward until contact,
//!    the next boxes catch up), and keeps its unrotated position when there is none (the roller
//!    left the object);
//! 5. the back edge F'G' along the negative normal of the new front face, at the previous depth
//!    (the thesis). With [`RollSettings::keep_direction`] it goes along the previous plane's back
//!    direction instead (a cutter cut along the view it was painted in: every plane shares the
//!    first plane's direction), and with [`RollSettings::keep_depth`] at the leading plane's own
//!    depth, so a deepened roller stays deep and the planes it locks take its depth.
//!
//! When the leading box reaches ω·δ wide it is locked and a new, thin leading box starts (several
//! per move when the mouse jumps far).

use glam::{DQuat, DVec2, DVec3};

use crate::camera::{Camera, Ray};
use crate::cutter::{CutKind, Cutter};
use crate::geom;
use crate::plane::BoundedPlane;
use crate::roll::MAX_BOXES_PER_MOVE;
pub use crate::roll::{INITIAL_DEPTH, INITIAL_WIDTH, MIN_WIDTH, ROTATION_STEP, RollSettings};
use crate::surface::{LocalSurface, Surface};

/// Largest inward rotation searched for the surface, in degrees.
const MAX_INWARD_DEG: f64 = 60.0;
/// Height above the contact where the front face rests, as a multiple of δ (at the leading edge).
pub const REST_GAP: f64 = 1.0;

/// Below this |cos| between the mouse ray and the front plane's normal (about 75°), the front
/// plane counts as seen edge-on.
const GRAZING: f64 = 0.25;

/// The strip dragged from `a` to `b` (pixels) as the four pixel corners A, D, H, E: the box
/// extends `width_px` to the screen-right of A→B (toward screen-right when A is below B).
pub fn strip_pixels(a: DVec2, b: DVec2, width_px: f64) -> [DVec2; 4] {
    let s = b - a;
    let w = DVec2::new(-s.y, s.x).normalize_or_zero() * width_px;
    [a, b, b + w, a + w]
}

/// Pixel size (world length per pixel) at view depth `z`.
fn pixel_size(camera: &Camera, viewport: DVec2, z: f64) -> f64 {
    2.0 * z * (camera.fov_y_deg.to_radians() * 0.5).tan() / viewport.y.max(1.0)
}

/// The point seen at pixel `px` at view depth `z` (distance along the forward axis).
fn point_at_depth(camera: &Camera, viewport: DVec2, px: DVec2, z: f64) -> DVec3 {
    let ray = camera.ray_through_pixel(viewport, px);
    let f = camera.forward();
    ray.at(z / ray.direction.dot(f).max(1e-12))
}

/// View depth of the surface point nearest to the view plane among those seen through the pixel
/// polygon `corners` (the thesis's "deep box" behind the strip, figure 22). None when the polygon
/// sees no surface.
fn min_depth_behind(
    surface: &Surface,
    camera: &Camera,
    viewport: DVec2,
    corners: &[DVec2; 4],
) -> Option<f64> {
    let f = camera.forward();
    let eye = camera.eye;
    let bbox = surface.bbox();
    if bbox.is_empty() {
        return None;
    }
    let mut zmin = f64::INFINITY;
    let mut zmax = f64::NEG_INFINITY;
    for i in 0..8 {
        let c = DVec3::new(
            if i & 1 == 0 { bbox.min.x } else { bbox.max.x },
            if i & 2 == 0 { bbox.min.y } else { bbox.max.y },
            if i & 4 == 0 { bbox.min.z } else { bbox.max.z },
        );
        let z = (c - eye).dot(f);
        zmin = zmin.min(z);
        zmax = zmax.max(z);
    }
    if zmax <= 0.0 {
        return None;
    }
    zmin = zmin.max(zmax * 1e-6);
    let dirs = corners.map(|c| camera.ray_through_pixel(viewport, c).direction);
    let mut region = csg::Aabb::EMPTY;
    for d in &dirs {
        for z in [zmin, zmax] {
            region.grow(eye + *d * (z / d.dot(f).max(1e-12)));
        }
    }
    let inside: DVec3 = dirs.iter().copied().sum();
    let planes: Vec<DVec3> = (0..4)
        .filter_map(|i| {
            let n = dirs[i].cross(dirs[(i + 1) % 4]).try_normalize()?;
            Some(if n.dot(inside) < 0.0 { -n } else { n })
        })
        .collect();
    let mut faces = Vec::new();
    surface.index.faces_in_box(&region, &mut faces);
    let mut best = f64::INFINITY;
    let mut poly = Vec::with_capacity(8);
    let mut next = Vec::with_capacity(8);
    for &fi in &faces {
        poly.clear();
        poly.extend_from_slice(&surface.mesh.corners(fi as usize));
        for n in &planes {
            next.clear();
            for k in 0..poly.len() {
                let p = poly[k];
                let q = poly[(k + 1) % poly.len()];
                let dp = (p - eye).dot(*n);
                let dq = (q - eye).dot(*n);
                if dp >= 0.0 {
                    next.push(p);
                }
                if (dp >= 0.0) != (dq >= 0.0) {
                    next.push(p + (q - p) * (dp / (dp - dq)));
                }
            }
            std::mem::swap(&mut poly, &mut next);
            if poly.is_empty() {
                break;
            }
        }
        for p in &poly {
            let z = (*p - eye).dot(f);
            if z > 0.0 && z < best {
                best = z;
            }
        }
    }
    best.is_finite().then_some(best)
}

/// Initialises a cutter from a drag A→B in pixels (thesis 3.3.1): the strip is built in the view
/// plane, pushed along the view direction onto the closest surface point behind it, and given a
/// back face 5δ deeper. Plane 0 is `ABCD` with A the press point; plane 1, 10δ to the
/// screen-right of A→B, is the leading plane. A wedge's back instead reaches into the target
/// ([`crate::wedge::reach_into_surface`]). Returns None for a drag shorter than 2 pixels.
///
/// When the strip sees no surface at all (a surrounding cut started off the object), the strip is
/// pushed to the depth of the surface point nearest to the view ray through its centre.
pub fn initialize(
    surface: &Surface,
    camera: &Camera,
    viewport: DVec2,
    a: DVec2,
    b: DVec2,
    delta: f64,
    kind: CutKind,
    smooth: bool,
) -> Option<Cutter> {
    if (b - a).length() < 2.0 || delta <= 0.0 {
        return None;
    }
    let f = camera.forward();
    let (r, u, _) = camera.basis();
    let width = INITIAL_WIDTH * delta;
    // First depth estimate: a ray through the drag, else the target's centre.
    let mut z = [a, (a + b) * 0.5, b]
        .iter()
        .find_map(|&px| {
            let ray = camera.ray_through_pixel(viewport, px);
            surface
                .ray_cast(ray.origin, ray.direction, f64::INFINITY)
                .map(|(_, p)| (p - camera.eye).dot(f))
        })
        .unwrap_or_else(|| (surface.bbox().center() - camera.eye).dot(f));
    let mut found = false;
    for _ in 0..2 {
        let width_px = width / pixel_size(camera, viewport, z.max(1e-9));
        let corners = strip_pixels(a, b, width_px);
        if let Some(zc) = min_depth_behind(surface, camera, viewport, &corners) {
            z = zc;
            found = true;
        } else {
            break;
        }
    }
    if !found {
        let centre_px = (a + b) * 0.5;
        let ray = camera.ray_through_pixel(viewport, centre_px);
        let probe = ray.at((surface.bbox().center() - camera.eye).dot(f).max(0.0));
        if let Some(c) = surface.closest_point(probe) {
            z = (c - camera.eye).dot(f);
        }
    }
    // Rest the strip REST_GAP·δ in front of the contact, as every extruded face rests (our
    // addition: a strip exactly touching the surface is a degenerate case for the boolean).
    let z = z - REST_GAP * delta;
    if z.is_nan() || z <= 0.0 {
        return None;
    }
    let s = b - a;
    let w3 = (r * -s.y - u * s.x).try_normalize()?;
    let a3 = point_at_depth(camera, viewport, a, z);
    let d3 = point_at_depth(camera, viewport, b, z);
    let depth = INITIAL_DEPTH * delta;
    let p0 = BoundedPlane::from_front_edge(a3, d3, f, depth);
    let p1 = match kind {
        CutKind::Wedge => {
            let len = (d3 - a3).length();
            let h = a3 + (d3 + w3 * width - a3).try_normalize()? * len;
            BoundedPlane::from_front_edge(a3, h, f, depth)
        }
        _ => BoundedPlane::from_front_edge(a3 + w3 * width, d3 + w3 * width, f, depth),
    };
    let mut cutter = Cutter {
        kind,
        smooth,
        levels: crate::subdivision::DEFAULT_LEVELS,
        direction: crate::cutter::CutDirection::Normal,
        planes: vec![p0, p1],
    };
    if kind == CutKind::Wedge {
        // The pie rests on the surface; its back reaches into the target (wedge.rs).
        crate::wedge::reach_into_surface(&mut cutter, surface, delta);
    }
    cutter.sanity_check().ok()?;
    Some(cutter)
}

/// Moves the leading plane toward the mouse ray (one extrusion move), locking boxes and starting
/// new ones as they reach ω·δ. Returns true when the cutter changed. The cutter stays valid: a
/// move that would fold the leading box onto the previous one is ignored.
pub fn extrude_move(
    cutter: &mut Cutter,
    surface: &Surface,
    ray: &Ray,
    settings: &RollSettings,
) -> bool {
    if cutter.planes.len() < 2 {
        return false;
    }
    if cutter.kind == CutKind::Wedge {
        return crate::wedge::wedge_move(cutter, surface, ray, settings);
    }
    let mut scratch = Vec::new();
    let lock_width = (settings.spacing * settings.delta).max(2.0 * MIN_WIDTH * settings.delta);
    let mut changed = false;
    for _ in 0..MAX_BOXES_PER_MOVE {
        let n = cutter.planes.len();
        let (prev, lead) = (cutter.planes[n - 2], cutter.planes[n - 1]);
        let Some(frame) = FrontFrame::new(&prev, &lead) else {
            break;
        };
        let Some(m) = frame.project(ray) else {
            break;
        };
        let v = frame.forward_offset(m, settings.straight, MIN_WIDTH * settings.delta);
        // A box locks when the mouse is more than ω·δ away and ahead (within about 75° of the
        // path); the box never gets wider than ω·δ. A mouse beside or behind the roller turns
        // it but locks nothing, so the roller cannot spin around the pointer box after box.
        let ahead = v.dot(frame.forward);
        let reach = v.length();
        let v = v * (lock_width / reach).min(1.0);
        if reach > lock_width + MIN_WIDTH * settings.delta && ahead > 0.25 * reach {
            // Lock this box at ω·δ and start a new thin one beyond it.
            let m_lock = frame.q + v;
            let Some(locked) = roll(&prev, &frame, m_lock, surface, settings, &mut scratch) else {
                break;
            };
            cutter.planes[n - 1] = locked;
            let dir = (locked.front_mid() - prev.front_mid()).normalize_or_zero();
            cutter
                .planes
                .push(locked.translated(dir * MIN_WIDTH * settings.delta));
            if cutter.sanity_check().is_err() {
                cutter.planes.pop();
                cutter.planes[n - 1] = lead;
                break;
            }
            changed = true;
            continue;
        }
        let target = frame.q + v;
        if let Some(new_lead) = roll(&prev, &frame, target, surface, settings, &mut scratch) {
            cutter.planes[n - 1] = new_lead;
            // The leading box must not run into earlier boxes (a path folding back on itself).
            if cutter.sanity_check().is_err() {
                cutter.planes[n - 1] = lead;
            } else {
                changed |= new_lead != lead;
            }
        }
        break;
    }
    changed
}

/// The front plane of the leading box and the roller's frame in it.
struct FrontFrame {
    /// Front-top and front-bottom of the previous plane.
    a: DVec3,
    d: DVec3,
    /// Midpoint of AD.
    q: DVec3,
    /// Unit direction D→A.
    up: DVec3,
    /// Unit normal of the front plane, pointing out of the object (away from the back).
    normal: DVec3,
    /// Unit in-plane direction ⟂ AD toward the leading plane.
    forward: DVec3,
    /// Back direction and depth of the previous plane.
    back: DVec3,
    depth: f64,
    /// Depth of the leading plane before the move.
    lead_depth: f64,
}

impl FrontFrame {
    fn new(prev: &BoundedPlane, lead: &BoundedPlane) -> Option<FrontFrame> {
        let a = prev.front_top;
        let d = prev.front_bottom;
        let q = (a + d) * 0.5;
        let up = (a - d).try_normalize()?;
        let back = prev.back_direction();
        let mut normal = (lead.front_top - a)
            .cross(d - a)
            .try_normalize()
            .or_else(|| (-back).try_normalize())?;
        if normal.dot(back) > 0.0 {
            normal = -normal;
        }
        let mut forward = normal.cross(up).try_normalize()?;
        if forward.dot(lead.front_mid() - q) < 0.0 {
            forward = -forward;
        }
        Some(FrontFrame {
            a,
            d,
            q,
            up,
            normal,
            forward,
            back,
            depth: prev.depth(),
            lead_depth: lead.depth(),
        })
    }

    /// M: the mouse ray meets the front plane (None when behind the eye). When the front plane
    /// is seen nearly edge-on (the roller went over the object's silhouette), that intersection
    /// runs off to infinity with the smallest mouse motion, so M is taken on the plane through Q
    /// facing the ray instead (the thesis's view-plane construction) and later flattened onto
    /// the front plane.
    fn project(&self, ray: &Ray) -> Option<DVec3> {
        let facing = ray.direction.dot(self.normal).abs() / ray.direction.length();
        let t = if facing < GRAZING {
            geom::line_plane(ray.origin, ray.direction, self.q, ray.direction)?
        } else {
            geom::line_plane(ray.origin, ray.direction, self.a, self.normal)?
        };
        (t > 0.0).then(|| ray.at(t))
    }

    /// The in-plane offset Q→M, forced at least `min_width` forward; with `straight`, turned
    /// ⟂ AD (thesis 3.3.2.2).
    fn forward_offset(&self, m: DVec3, straight: bool, min_width: f64) -> DVec3 {
        let mut v = m - self.q;
        v -= self.normal * v.dot(self.normal);
        if straight {
            return self.forward * v.dot(self.forward).max(min_width);
        }
        let ahead = v.dot(self.forward);
        if ahead < min_width {
            v += self.forward * (min_width - ahead);
        }
        v
    }
}

/// One paint-roller placement of the leading plane for the in-plane target point `m` (stages 2–5
/// of the module doc). None when the result would fold onto the previous plane.
fn roll(
    prev: &BoundedPlane,
    frame: &FrontFrame,
    m: DVec3,
    surface: &Surface,
    settings: &RollSettings,
    scratch: &mut Vec<u32>,
) -> Option<BoundedPlane> {
    let FrontFrame {
        a,
        d,
        q,
        up,
        normal,
        ..
    } = *frame;
    let half = (a - d).length() * 0.5;
    let v = m - q;
    let width = v.length();
    // Stage 2: E'H' ⟂ MQ through M; its direction `p` is v turned 90° in the plane, on A's side.
    let mut p = normal.cross(v).try_normalize()?;
    if p.dot(up) < 0.0 {
        p = -p;
    }
    // Stage 3: parallel correction by turning AD about x.
    let (e, h);
    let denom = up.cross(p);
    if denom.length() < 1e-9 {
        e = a + v;
        h = d + v;
    } else {
        // x = Q + up·s = M + p·t  →  solve in the plane.
        let s = (m - q).cross(p).dot(denom) / denom.length_squared();
        let min_s = 1.25 * half;
        let (x, phi) = if s.abs() < min_s {
            let s = if s >= 0.0 { min_s } else { -min_s };
            let x = q + up * s;
            let turn = 2.0 * (width / (2.0 * s.abs())).min(1.0).asin();
            let sign = normal.dot((q - x).cross(v)).signum();
            (x, turn * sign)
        } else {
            let x = q + up * s;
            let (u0, u1) = (q - x, m - x);
            let phi = normal.dot(u0.cross(u1)).atan2(u0.dot(u1));
            (x, phi)
        };
        let phi = phi.clamp(-60f64.to_radians(), 60f64.to_radians());
        let rot = DQuat::from_axis_angle(normal, phi);
        e = x + rot * (a - x);
        h = x + rot * (d - x);
        if (e + h) * 0.5 == q {
            return None;
        }
    }
    // Stage 4: rotate the face about DA until it rests just above the surface.
    let axis = up;
    // The farther of E'' and H'' from the axis sets the step, so no point moves more than 2δ.
    let radius = {
        let off_axis = |p: DVec3| {
            let w = p - d;
            (w - axis * w.dot(axis)).length()
        };
        off_axis(e).max(off_axis(h))
    };
    if radius <= 0.0 {
        return None;
    }
    let step = (ROTATION_STEP * settings.delta / radius).clamp(1e-4, 10f64.to_radians());
    // A box narrower than one step stays in the front plane: turning it cannot move its leading
    // edge by 2δ, and its orientation would be noise.
    let settle = radius > ROTATION_STEP * settings.delta;
    let rotate = |p: DVec3, angle: f64| d + DQuat::from_axis_angle(axis, angle) * (p - d);
    // Sign of an outward (away from the object) rotation.
    let outward = if (rotate(e, step) - e).dot(normal) >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let (e0, h0) = (e, h);
    // Angles are measured outward from the corrected position.
    // The band of the face next to AD is not tested: AD was settled by the previous box, and a
    // contact there (AD itself resting on the surface, possibly a little twisted) would stop the
    // rotation long before the leading edge reaches the surface. A leading edge that slipped
    // under the surface entirely counts as intersecting too (no crossing is left to see).
    // Every face tested below lies within `radius` of the axis segment DA.
    let region = csg::Aabb::from_points([a, d].iter()).expanded(radius * 1.01);
    let local = surface.local(&region);
    let hits_at = |angle: f64, _: &mut Vec<u32>| {
        let (e1, h1) = (rotate(e0, outward * angle), rotate(h0, outward * angle));
        let q = [a.lerp(e1, 0.2), e1, h1, d.lerp(h1, 0.2)];
        local.quad_intersects(&q) || surface.is_inside((e1 + h1) * 0.5)
    };
    // Bracket the contact in 2δ steps: `clear` is an angle where the face floats, `hit` one where
    // it crosses the surface.
    let bracket = if !settle {
        Some((0.0, 0.0))
    } else if hits_at(0.0, scratch) {
        let mut hit = 0.0;
        let mut clear = None;
        for _ in 0..45 {
            let next = hit + step;
            if !hits_at(next, scratch) {
                clear = Some(next);
                break;
            }
            hit = next;
        }
        clear.map(|c| (c, hit))
    } else {
        let mut clear = 0.0;
        let mut hit = None;
        while clear > -MAX_INWARD_DEG.to_radians() {
            let next = clear - step;
            if hits_at(next, scratch) {
                hit = Some(next);
                break;
            }
            clear = next;
        }
        match hit {
            Some(h) => Some((clear, h)),
            // No contact within the inward limit. The thesis keeps turning inward "until an
            // intersection occurs": where the surface is still within the roller's reach (it
            // falls away faster than the limit, e.g. over an edge), turn by the limit and let
            // the next boxes catch up; a roller that left the object altogether (no surface
            // within reach) stays unrotated instead of curling up in the air.
            None if surface.distance((e0 + h0) * 0.5) <= 2.0 * radius => Some((clear, clear)),
            None => Some((0.0, 0.0)),
        }
    };
    let angle = match bracket {
        None => 45.0 * step,
        Some((clear, hit)) if clear == hit => clear,
        Some((mut clear, mut hit)) => {
            // Refine the contact (our addition), then rest the face REST_GAP·δ outside it: the
            // thesis's final 2δ step leaves it anywhere 0–2δ above; this is the middle of that.
            for _ in 0..6 {
                let mid = 0.5 * (clear + hit);
                if hits_at(mid, scratch) {
                    hit = mid;
                } else {
                    clear = mid;
                }
            }
            let rest = clear + (REST_GAP * settings.delta / radius).min(step);
            if hits_at(rest, scratch) { clear } else { rest }
        }
    };
    // Stage 5: back edge along the new face's negative normal (at the leading edge: ⟂ to the
    // edge and to the path), at the previous depth. A box too narrow for the turn its face
    // needs would fold (its back face would cross the previous plane), so the turn is halved
    // until the box is well formed; turn 0 (the front plane itself) always is.
    let place = |angle: f64, levelled: bool| -> Option<BoundedPlane> {
        let (mut e, mut h) = (rotate(e0, outward * angle), rotate(h0, outward * angle));
        if levelled {
            (e, h) = level(a, d, e, h, surface, &local, settings.delta);
        }
        let path = ((e + h) * 0.5 - q).try_normalize()?;
        let mut n = (e - h).cross(path).try_normalize()?;
        if n.dot(frame.back) > 0.0 {
            n = -n;
        }
        let back = if settings.keep_direction {
            frame.back
        } else {
            -n
        };
        let depth = if settings.keep_depth {
            frame.lead_depth
        } else {
            frame.depth
        };
        let lead = BoundedPlane::from_front_edge(e, h, back, depth);
        let pair = Cutter {
            kind: CutKind::Curving,
            smooth: false,
            levels: crate::subdivision::DEFAULT_LEVELS,
            direction: crate::cutter::CutDirection::Normal,
            planes: vec![*prev, lead],
        };
        pair.sanity_check().ok().map(|_| lead)
    };
    [1.0, 0.5, 0.25, 0.125]
        .iter()
        .find_map(|&f| place(angle * f, settle))
        .or_else(|| place(0.0, false))
}

/// Stage 4b (our addition): levels the leading edge E''H'' across the path. Rotating about DA
/// alone cannot undo a twist of the roller relative to the surface (it accumulates where the path
/// turns on a curved surface, e.g. an S on a sphere), so one end would float ever higher. Turns
/// E''H'' about the path direction through its midpoint until both ends are equally far from the
/// surface, unless that makes the face cross it.
fn level(
    a: DVec3,
    d: DVec3,
    e: DVec3,
    h: DVec3,
    surface: &Surface,
    local: &LocalSurface,
    delta: f64,
) -> (DVec3, DVec3) {
    let m = (e + h) * 0.5;
    let q = (a + d) * 0.5;
    let (Some(path), Some(half)) = ((m - q).try_normalize(), Some((e - h).length() * 0.5)) else {
        return (e, h);
    };
    if half <= 0.0 {
        return (e, h);
    }
    let (ge, gh) = (surface.distance(e), surface.distance(h));
    if !(ge.is_finite() && gh.is_finite()) || (ge - gh).abs() < 0.5 * delta {
        return (e, h);
    }
    // An end farther from the surface than half the edge's length hangs over an edge of the
    // object (the surface under it fell away), not over a twist: levelling would lift the face
    // off the surface the other end rests on.
    if ge.max(gh) > half {
        return (e, h);
    }
    // Lower the higher end by half the difference, raise the other by as much.
    let alpha = ((ge - gh) * 0.5 / half).clamp(-0.5, 0.5).atan();
    let turn = |angle: f64| {
        let r = DQuat::from_axis_angle(path, angle);
        (m + r * (e - m), m + r * (h - m))
    };
    let (e1, h1) = turn(alpha);
    let (e2, h2) = turn(-alpha);
    // Pick the sense that brings E toward the surface when it is the higher end.
    let better = |x: DVec3, y: DVec3| (surface.distance(x) - surface.distance(y)).abs();
    let (e3, h3) = if better(e1, h1) <= better(e2, h2) {
        (e1, h1)
    } else {
        (e2, h2)
    };
    if local.quad_intersects(&[a, e3, h3, d]) {
        (e, h)
    } else {
        (e3, h3)
    }
}

/// Largest distance from a plane's front-edge midpoint to the surface (the `max_surface_gap` of
/// `cutaway extrude --json`).
pub fn max_surface_gap(cutter: &Cutter, surface: &Surface) -> f64 {
    cutter
        .planes
        .iter()
        .map(|p| surface.distance(p.front_mid()))
        .fold(0.0, f64::max)
}
