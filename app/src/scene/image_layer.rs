//! The scene's image layer: which image, its window, where it is shown and how it mixes with the
//! structure colour. Part of [`crate::scene::Scene`]; stored in sessions as the `"image"` object
//! (`crate::session::image`).

use std::sync::Arc;

use glam::DVec3;

use crate::io::intensity::{IntensityImage, Window};

/// What a wall shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WallDisplay {
    /// The structure's wall colour, as without an image.
    Color,
    /// The image in grey (window/level), shaded like the wall.
    #[default]
    Image,
    /// Half structure colour, half image.
    Blend,
}

impl WallDisplay {
    pub const ALL: [WallDisplay; 3] = [WallDisplay::Color, WallDisplay::Image, WallDisplay::Blend];

    pub fn name(self) -> &'static str {
        match self {
            WallDisplay::Color => "color",
            WallDisplay::Image => "image",
            WallDisplay::Blend => "blend",
        }
    }

    pub fn parse(name: &str) -> Option<WallDisplay> {
        WallDisplay::ALL.into_iter().find(|d| d.name() == name)
    }

    /// How much of the image goes into the colour: 0, 1 or ½.
    pub fn image_weight(self) -> f32 {
        match self {
            WallDisplay::Color => 0.0,
            WallDisplay::Image => 1.0,
            WallDisplay::Blend => 0.5,
        }
    }
}

/// An image shown in the scene. Cheap to clone (the image is shared).
#[derive(Clone, Debug)]
pub struct ImageLayer {
    pub image: Arc<IntensityImage>,
    pub window: Window,
    /// Walls (and the walls of slices) show the image.
    pub on_walls: bool,
    /// Slices and ribbons show the image on their outer surface.
    pub on_slices: bool,
    pub display: WallDisplay,
}

impl ImageLayer {
    /// `image` with its default window, shown on walls and slices.
    pub fn new(image: Arc<IntensityImage>) -> ImageLayer {
        ImageLayer {
            window: Window::default_for(&image),
            image,
            on_walls: true,
            on_slices: true,
            display: WallDisplay::Image,
        }
    }

    /// The sRGB colour (0..=1) a surface of colour `base` shows at world point `p`: the grey of
    /// the windowed image mixed with `base` by [`WallDisplay::image_weight`]; `base` outside the
    /// image. The renderer's shader does the same per fragment (`image.wgsl`).
    pub fn color_at(&self, p: DVec3, base: [f32; 3]) -> [f32; 3] {
        let weight = self.display.image_weight();
        match self.image.sample_world(p) {
            Some(v) if weight > 0.0 => {
                let grey = self.window.map(v) as f32;
                base.map(|c| c + (grey - c) * weight)
            }
            _ => base,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DAffine3;

    use super::*;
    use crate::io::intensity::SampleKind;

    #[test]
    fn layer_colour_mixes_by_display() {
        let img = Arc::new(
            IntensityImage::new(
                "t".into(),
                [2, 1, 1],
                DAffine3::IDENTITY,
                SampleKind::I16,
                [0i16, 100].iter().flat_map(|v| v.to_le_bytes()).collect(),
                (1.0, 0.0),
            )
            .unwrap(),
        );
        let mut layer = ImageLayer::new(img);
        layer.window = Window {
            level: 50.0,
            width: 100.0,
        };
        let base = [1.0, 0.0, 0.0];
        assert_eq!(layer.color_at(DVec3::ZERO, base), [0.0, 0.0, 0.0]);
        assert_eq!(layer.color_at(DVec3::X, base), [1.0, 1.0, 1.0]);
        layer.display = WallDisplay::Blend;
        assert_eq!(layer.color_at(DVec3::ZERO, base), [0.5, 0.0, 0.0]);
        layer.display = WallDisplay::Color;
        assert_eq!(layer.color_at(DVec3::X, base), base);
        assert_eq!(layer.color_at(DVec3::splat(50.0), base), base, "outside");
    }
}
