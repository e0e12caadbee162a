//! Camera manipulation of the viewport: orbit, pan, zoom and framing (picking: `crate::cutting::pick`).
//!
//! Behaves like VTK's trackball-camera style that the thesis used (section 3.5, "Mode buttons"):
//! a left drag orbits the eye around the target (horizontal motion about the camera's up axis,
//! vertical motion about its right axis, with the up vector re-orthogonalised so the camera can go
//! over the poles), Shift + drag pans eye and target together so the point under the cursor stays
//! under it, and the wheel dollies toward the target. All functions work on [`cutter::Camera`] in
//! world space; pixel deltas are in viewport pixels (origin top-left, y down).

use glam::{DQuat, DVec2, DVec3};

use csg::Aabb;
use cutter::Camera;

/// Radians of orbit per pixel of drag.
const ORBIT_RADIANS_PER_PIXEL: f64 = 0.008;
/// Distance factor per wheel notch (one notch = 1.0 of `notches`): about 8 % closer a notch, so
/// a few notches frame a structure without overshooting it.
const ZOOM_PER_NOTCH: f64 = 0.92;

/// Orbits the eye around the target by a drag of `delta_px` pixels.
pub fn orbit(camera: &mut Camera, delta_px: DVec2) {
    let (right, up, _forward) = camera.basis();
    let yaw = DQuat::from_axis_angle(up, -delta_px.x * ORBIT_RADIANS_PER_PIXEL);
    let pitch = DQuat::from_axis_angle(right, -delta_px.y * ORBIT_RADIANS_PER_PIXEL);
    let rotation = yaw * pitch;
    let eye_from_target = camera.eye - camera.target;
    camera.eye = camera.target + rotation * eye_from_target;
    // Keep the up vector orthogonal to the new view direction (VTK's OrthogonalizeViewUp).
    camera.up = (rotation * up).try_normalize().unwrap_or(up);
}

/// World-space point under pixel `px` on the plane through the camera target facing the camera
/// (for tools that need a 3D point where nothing is hit, and for panning). Uses the camera's own
/// pixel rays, so it agrees with the renderer and the editor by construction.
pub fn point_on_target_plane(camera: &Camera, viewport_px: DVec2, px: DVec2) -> DVec3 {
    let ray = camera.ray_through_pixel(viewport_px, px);
    let normal = camera.forward();
    let denom = ray.direction.dot(normal);
    if denom.abs() < 1e-12 {
        return camera.target;
    }
    ray.at((camera.target - ray.origin).dot(normal) / denom)
}

/// World-space length of one pixel at the target's depth: the distance between the points under
/// two vertically adjacent pixels at the viewport centre.
pub fn world_per_pixel(camera: &Camera, viewport_px: DVec2) -> f64 {
    let centre = viewport_px * 0.5;
    let a = point_on_target_plane(camera, viewport_px, centre);
    let b = point_on_target_plane(camera, viewport_px, centre + DVec2::Y);
    a.distance(b)
}

/// Pans eye and target together so the scene follows a drag of `delta_px` pixels.
pub fn pan(camera: &mut Camera, delta_px: DVec2, viewport_px: DVec2) {
    let (right, up, _) = camera.basis();
    let scale = world_per_pixel(camera, viewport_px);
    let shift = (-right * delta_px.x + up * delta_px.y) * scale;
    camera.eye += shift;
    camera.target += shift;
}

/// Dollies toward (positive `notches`) or away from the target; never reaches or passes it.
pub fn zoom(camera: &mut Camera, notches: f64, min_distance: f64) {
    let distance = camera.distance();
    let wanted = (distance * ZOOM_PER_NOTCH.powf(notches)).max(min_distance.max(1e-9));
    camera.eye = camera.target - camera.forward() * wanted;
}

/// Dollies toward (positive `notches`) or away from `anchor`, the world point under the pointer:
/// eye and target move along their lines to it, so the anchor stays under the pointer (the view
/// direction is kept) and what the user points at comes closer. The eye never comes nearer the
/// target than `min_distance`.
pub fn zoom_at(camera: &mut Camera, notches: f64, min_distance: f64, anchor: DVec3) {
    let distance = camera.distance();
    let wanted = (distance * ZOOM_PER_NOTCH.powf(notches)).max(min_distance.max(1e-9));
    let factor = wanted / distance.max(1e-300);
    camera.eye = anchor + (camera.eye - anchor) * factor;
    camera.target = anchor + (camera.target - anchor) * factor;
}

/// Moves the target to `centre`, keeping the viewing direction and distance.
pub fn centre_on(camera: &mut Camera, centre: DVec3) {
    let shift = centre - camera.target;
    camera.eye += shift;
    camera.target += shift;
}

/// A camera looking at `bbox` from the front (−Y toward the eye would hide it; anatomy is Z-up and
/// faces −Y), framing all of it. An empty box gives a unit view of the origin.
pub fn frame_all(bbox: &Aabb, fov_y_deg: f64) -> Camera {
    if bbox.is_empty() || !bbox.diagonal().is_finite() || bbox.diagonal() <= 0.0 {
        return Camera {
            eye: DVec3::new(0.0, -3.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg,
        };
    }
    Camera::framing(bbox, DVec3::NEG_Y, DVec3::Z, fov_y_deg)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: DVec3::new(0.0, -300.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg: 30.0,
        }
    }

    #[test]
    fn orbit_keeps_distance_and_turns_the_view() {
        let mut c = camera();
        orbit(&mut c, DVec2::new(120.0, -40.0));
        assert!((c.distance() - 300.0).abs() < 1e-9);
        assert!(
            c.forward().dot(DVec3::Y) < 0.99,
            "the view must have turned"
        );
        assert!(
            c.up.dot(c.forward()).abs() < 1e-9,
            "up stays orthogonal to the view"
        );
        // Dragging back undoes a pure horizontal orbit.
        let mut d = camera();
        orbit(&mut d, DVec2::new(50.0, 0.0));
        orbit(&mut d, DVec2::new(-50.0, 0.0));
        assert!((d.eye - camera().eye).length() < 1e-9);
    }

    #[test]
    fn pan_keeps_the_target_under_the_cursor() {
        let vp = DVec2::new(1280.0, 800.0);
        let mut c = camera();
        let before = c.project(vp, DVec3::ZERO).unwrap();
        pan(&mut c, DVec2::new(30.0, -12.0), vp);
        let after = c.project(vp, DVec3::ZERO).unwrap();
        assert!(
            (after - before - DVec2::new(30.0, -12.0)).length() < 1e-6,
            "{before} -> {after}"
        );
    }

    #[test]
    fn zoom_at_keeps_the_point_under_the_pointer_and_comes_closer() {
        let vp = DVec2::new(1280.0, 800.0);
        let pointer = DVec2::new(900.0, 250.0);
        let mut c = camera();
        let anchor = point_on_target_plane(&c, vp, pointer);
        let forward = c.forward();
        for notches in [1.0, 3.0, -2.0] {
            let before = c.distance();
            zoom_at(&mut c, notches, 1.0, anchor);
            let seen = c.project(vp, anchor).unwrap();
            assert!((seen - pointer).length() < 1e-6, "{seen} vs {pointer}");
            assert!((c.forward() - forward).length() < 1e-12, "the view turned");
            let expected = before * ZOOM_PER_NOTCH.powf(notches);
            assert!((c.distance() - expected).abs() < 1e-9 * expected);
        }
        // One notch is a fine step, and the eye stops short of the anchor.
        assert!((0.9..0.95).contains(&ZOOM_PER_NOTCH));
        zoom_at(&mut c, 1000.0, 2.0, anchor);
        assert!((c.distance() - 2.0).abs() < 1e-9);
    }

    #[test]
    fn zoom_moves_toward_the_target_and_stops_short() {
        let mut c = camera();
        zoom(&mut c, 1.0, 1.0);
        assert!(c.distance() < 300.0);
        zoom(&mut c, 1000.0, 2.0);
        assert!((c.distance() - 2.0).abs() < 1e-9);
        assert!(c.forward().dot(DVec3::Y) > 0.999);
    }
}
