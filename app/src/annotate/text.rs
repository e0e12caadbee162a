//! Text drawn into an RGBA image: glyph outlines of the fonts egui bundles (Ubuntu Light for
//! prose, Hack for tables whose columns must line up), laid out with kerning and rasterized with
//! coverage anti-aliasing by `ab_glyph`. Used for the metrics table of `cutaway compare` and
//! the labels of exported images.

use ab_glyph::{Font as _, FontRef, PxScale, ScaleFont as _};
use image::RgbaImage;

/// Which of the bundled fonts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// Proportional (Ubuntu Light).
    Sans,
    /// Monospaced (Hack): every character has the same advance.
    Mono,
}

/// The bundled fonts, parsed once.
pub struct TextPainter {
    sans: FontRef<'static>,
    mono: FontRef<'static>,
}

impl Default for TextPainter {
    fn default() -> TextPainter {
        TextPainter::new()
    }
}

impl TextPainter {
    pub fn new() -> TextPainter {
        // The fonts are compiled in (not input): a parse failure is a broken build.
        let parse = |bytes: &'static [u8]| {
            FontRef::try_from_slice(bytes).expect("egui's bundled font parses")
        };
        TextPainter {
            sans: parse(epaint_default_fonts::UBUNTU_LIGHT),
            mono: parse(epaint_default_fonts::HACK_REGULAR),
        }
    }

    fn font(&self, face: Face) -> &FontRef<'static> {
        match face {
            Face::Sans => &self.sans,
            Face::Mono => &self.mono,
        }
    }

    /// Height of one line of text at `px` pixels (ascent − descent + line gap).
    pub fn line_height(&self, face: Face, px: f32) -> f32 {
        let f = self.font(face).as_scaled(PxScale::from(px));
        f.ascent() - f.descent() + f.line_gap()
    }

    /// Width in pixels of `text` on one line at `px` pixels.
    pub fn width(&self, face: Face, px: f32, text: &str) -> f32 {
        self.layout(face, px, text).1
    }

    /// Each glyph with its pen position from the start of the line, and where the line ends.
    fn layout(&self, face: Face, px: f32, text: &str) -> (Vec<(ab_glyph::GlyphId, f32)>, f32) {
        let f = self.font(face).as_scaled(PxScale::from(px));
        let mut glyphs = Vec::with_capacity(text.len());
        let mut pen = 0.0;
        let mut previous = None;
        for c in text.chars() {
            let id = f.glyph_id(c);
            if let Some(p) = previous {
                pen += f.kern(p, id);
            }
            glyphs.push((id, pen));
            pen += f.h_advance(id);
            previous = Some(id);
        }
        (glyphs, pen)
    }

    /// Draws `text` on one line with its top-left corner at (`x`, `top`), blending `color`
    /// (straight-alpha RGBA) over the image by glyph coverage; pixels outside the image are
    /// skipped.
    pub fn draw(
        &self,
        image: &mut RgbaImage,
        face: Face,
        px: f32,
        x: f32,
        top: f32,
        text: &str,
        color: [u8; 4],
    ) {
        let font = self.font(face);
        let scale = PxScale::from(px);
        let baseline = top + font.as_scaled(scale).ascent();
        for (id, pen) in self.layout(face, px, text).0 {
            let glyph = id.with_scale_and_position(scale, ab_glyph::point(x + pen, baseline));
            let Some(outlined) = font.outline_glyph(glyph) else {
                continue; // a space
            };
            let bounds = outlined.px_bounds();
            outlined.draw(|gx, gy, coverage| {
                let px_x = bounds.min.x as i64 + gx as i64;
                let px_y = bounds.min.y as i64 + gy as i64;
                if px_x < 0
                    || px_y < 0
                    || px_x >= image.width() as i64
                    || px_y >= image.height() as i64
                {
                    return;
                }
                blend(
                    image.get_pixel_mut(px_x as u32, px_y as u32),
                    color,
                    coverage,
                );
            });
        }
    }
}

/// `color` over `pixel` with `coverage` × its alpha.
pub fn blend(pixel: &mut image::Rgba<u8>, color: [u8; 4], coverage: f32) {
    let a = (coverage.clamp(0.0, 1.0) * color[3] as f32 / 255.0).clamp(0.0, 1.0);
    for k in 0..3 {
        let under = pixel[k] as f32;
        pixel[k] = (under + (color[k] as f32 - under) * a).round() as u8;
    }
    let under_a = pixel[3] as f32 / 255.0;
    pixel[3] = ((under_a + a * (1.0 - under_a)) * 255.0).round() as u8;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ink(image: &RgbaImage) -> Vec<(u32, u32)> {
        image
            .enumerate_pixels()
            .filter(|(_, _, p)| p[0] < 128)
            .map(|(x, y, _)| (x, y))
            .collect()
    }

    #[test]
    fn text_is_drawn_inside_its_measured_box() {
        let painter = TextPainter::new();
        let mut image = RgbaImage::from_pixel(200, 40, image::Rgba([255, 255, 255, 255]));
        let width = painter.width(Face::Sans, 20.0, "Cutaway 12 mm");
        assert!((80.0..200.0).contains(&width), "{width}");
        painter.draw(
            &mut image,
            Face::Sans,
            20.0,
            10.0,
            5.0,
            "Cutaway 12 mm",
            [0, 0, 0, 255],
        );
        let pixels = ink(&image);
        assert!(pixels.len() > 100, "{} dark pixels", pixels.len());
        let line = painter.line_height(Face::Sans, 20.0);
        for &(x, y) in &pixels {
            assert!(x as f32 >= 9.0 && x as f32 <= 10.0 + width + 1.0, "x {x}");
            assert!(y as f32 >= 5.0 && y as f32 <= 5.0 + line + 1.0, "y {y}");
        }
        // Different text draws different pixels.
        let mut other = RgbaImage::from_pixel(200, 40, image::Rgba([255, 255, 255, 255]));
        painter.draw(
            &mut other,
            Face::Sans,
            20.0,
            10.0,
            5.0,
            "Cutaway 13 mm",
            [0, 0, 0, 255],
        );
        assert_ne!(ink(&other), pixels);
    }

    #[test]
    fn mono_columns_line_up_and_offscreen_text_is_clipped() {
        let painter = TextPainter::new();
        let a = painter.width(Face::Mono, 14.0, "iiii");
        let b = painter.width(Face::Mono, 14.0, "WWWW");
        assert!((a - b).abs() < 1e-3, "{a} {b}");
        assert!(painter.width(Face::Sans, 14.0, "iiii") < painter.width(Face::Sans, 14.0, "WWWW"));
        let mut image = RgbaImage::from_pixel(20, 20, image::Rgba([255, 255, 255, 255]));
        painter.draw(
            &mut image,
            Face::Sans,
            30.0,
            -50.0,
            -5.0,
            "far away text",
            [0, 0, 0, 255],
        );
        painter.draw(
            &mut image,
            Face::Sans,
            30.0,
            500.0,
            500.0,
            "far",
            [0, 0, 0, 255],
        );
    }
}
