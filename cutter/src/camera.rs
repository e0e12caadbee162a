//! The pinhole camera shared by the editor (unprojecting mouse events) and the renderer.
//!
//! Conventions: right-handed world; the camera looks from `eye` toward `target` with `up` roughly
//! up on screen. View space is right-handed with the camera looking down −Z, +Y up, +X right.
//! Clip space depth runs 0 (near) to 1 (far), as wgpu expects. Pixel coordinates have their origin
//! at the top-left of the viewport with y growing downward; pixel centres are at half-integers but
//! a pixel coordinate `(x, y)` is used as given (no half-pixel shift), matching the gesture format.

use glam::{DMat4, DVec2, DVec3, DVec4};

use csg::Aabb;

/// A ray `origin + t * direction`, `direction` of unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    /// Unit length.
    pub direction: DVec3,
}

impl Ray {
    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }
}

/// A perspective camera (the `camera` object of the gesture and session formats).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    pub target: DVec3,
    /// Approximate up direction; must not be parallel to `target - eye`.
    pub up: DVec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub fov_y_deg: f64,
}

impl Camera {
    /// A camera looking at `bbox` from `direction` (pointing from the target toward the eye) at the
    /// distance that frames the whole box (see [`Camera::framing_distance`]).
    pub fn framing(bbox: &Aabb, direction: DVec3, up: DVec3, fov_y_deg: f64) -> Camera {
        let target = bbox.center();
        let distance = Camera::framing_distance(bbox, fov_y_deg);
        let dir = direction.try_normalize().unwrap_or(DVec3::NEG_Y);
        Camera {
            eye: target + dir * distance,
            target,
            up,
            fov_y_deg,
        }
    }

    /// Distance from the box centre at which the box's bounding sphere exactly fits the vertical
    /// field of view: `radius / sin(fov_y / 2)`. The thesis's scene increment is δ = this / 2000.
    pub fn framing_distance(bbox: &Aabb, fov_y_deg: f64) -> f64 {
        let radius = 0.5 * bbox.diagonal();
        let half = (fov_y_deg.clamp(1.0, 179.0) * 0.5).to_radians();
        radius / half.sin()
    }

    /// Distance from the eye to the target.
    pub fn distance(&self) -> f64 {
        (self.target - self.eye).length()
    }

    /// Unit viewing direction (from eye toward target).
    pub fn forward(&self) -> DVec3 {
        (self.target - self.eye)
            .try_normalize()
            .unwrap_or(DVec3::NEG_Z)
    }

    /// Orthonormal (right, true up, forward) basis of the camera in world space.
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let f = self.forward();
        let r = f
            .cross(self.up)
            .try_normalize()
            .or_else(|| f.cross(DVec3::Z).try_normalize())
            .or_else(|| f.cross(DVec3::X).try_normalize())
            .unwrap_or(DVec3::X);
        let u = r.cross(f);
        (r, u, f)
    }

    /// World → view transform (right-handed, looking down −Z).
    pub fn view_from_world(&self) -> DMat4 {
        let (r, u, f) = self.basis();
        let e = self.eye;
        DMat4::from_cols(
            DVec4::new(r.x, u.x, -f.x, 0.0),
            DVec4::new(r.y, u.y, -f.y, 0.0),
            DVec4::new(r.z, u.z, -f.z, 0.0),
            DVec4::new(-r.dot(e), -u.dot(e), f.dot(e), 1.0),
        )
    }

    /// View → clip transform: perspective with depth 0 at `near` and 1 at `far`.
    pub fn clip_from_view(&self, aspect: f64, near: f64, far: f64) -> DMat4 {
        let h = 1.0 / (self.fov_y_deg.to_radians() * 0.5).tan();
        let w = h / aspect;
        let range = far / (near - far);
        DMat4::from_cols(
            DVec4::new(w, 0.0, 0.0, 0.0),
            DVec4::new(0.0, h, 0.0, 0.0),
            DVec4::new(0.0, 0.0, range, -1.0),
            DVec4::new(0.0, 0.0, range * near, 0.0),
        )
    }

    /// World → clip transform for a viewport of `viewport` pixels.
    pub fn clip_from_world(&self, viewport: DVec2, near: f64, far: f64) -> DMat4 {
        self.clip_from_view(viewport.x / viewport.y.max(1.0), near, far) * self.view_from_world()
    }

    /// The ray from the eye through pixel `pixel` of a `viewport`-sized image.
    pub fn ray_through_pixel(&self, viewport: DVec2, pixel: DVec2) -> Ray {
        let (r, u, f) = self.basis();
        let tan_half = (self.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = viewport.x / viewport.y.max(1.0);
        let ndc_x = 2.0 * pixel.x / viewport.x.max(1.0) - 1.0;
        let ndc_y = 1.0 - 2.0 * pixel.y / viewport.y.max(1.0);
        let direction = (f + r * (ndc_x * tan_half * aspect) + u * (ndc_y * tan_half)).normalize();
        Ray {
            origin: self.eye,
            direction,
        }
    }

    /// Pixel position of world point `p`, or `None` when it is at or behind the eye plane.
    pub fn project(&self, viewport: DVec2, p: DVec3) -> Option<DVec2> {
        let (r, u, f) = self.basis();
        let d = p - self.eye;
        let z = d.dot(f);
        if z <= 0.0 {
            return None;
        }
        let tan_half = (self.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = viewport.x / viewport.y.max(1.0);
        let ndc_x = d.dot(r) / (z * tan_half * aspect);
        let ndc_y = d.dot(u) / (z * tan_half);
        Some(DVec2::new(
            (ndc_x + 1.0) * 0.5 * viewport.x,
            (1.0 - ndc_y) * 0.5 * viewport.y,
        ))
    }
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
    fn centre_pixel_ray_points_at_target() {
        let c = camera();
        let ray = c.ray_through_pixel(DVec2::new(1280.0, 800.0), DVec2::new(640.0, 400.0));
        assert!((ray.direction - DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn project_inverts_ray_through_pixel() {
        let c = camera();
        let vp = DVec2::new(1280.0, 800.0);
        for px in [
            DVec2::new(10.0, 20.0),
            DVec2::new(1000.0, 700.0),
            DVec2::new(640.0, 0.0),
        ] {
            let p = c.ray_through_pixel(vp, px).at(250.0);
            let back = c.project(vp, p).unwrap();
            assert!((back - px).length() < 1e-9, "{px} -> {back}");
        }
        // Screen right is world +X and screen up is world +Z for this camera.
        let right = c.project(vp, DVec3::new(10.0, 0.0, 0.0)).unwrap();
        let up = c.project(vp, DVec3::new(0.0, 0.0, 10.0)).unwrap();
        assert!(right.x > 640.0 && up.y < 400.0);
        assert!(c.project(vp, DVec3::new(0.0, -400.0, 0.0)).is_none());
    }

    #[test]
    fn clip_from_world_matches_project() {
        let c = camera();
        let vp = DVec2::new(1280.0, 800.0);
        let p = DVec3::new(12.0, 30.0, -7.0);
        let clip = c.clip_from_world(vp, 1.0, 1000.0) * p.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        let px = c.project(vp, p).unwrap();
        assert!(((ndc.x + 1.0) * 640.0 - px.x).abs() < 1e-9);
        assert!(((1.0 - ndc.y) * 400.0 - px.y).abs() < 1e-9);
        assert!(ndc.z > 0.0 && ndc.z < 1.0);
    }
}
