//! Zoom to fit: move the camera along its viewing direction so a box fills the view, keeping
//! the direction the user chose (a preset or an orbit) instead of resetting it.

use csg::Aabb;
use cutter::Camera;

/// `camera` looking at the centre of `bbox` from its current direction, at the distance where
/// the box's bounding sphere fits the narrower of the two fields of view of a viewport with
/// `aspect` = width / height. An empty box leaves the camera as it is.
pub fn fit_to_box(camera: &Camera, bbox: &Aabb, aspect: f64) -> Camera {
    let d = bbox.diagonal();
    if bbox.is_empty() || !d.is_finite() || d <= 0.0 {
        return *camera;
    }
    let radius = 0.5 * d;
    let half_y = (camera.fov_y_deg.clamp(1.0, 179.0) * 0.5).to_radians();
    let half_x = (half_y.tan() * aspect.max(1e-3)).atan();
    let half = half_y.min(half_x);
    // A little margin so the silhouette does not touch the border.
    let distance = 1.05 * radius / half.sin();
    let target = bbox.center();
    Camera {
        eye: target - camera.forward() * distance,
        target,
        up: camera.basis().1,
        fov_y_deg: camera.fov_y_deg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn the_fitted_box_is_inside_the_view_and_the_direction_is_kept() {
        let camera = Camera {
            eye: DVec3::new(300.0, -200.0, 50.0),
            target: DVec3::new(5.0, 5.0, 5.0),
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        let mut bbox = Aabb::EMPTY;
        bbox.grow(DVec3::new(100.0, 100.0, 100.0));
        bbox.grow(DVec3::new(110.0, 130.0, 140.0));
        for vp in [DVec2::new(1280.0, 800.0), DVec2::new(400.0, 900.0)] {
            let fitted = fit_to_box(&camera, &bbox, vp.x / vp.y);
            assert!((fitted.forward() - camera.forward()).length() < 1e-9);
            assert!((fitted.target - bbox.center()).length() < 1e-9);
            for x in [bbox.min.x, bbox.max.x] {
                for y in [bbox.min.y, bbox.max.y] {
                    for z in [bbox.min.z, bbox.max.z] {
                        let p = fitted.project(vp, DVec3::new(x, y, z)).unwrap();
                        assert!(p.x >= 0.0 && p.x <= vp.x && p.y >= 0.0 && p.y <= vp.y);
                    }
                }
            }
            // Not absurdly far: the box's sphere spans at least half the narrower side.
            let r = fitted.project(vp, bbox.center() + fitted.basis().0 * 0.5 * bbox.diagonal());
            let span = (r.unwrap() - vp * 0.5).length() * 2.0;
            assert!(span > 0.5 * vp.x.min(vp.y), "{span}");
        }
    }
}
