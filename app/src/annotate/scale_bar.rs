//! The scale bar: a round length in millimetres and its length in pixels at the depth of the
//! camera's target (the point the view orbits, normally the middle of the scene). A perspective
//! view has no single scale; the bar is exact in the plane through the target facing the camera
//! and says so in its caption (`at target depth` is implied by the documentation, not drawn).

use cutter::Camera;

/// A scale bar's length in world millimetres and in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleBar {
    pub millimetres: f64,
    pub pixels: f64,
}

/// Pixels per millimetre at the target's depth for an image `height` pixels tall.
pub fn pixels_per_mm(camera: &Camera, height: u32) -> f64 {
    let visible_height_mm = 2.0 * camera.distance() * (camera.fov_y_deg.to_radians() * 0.5).tan();
    height as f64 / visible_height_mm
}

/// The longest round length (1, 2 or 5 × 10ⁿ mm) whose bar is at most `max_pixels` long; `None`
/// when the scale is degenerate.
pub fn scale_bar(camera: &Camera, height: u32, max_pixels: f64) -> Option<ScaleBar> {
    let per_mm = pixels_per_mm(camera, height);
    if !(per_mm.is_finite() && per_mm > 0.0 && max_pixels > 0.0) {
        return None;
    }
    let max_mm = max_pixels / per_mm;
    let decade = 10f64.powf(max_mm.log10().floor());
    let millimetres = [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&m| m <= max_mm)?;
    Some(ScaleBar {
        millimetres,
        pixels: millimetres * per_mm,
    })
}

/// The bar's caption: `50 mm`, `0.5 mm`.
pub fn caption(bar: &ScaleBar) -> String {
    let mm = bar.millimetres;
    if mm >= 1.0 {
        format!("{mm:.0} mm")
    } else {
        format!("{} mm", (mm * 1e6).round() / 1e6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn the_bar_spans_as_many_pixels_as_its_length_projects_to_at_the_target() {
        let camera = Camera {
            eye: DVec3::new(0.0, -250.0, 40.0),
            target: DVec3::new(0.0, 0.0, 40.0),
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        let size = DVec2::new(1200.0, 800.0);
        let bar = scale_bar(&camera, 800, 300.0).unwrap();
        assert_eq!(bar.millimetres, 50.0);
        assert!(bar.pixels <= 300.0);
        // Two points `millimetres` apart across the view at the target project that far apart.
        let a = camera.project(size, camera.target).unwrap();
        let b = camera
            .project(size, camera.target + DVec3::X * bar.millimetres)
            .unwrap();
        assert!(
            ((b - a).length() - bar.pixels).abs() < 1e-6,
            "{} {}",
            (b - a).length(),
            bar.pixels
        );
        assert_eq!(caption(&bar), "50 mm");
        let tiny = scale_bar(&camera, 800, 1.0).unwrap();
        assert!(tiny.millimetres < 1.0 && tiny.pixels <= 1.0);
        assert_eq!(
            caption(&ScaleBar {
                millimetres: 0.5,
                pixels: 1.0
            }),
            "0.5 mm"
        );
    }
}
