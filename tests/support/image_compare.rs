//! The one place the image tolerances of the end-to-end tests are set, shared by the golden
//! images (`tests/render/`) and the window's exports (`tests/window/gui/`). Included with `#[path]`; not a test
//! target of its own.
//!
//! A pixel differs when any channel is off by more than [`CHANNEL_TOLERANCE`]; at most
//! [`MAX_DIFFERING`] of the pixels may differ, and the mean absolute channel difference must stay
//! under [`MAX_MEAN`]. (Software rasterizers of different LLVM versions move a few edge pixels; a
//! real change moves hundreds.)

pub const CHANNEL_TOLERANCE: i32 = 24;
pub const MAX_DIFFERING: f64 = 0.01;
pub const MAX_MEAN: f64 = 1.5;

/// How two images of the same size differ.
#[derive(Clone, Copy, Debug)]
pub struct Difference {
    /// Pixels with a channel off by more than [`CHANNEL_TOLERANCE`].
    pub differing: usize,
    pub pixels: usize,
    /// Mean absolute channel difference.
    pub mean: f64,
}

impl Difference {
    /// True when the images count as the same picture.
    pub fn within_tolerance(&self) -> bool {
        self.differing as f64 <= MAX_DIFFERING * self.pixels as f64 && self.mean <= MAX_MEAN
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} of {} pixels differ, mean channel difference {:.2}",
            self.differing, self.pixels, self.mean
        )
    }
}

/// Compares two images of the same size (panics when the sizes differ).
pub fn difference(actual: &image::RgbaImage, expected: &image::RgbaImage) -> Difference {
    assert_eq!(
        actual.dimensions(),
        expected.dimensions(),
        "image sizes differ"
    );
    let mut differing = 0usize;
    let mut sum = 0u64;
    for (a, e) in actual.pixels().zip(expected.pixels()) {
        let d = (0..4)
            .map(|k| (a[k] as i32 - e[k] as i32).abs())
            .max()
            .unwrap_or(0);
        sum += (0..4)
            .map(|k| (a[k] as i32 - e[k] as i32).unsigned_abs() as u64)
            .sum::<u64>();
        if d > CHANNEL_TOLERANCE {
            differing += 1;
        }
    }
    let pixels = (actual.width() * actual.height()) as usize;
    Difference {
        differing,
        pixels,
        mean: sum as f64 / (4.0 * pixels.max(1) as f64),
    }
}
