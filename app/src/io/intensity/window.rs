//! Window/level: which intensity range is spread from black to white, as in a radiology viewer.
//! `level` is the centre, `width` the range; values below are black, above white.

use super::IntensityImage;

/// A window on the intensity axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    pub level: f64,
    pub width: f64,
}

/// The usual radiology windows (Hounsfield units for CT) and the automatic one for other images.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WindowPreset {
    SoftTissue,
    Lung,
    Bone,
    Brain,
    /// From the image's own values: the 1st to the 99th percentile (MR, whatever its units).
    Auto,
}

impl WindowPreset {
    pub const ALL: [WindowPreset; 5] = [
        WindowPreset::SoftTissue,
        WindowPreset::Lung,
        WindowPreset::Bone,
        WindowPreset::Brain,
        WindowPreset::Auto,
    ];

    /// The name on the command line, in the GUI and in messages.
    pub fn name(self) -> &'static str {
        match self {
            WindowPreset::SoftTissue => "soft-tissue",
            WindowPreset::Lung => "lung",
            WindowPreset::Bone => "bone",
            WindowPreset::Brain => "brain",
            WindowPreset::Auto => "auto",
        }
    }

    pub fn parse(name: &str) -> Option<WindowPreset> {
        WindowPreset::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The window this preset gives for `image` (only [`WindowPreset::Auto`] looks at it).
    pub fn window(self, image: &IntensityImage) -> Window {
        let fixed = |level, width| Window { level, width };
        match self {
            WindowPreset::SoftTissue => fixed(40.0, 400.0),
            WindowPreset::Lung => fixed(-600.0, 1500.0),
            WindowPreset::Bone => fixed(400.0, 1800.0),
            WindowPreset::Brain => fixed(40.0, 80.0),
            WindowPreset::Auto => Window::from_percentiles(image, 0.01, 0.99),
        }
    }
}

impl Window {
    /// Narrowest width accepted (a zero width would divide by zero).
    pub const MIN_WIDTH: f64 = 1e-6;

    /// The window from the `low` to the `high` quantile of the image's values (sampled at up to
    /// a million voxels spread over the grid, so a large scan costs milliseconds).
    pub fn from_percentiles(image: &IntensityImage, low: f64, high: f64) -> Window {
        let mut values = image.spread_samples(1 << 20);
        if values.is_empty() {
            return Window {
                level: 0.0,
                width: 1.0,
            };
        }
        values.sort_unstable_by(f64::total_cmp);
        let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
        let (lo, hi) = (at(low), at(high));
        Window {
            level: (lo + hi) / 2.0,
            width: (hi - lo).max(Window::MIN_WIDTH),
        }
    }

    /// The window a freshly opened image gets: soft tissue for a CT (values in Hounsfield units,
    /// air near -1000), else the percentile window.
    pub fn default_for(image: &IntensityImage) -> Window {
        let (lo, hi) = image.range();
        if (-3100.0..=-900.0).contains(&lo) && hi >= 0.0 {
            WindowPreset::SoftTissue.window(image)
        } else {
            WindowPreset::Auto.window(image)
        }
    }

    /// A window from the command line: a preset name (`soft-tissue`, `lung`, `bone`, `brain`,
    /// `auto`) or `LEVEL,WIDTH`.
    pub fn parse(text: &str, image: &IntensityImage) -> anyhow::Result<Window> {
        if let Some(preset) = WindowPreset::parse(text) {
            return Ok(preset.window(image));
        }
        let numbers: Vec<f64> = text
            .split(',')
            .map(|t| t.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| anyhow::anyhow!("window {text:?} is not a preset (soft-tissue, lung, bone, brain, auto) or LEVEL,WIDTH"))?;
        match numbers.as_slice() {
            [level, width] if level.is_finite() && width.is_finite() && *width > 0.0 => {
                Ok(Window {
                    level: *level,
                    width: *width,
                })
            }
            _ => anyhow::bail!("window {text:?} needs LEVEL,WIDTH with a positive width"),
        }
    }

    /// Lowest value shown above black.
    pub fn low(&self) -> f64 {
        self.level - self.width / 2.0
    }

    /// `value` as a grey level in 0..=1.
    pub fn map(&self, value: f64) -> f64 {
        ((value - self.low()) / self.width.max(Window::MIN_WIDTH)).clamp(0.0, 1.0)
    }

    /// The window after a mouse drag of (`dx`, `dy`) pixels, as radiology viewers do it: right
    /// widens, down raises the level; `scale` is the intensity change per pixel.
    pub fn dragged(&self, dx: f64, dy: f64, scale: f64) -> Window {
        Window {
            level: self.level + dy * scale,
            width: (self.width + dx * scale * 2.0).max(Window::MIN_WIDTH),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DAffine3;

    #[test]
    fn map_clamps_outside_the_window_and_is_linear_inside() {
        let w = Window {
            level: 40.0,
            width: 400.0,
        };
        assert_eq!(w.map(-1000.0), 0.0);
        assert_eq!(w.map(1000.0), 1.0);
        assert_eq!(w.map(40.0), 0.5);
        assert!((w.map(-60.0) - 0.25).abs() < 1e-12);
        let d = w.dragged(10.0, -5.0, 2.0);
        assert_eq!((d.level, d.width), (30.0, 440.0));
        assert!(w.dragged(-1e6, 0.0, 1.0).width > 0.0);
    }

    #[test]
    fn presets_and_the_automatic_window() {
        let ct = IntensityImage::from_fn([8, 8, 8], DAffine3::IDENTITY, |p| {
            if p.x < 4.0 { -1000.0 } else { 60.0 }
        });
        assert_eq!(
            Window::default_for(&ct),
            WindowPreset::SoftTissue.window(&ct)
        );
        assert_eq!(WindowPreset::Lung.window(&ct).level, -600.0);
        assert_eq!(WindowPreset::parse("bone"), Some(WindowPreset::Bone));
        assert_eq!(WindowPreset::parse("liver"), None);
        assert_eq!(Window::parse("lung", &ct).unwrap().width, 1500.0);
        assert_eq!(Window::parse("-500, 1000", &ct).unwrap().level, -500.0);
        assert!(Window::parse("1,0", &ct).is_err());
        assert!(
            Window::parse("wide", &ct)
                .unwrap_err()
                .to_string()
                .contains("preset")
        );
        // An MR-like ramp 0..=999 along x: the auto window spans about its 1st..99th percentile.
        let mr = IntensityImage::from_fn([1000, 2, 2], DAffine3::IDENTITY, |p| p.x as f32);
        let w = Window::default_for(&mr);
        assert!((w.low() - 10.0).abs() <= 2.0, "{w:?}");
        assert!((w.low() + w.width - 989.0).abs() <= 2.0, "{w:?}");
    }
}
