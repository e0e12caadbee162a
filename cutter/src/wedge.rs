//! The wedge cut (thesis 3.3.2.3): prisms fanned around one shared top axis, the "pie" whose
//! front triangles rest on the surface and whose back reaches into the target.
//!
//! The thesis builds the wedge like a box (front face on the surface, back face 5δ behind it) and
//! pushes the whole cutter out along BA whenever a front triangle would cross the surface. On a
//! curved target that leaves a pie lying on the surface: its front is a tangent plane at the
//! nearest point, the rim recedes from it, and the 5δ back reaches the surface only near the
//! apex, so the cut is a thin sliver that mostly sits in the air. Here the wedge keeps its
//! front on the surface but its back always lies inside: after initialisation and after every
//! extrusion move the shared axis is lengthened (never shortened) until the back lies
//! [`reach`] below the deepest surface point under the front triangles, and the collision push
//! moves only the front out, so pushing never lifts the back out of the target.

use glam::{DQuat, DVec3};

use crate::camera::Ray;
use crate::cutter::Cutter;
use crate::geom;
use crate::plane::BoundedPlane;
use crate::roll::{INITIAL_DEPTH, MIN_WIDTH, ROTATION_STEP, RollSettings};
use crate::surface::Surface;

/// Points sampled along each front edge (apex to rim) when looking for the surface under the
/// front triangles.
const SAMPLES_PER_EDGE: usize = 8;

/// How far below the deepest surface point under its front a wedge's back lies: half the pie's
/// radius (a wedge as deep as it is wide removes a sector, not a shaving), at least the initial
/// depth of a box.
pub fn reach(cutter: &Cutter, delta: f64) -> f64 {
    let a = cutter.planes[0].front_top;
    let radius = cutter
        .planes
        .iter()
        .map(|p| (p.front_bottom - a).length())
        .fold(0.0, f64::max);
    (0.5 * radius).max(INITIAL_DEPTH * delta)
}

/// Lengthens the wedge's shared axis (moves every back point along it) so that the back lies
/// [`reach`] below the deepest surface point met by the axis-parallel lines through the front
/// triangles. Never shortens it. Returns true when the wedge changed; a wedge whose front sees no
/// surface keeps its depth.
pub fn reach_into_surface(cutter: &mut Cutter, surface: &Surface, delta: f64) -> bool {
    let p0 = cutter.planes[0];
    let a = p0.front_top;
    let Some(axis) = (p0.back_top - a).try_normalize() else {
        return false;
    };
    let depth = (p0.back_top - a).length();
    let mut deepest: Option<f64> = None;
    for p in &cutter.planes {
        for k in 0..=SAMPLES_PER_EDGE {
            let q = a.lerp(p.front_bottom, k as f64 / SAMPLES_PER_EDGE as f64);
            // From a little in front of the face, so a face resting on the surface still sees it.
            let origin = q - axis * (2.0 * ROTATION_STEP * delta);
            if let Some((t, _)) = surface.ray_cast(origin, axis, f64::INFINITY) {
                let below = t - 2.0 * ROTATION_STEP * delta;
                deepest = Some(deepest.map_or(below, |d: f64| d.max(below)));
            }
        }
    }
    let Some(deepest) = deepest else {
        return false;
    };
    let wanted = deepest.max(0.0) + reach(cutter, delta);
    if wanted <= depth {
        return false;
    }
    let back = axis * wanted;
    for p in &mut cutter.planes {
        p.back_top = a + back;
        p.back_bottom = p.front_bottom + back;
    }
    true
}

/// Wedge extrusion (thesis 3.3.2.3): E' stays on the shared axis, M sets the rotation, and on a
/// collision the front moves 2δ along BA (out of the object) until the new front triangle is
/// clear; the back stays, so the wedge gets deeper rather than lifting out. The back then reaches
/// the surface under the swept front ([`reach_into_surface`]).
pub(crate) fn wedge_move(
    cutter: &mut Cutter,
    surface: &Surface,
    ray: &Ray,
    settings: &RollSettings,
) -> bool {
    let mut scratch = Vec::new();
    let delta = settings.delta;
    let lock = (settings.spacing * delta).max(2.0 * MIN_WIDTH * delta);
    let mut changed = false;
    for _ in 0..crate::roll::MAX_BOXES_PER_MOVE {
        let n = cutter.planes.len();
        let p0 = cutter.planes[0];
        let prev = cutter.planes[n - 2];
        let lead = cutter.planes[n - 1];
        let a = p0.front_top;
        let axis_back = p0.back_top - p0.front_top;
        let Some(normal) = (cutter.planes[0].front_bottom - a)
            .cross(cutter.planes[1].front_bottom - a)
            .try_normalize()
        else {
            break;
        };
        // Rotation sense: from plane 0 toward plane 1 about `normal`.
        let Some(t) = geom::line_plane(ray.origin, ray.direction, a, normal) else {
            break;
        };
        if t <= 0.0 {
            break;
        }
        let m = ray.at(t);
        let radius = (prev.front_bottom - a).length();
        let u0 = prev.front_bottom - a;
        let Some(um) = (m - a).try_normalize() else {
            break;
        };
        let mut phi = normal.dot(u0.cross(um)).atan2(u0.dot(um));
        let min_phi = MIN_WIDTH * delta / radius;
        let lock_phi = 2.0 * (lock / (2.0 * radius)).min(1.0).asin();
        let locking = phi > lock_phi + min_phi;
        if locking {
            phi = lock_phi;
        }
        phi = phi.max(min_phi).min(90f64.to_radians());
        let h = a + DQuat::from_axis_angle(normal, phi) * u0;
        let new_lead = BoundedPlane {
            front_top: a,
            back_top: p0.back_top,
            back_bottom: h + axis_back,
            front_bottom: h,
        };
        let previous_planes = cutter.planes.clone();
        cutter.planes[n - 1] = new_lead;
        // Collision: move the front out along BA in 2δ steps (the back stays in the target).
        let out = (-axis_back).normalize_or_zero() * ROTATION_STEP * delta;
        let mut pushes = 0;
        while pushes < 50 {
            let l = cutter.planes[n - 1];
            if !surface.triangle_intersects(
                &[
                    l.front_top,
                    cutter.planes[n - 2].front_bottom,
                    l.front_bottom,
                ],
                &mut scratch,
            ) {
                break;
            }
            for p in &mut cutter.planes {
                p.front_top += out;
                p.front_bottom += out;
            }
            pushes += 1;
        }
        if locking {
            let l = cutter.planes[n - 1];
            let apex = cutter.planes[0].front_top;
            let turn = DQuat::from_axis_angle(normal, min_phi);
            let fb = apex + turn * (l.front_bottom - apex);
            let shared = cutter.planes[0];
            cutter.planes.push(BoundedPlane {
                front_top: shared.front_top,
                back_top: shared.back_top,
                back_bottom: fb + (shared.back_top - shared.front_top),
                front_bottom: fb,
            });
        }
        reach_into_surface(cutter, surface, delta);
        if cutter.sanity_check().is_err() {
            cutter.planes = previous_planes;
            break;
        }
        changed |= cutter.planes[n - 1] != lead || locking;
        if !locking {
            break;
        }
    }
    changed
}

/// The share of a wedge's volume for which `inside` holds (the part that cuts the target rather
/// than the air), from a grid of samples in each prism weighted by its front triangle's area.
pub fn share_inside(cutter: &Cutter, inside: impl Fn(DVec3) -> bool) -> f64 {
    const N: usize = 6;
    let a = cutter.planes[0].front_top;
    let back = cutter.planes[0].back_top - a;
    let (mut total, mut hit) = (0.0, 0.0);
    for w in cutter.planes.windows(2) {
        let (d0, d1) = (w[0].front_bottom, w[1].front_bottom);
        let area = 0.5 * (d0 - a).cross(d1 - a).length();
        for i in 0..N {
            for j in 0..N - i {
                // Cell centres of a barycentric grid on the front triangle.
                let (u, v) = (
                    (i as f64 + 1.0 / 3.0) / N as f64,
                    (j as f64 + 1.0 / 3.0) / N as f64,
                );
                let p = a + (d0 - a) * u + (d1 - a) * v;
                for k in 0..N {
                    let q = p + back * ((k as f64 + 0.5) / N as f64);
                    total += area;
                    if inside(q) {
                        hit += area;
                    }
                }
            }
        }
    }
    if total > 0.0 { hit / total } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::share_inside;
    use crate::camera::Camera;
    use crate::cutter::CutKind;
    use crate::extrude::{RollSettings, extrude_move, initialize};
    use crate::surface::Surface;

    #[test]
    fn a_wedge_on_a_sphere_rests_on_it_and_reaches_into_it() {
        let mesh = csg::testkit::icosphere(4, 50.0);
        let index = csg::SpatialIndex::build(&mesh);
        let surface = Surface::new(&mesh, &index);
        let camera = Camera::framing(&mesh.bbox(), DVec3::NEG_Y, DVec3::Z, 30.0);
        let viewport = DVec2::new(1280.0, 800.0);
        let delta = (camera.eye - camera.target).length() / 2000.0;
        // Press near the centre, drag 120 px up: the pie's first radius.
        let a = DVec2::new(650.0, 410.0);
        let b = DVec2::new(650.0, 290.0);
        let mut cutter = initialize(
            &surface,
            &camera,
            viewport,
            a,
            b,
            delta,
            CutKind::Wedge,
            false,
        )
        .unwrap();
        // Sweep the rim a quarter turn about the press point.
        let settings = RollSettings {
            delta,
            spacing: 20.0,
            straight: false,
            keep_direction: false,
            keep_depth: false,
        };
        for k in 1..=30 {
            let ang = (k as f64 * 3.0).to_radians();
            let m = a + DVec2::new(ang.sin(), -ang.cos()) * 120.0;
            extrude_move(
                &mut cutter,
                &surface,
                &camera.ray_through_pixel(viewport, m),
                &settings,
            );
        }
        cutter.sanity_check().unwrap();
        assert!(cutter.planes.len() >= 4, "{} planes", cutter.planes.len());
        let inside = |p: DVec3| csg::winding::winding_number_exact(&mesh, p) > 0.5;
        // The front starts on the surface: the apex is outside, within a few δ of it.
        let apex = cutter.planes[0].front_top;
        assert!(!inside(apex));
        let gap = surface.distance(apex);
        assert!(
            gap < 4.0 * delta,
            "apex {:.1}δ above the surface",
            gap / delta
        );
        // The back lies below the surface points under the front: the shared axis's back end and
        // every plane's back-bottom corner are inside the sphere.
        assert!(
            inside(cutter.planes[0].back_top),
            "the axis does not reach in"
        );
        for (i, p) in cutter.planes.iter().enumerate() {
            assert!(
                inside(p.back_bottom),
                "plane {i}'s back corner is in the air"
            );
        }
        // Most of the wedge cuts the target, not the air.
        let share = share_inside(&cutter, inside);
        assert!(
            share > 0.5,
            "only {:.0} % of the wedge is inside",
            share * 100.0
        );
    }
}
