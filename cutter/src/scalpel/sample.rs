//! A committed step's tool sample, as the scalpel records it for the opening
//! ([`super::drawn`]). Its own module so that the scalpel (`step`) records samples without
//! depending on the opening that reads them.

use glam::DVec3;

/// One committed step's tool sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Number of the stroke (the strokes committed before it).
    pub stroke: usize,
    /// Tool clock of the step (the time of the segments it cut).
    pub time: f64,
    /// The sample as the tool gave it.
    pub point: DVec3,
}

impl Sample {
    pub fn new(stroke: usize, time: f64, point: DVec3) -> Sample {
        Sample {
            stroke,
            time,
            point,
        }
    }
}
