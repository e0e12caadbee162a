//! The scene's saved rulers ([`crate::scene::ruler`]) drawn over a rendered picture, as the window draws
//! them over its view: a yellow line with black edges between the two ends, a dot at each end and
//! the length in millimetres in a yellow box beside the middle.

use glam::DVec2;
use image::RgbaImage;

use super::labelled::{disc, fill_rect, line_segment};
use super::layout::Rect;
use super::text::{Face, TextPainter};
use crate::scene::Scene;

const RULER: [u8; 4] = [255, 200, 0, 255];
const EDGE: [u8; 4] = [0, 0, 0, 255];

/// Draws every ruler of `scene` whose ends are in front of the camera; returns how many.
pub fn draw_rulers(image: &mut RgbaImage, scene: &Scene) -> usize {
    if scene.rulers.is_empty() {
        return 0;
    }
    let size = DVec2::new(image.width() as f64, image.height() as f64);
    let px = (image.height().min(image.width()) as f32 / 50.0).clamp(11.0, 26.0);
    let painter = TextPainter::new();
    let mut drawn = 0;
    for ruler in &scene.rulers {
        let project = |p| {
            scene
                .camera
                .project(size, p)
                .map(|q| [q.x as f32, q.y as f32])
        };
        let (Some(a), Some(b)) = (project(ruler.a), project(ruler.b)) else {
            continue;
        };
        let width = (px / 7.0).max(2.0);
        line_segment(image, a, b, width + 2.0, EDGE);
        line_segment(image, a, b, width, RULER);
        for end in [a, b] {
            disc(image, end, width * 1.6, EDGE);
            disc(image, end, width * 1.1, RULER);
        }
        let text = ruler.caption(scene.unit);
        let pad = px * 0.25;
        let (w, h) = (
            painter.width(Face::Sans, px, &text),
            painter.line_height(Face::Sans, px),
        );
        let middle = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
        let (x, y) = (middle[0] + px * 0.5, middle[1] - px * 0.5 - h);
        fill_rect(
            image,
            Rect {
                x: x - pad,
                y: y - pad,
                w: w + 2.0 * pad,
                h: h + 2.0 * pad,
            },
            RULER,
        );
        painter.draw(image, Face::Sans, px, x, y, &text, EDGE);
        drawn += 1;
    }
    drawn
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ruler::Ruler;
    use glam::DVec3;

    #[test]
    fn a_ruler_in_view_is_drawn_in_its_colour_and_one_behind_the_eye_is_not() {
        let mut scene = Scene::default();
        scene.camera.eye = DVec3::new(0.0, -100.0, 0.0);
        scene.camera.target = DVec3::ZERO;
        scene.rulers = vec![
            Ruler {
                a: DVec3::new(-10.0, 0.0, 0.0),
                b: DVec3::new(10.0, 0.0, 0.0),
            },
            Ruler {
                a: DVec3::new(0.0, -200.0, 0.0),
                b: DVec3::new(1.0, -200.0, 0.0),
            },
        ];
        let mut image = RgbaImage::from_pixel(200, 150, image::Rgba([255, 255, 255, 255]));
        assert_eq!(draw_rulers(&mut image, &scene), 1);
        // The middle of the line, at the image centre, is ruler-coloured.
        let p = image.get_pixel(100, 75);
        assert!(p[0] > 200 && p[1] > 150 && p[2] < 80, "{p:?}");
        // Above and below the line, far from the caption, stays white.
        assert_eq!(image.get_pixel(60, 40)[2], 255);
    }
}
