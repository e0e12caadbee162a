//! The one place the image tolerances of the end-to-end tests are set, shared by the golden
//! images (`tests/render/`) and the window's exports (`tests/window/gui/`). Included with `#[path]`; not a test
//! target of its own.
//!
//! A pixel differs when any channel is off by more than the tolerance's `channel`; at most the
//! share `max_differing` of the pixels may differ, and the mean absolute channel difference must
//! stay at or under `max_mean`.
//!
//! - [`GOLDEN`]: a deterministic render (no supersampling, lavapipe) against its golden image at
//!   full size. Measured noise on lavapipe: none, within a run (the same state rendered twice)
//!   and across runs (goldens written by one process, compared in another): 0 pixels differ,
//!   mean 0.000. The tolerance is just above that (a handful of pixels one or two levels off,
//!   for a rebuilt rasterizer), far below a moved feature: a 10 × 10 patch of another colour, or
//!   a sphere moved by a few pixels, fails (`render/goldens.rs` shows both).
//! - [`SAME_PICTURE`]: one picture made two ways (the window's export against its 3D view or
//!   against `cutaway render`), supersampled by different paths. Measured: the 1× export against
//!   the view, 0 of 680 130 pixels off by more than 24 (largest 1); the 2× transparent export
//!   composited against `cutaway render`, 803 of 2 720 520 (0.03 %, edge pixels), mean 0.007.
//!   The tolerance allows three times that.

/// How much two images may differ and still count as the same picture.
#[derive(Clone, Copy, Debug)]
pub struct Tolerance {
    /// A pixel differs when one of its channels is off by more than this.
    pub channel: i32,
    /// Share of the pixels allowed to differ.
    pub max_differing: f64,
    /// Mean absolute channel difference allowed (0–255).
    pub max_mean: f64,
}

/// Golden images (see the module docs for the measured noise): 20 pixels of 1280 × 800.
#[allow(dead_code)] // the golden images' binary (`render.rs`) only
pub const GOLDEN: Tolerance = Tolerance {
    channel: 2,
    max_differing: 20.0 / (1280.0 * 800.0),
    max_mean: 0.01,
};

/// The same picture made by two paths of the app.
#[allow(dead_code)] // the window's binary (`gui.rs`) only
pub const SAME_PICTURE: Tolerance = Tolerance {
    channel: 24,
    max_differing: 0.001,
    max_mean: 0.05,
};

/// How two images of the same size differ.
#[derive(Clone, Copy, Debug)]
pub struct Difference {
    /// Pixels with a channel off by more than the tolerance's `channel`.
    pub differing: usize,
    pub pixels: usize,
    /// Mean absolute channel difference.
    pub mean: f64,
    /// The largest channel difference anywhere.
    pub largest: i32,
}

impl Difference {
    /// True when the images count as the same picture under `tolerance`.
    pub fn within(&self, tolerance: &Tolerance) -> bool {
        self.differing as f64 <= tolerance.max_differing * self.pixels as f64
            && self.mean <= tolerance.max_mean
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} of {} pixels differ, mean channel difference {:.3}, largest {}",
            self.differing, self.pixels, self.mean, self.largest
        )
    }
}

/// Compares two images of the same size under `tolerance`'s channel threshold (panics when the
/// sizes differ).
pub fn difference(
    actual: &image::RgbaImage,
    expected: &image::RgbaImage,
    tolerance: &Tolerance,
) -> Difference {
    assert_eq!(
        actual.dimensions(),
        expected.dimensions(),
        "image sizes differ"
    );
    let (mut differing, mut sum, mut largest) = (0usize, 0u64, 0i32);
    for (a, e) in actual.pixels().zip(expected.pixels()) {
        let d = (0..4)
            .map(|k| (a[k] as i32 - e[k] as i32).abs())
            .max()
            .unwrap_or(0);
        sum += (0..4)
            .map(|k| (a[k] as i32 - e[k] as i32).unsigned_abs() as u64)
            .sum::<u64>();
        largest = largest.max(d);
        if d > tolerance.channel {
            differing += 1;
        }
    }
    let pixels = (actual.width() * actual.height()) as usize;
    Difference {
        differing,
        pixels,
        mean: sum as f64 / (4.0 * pixels.max(1) as f64),
        largest,
    }
}
