//! The opening of one vertex split into what the clock does not change and the clock's part.
//!
//! [`super::dffd`] moves a vertex within the support by
//! `ramp · φ · (δ + σ · (w / 2) · taper · l)`. Finding the vertex's side `σ` (a walk from the
//! lips), its nearest cut segment (which gives `l` and the distance in `φ`), its taper and its
//! path correction `δ` is nearly all of the cost; the ramp is one clamp. Between two steps of a
//! stroke most vertices of the opening only see their segment's ramp grow (the last half second
//! of path is still opening), so the live opening ([`super::live_opening`]) keeps a
//! [`FieldAt`] per vertex and only evaluates it again ([`FieldAt::opened`]) where nothing but
//! the clock changed. Both the opening from scratch and the kept one evaluate the same formula
//! on the same values, so they agree bit for bit.

use glam::DVec3;

use super::dffd::Inputs;
use super::step::CutSegment;

/// What the opening of one vertex inside the support is made of, apart from the clock (see the
/// module doc).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FieldAt {
    pub vertex: u32,
    /// The nearest cut segment (its ramp and its frame's lateral).
    pub segment: u32,
    /// Rest position.
    pub rest: DVec3,
    /// The nearest cut point (the taper is measured from it) and its distance.
    pub nearest: DVec3,
    pub dist: f64,
    /// The side of the cut, `±1`.
    pub sigma: f64,
    pub taper: f64,
    /// `φ(dist / r)`.
    pub falloff: f64,
    /// The blended path correction at the vertex, before the ramp and the falloff scale it
    /// (zero when the lips are not moved onto the drawn path).
    pub correction: DVec3,
}

/// The taper at nearest cut point `c`: from 0 at a crack tip of `tips` to 1 `taper_len` from
/// the nearest.
#[inline]
pub(crate) fn taper_at(tips: &[DVec3], c: DVec3, taper_len: f64) -> f64 {
    let tip_dist = tips
        .iter()
        .map(|t| t.distance(c))
        .fold(f64::INFINITY, f64::min);
    let x = (tip_dist / taper_len).min(1.0);
    x * x * (3.0 - 2.0 * x)
}

impl FieldAt {
    /// The vertex's opened position and the path correction it holds at this clock, `None` when
    /// it does not move (its segment has not begun to open, or it sits at a crack tip).
    #[inline]
    pub fn opened(&self, inputs: &Inputs, segments: &[CutSegment]) -> Option<(DVec3, DVec3)> {
        let i = self.segment as usize;
        let ramp = inputs.ramp(segments[i].time);
        let lateral = inputs.frames[i].lateral;
        let amount = self.sigma * 0.5 * inputs.width * ramp * self.taper * self.falloff;
        let correction = if inputs.onto_path {
            self.correction * (ramp * self.falloff)
        } else {
            DVec3::ZERO
        };
        (amount != 0.0 || correction != DVec3::ZERO)
            .then(|| (self.rest + correction + lateral * amount, correction))
    }
}
