//! The risk map: cut walls coloured by their distance to the structures a planner marks
//! critical, as liver-surgery planners read risk maps around vessels.
//!
//! A wall point closer than [`RiskSettings::near_mm`] to a critical structure is red; from there
//! to [`RiskSettings::far_mm`] its colour is graded from orange to yellow; beyond it the wall
//! shows what it shows without the map (its wall colour, or the intensity image). The steps at
//! both distances are sharp, so the 2 mm and 10 mm lines can be read off the wall; the legend
//! draws the same ramp ([`RiskSettings::color_at`]).
//!
//! The distances themselves are computed per wall vertex by `crate::cutting::wall_risk`; this
//! file holds only what the user chose and what the colours mean, shared by the renderer, the
//! glTF export and the legends. Stored in sessions as the `"risk"` object
//! (`crate::session::risk`).

/// Red: a wall point within [`RiskSettings::near_mm`] of a critical structure (sRGB).
pub const RISK_NEAR_COLOR: [f32; 3] = [0.86, 0.06, 0.06];
/// The graded band's colour just past `near_mm` (sRGB orange).
pub const RISK_BAND_START: [f32; 3] = [1.0, 0.47, 0.0];
/// The graded band's colour at `far_mm` (sRGB yellow).
pub const RISK_BAND_END: [f32; 3] = [1.0, 0.9, 0.22];

/// The legend's swatch for "beyond the far distance" (sRGB): a cream like the walls' tint,
/// standing for the wall's own colour.
pub const LEGEND_BEYOND: [f32; 3] = [0.96, 0.92, 0.8];

/// Which structures are critical and where the walls warn. Default: none critical, 2 mm and
/// 10 mm, shown.
#[derive(Clone, Debug, PartialEq)]
pub struct RiskSettings {
    /// Names of the critical structures, as the model list names them, in the order marked (a
    /// name matches every model of that name).
    pub critical: Vec<String>,
    /// Walls closer than this to a critical structure are red (mm, ≥ 0).
    pub near_mm: f64,
    /// Walls up to this far are graded; beyond it they keep their colour (mm, > `near_mm`).
    pub far_mm: f64,
    /// Whether the walls are coloured; the critical set is kept while it is off.
    pub shown: bool,
}

impl Default for RiskSettings {
    fn default() -> RiskSettings {
        RiskSettings {
            critical: Vec::new(),
            near_mm: RiskSettings::NEAR_MM,
            far_mm: RiskSettings::FAR_MM,
            shown: true,
        }
    }
}

impl RiskSettings {
    /// The default red distance (mm).
    pub const NEAR_MM: f64 = 2.0;
    /// The default end of the graded band (mm).
    pub const FAR_MM: f64 = 10.0;
    /// The largest distance either may be set to (mm).
    pub const MAX_MM: f64 = 1000.0;

    /// Whether the walls are coloured: shown, with at least one critical structure.
    pub fn is_on(&self) -> bool {
        self.shown && !self.critical.is_empty()
    }

    /// Checks the distances: finite, `0 ≤ near < far ≤` [`RiskSettings::MAX_MM`].
    pub fn check(&self) -> Result<(), String> {
        let (near, far) = (self.near_mm, self.far_mm);
        if !(near.is_finite()
            && far.is_finite()
            && 0.0 <= near
            && near < far
            && far <= Self::MAX_MM)
        {
            return Err(format!(
                "near_mm {near} and far_mm {far} must satisfy 0 <= near_mm < far_mm <= {}",
                Self::MAX_MM
            ));
        }
        if let Some(name) = self.critical.iter().find(|n| n.trim().is_empty()) {
            return Err(format!("critical structure name {name:?} is blank"));
        }
        Ok(())
    }

    /// Where `distance_mm` lies on the ramp: ≤ 0 red, 0..1 the graded band, ≥ 1 beyond it. The
    /// renderer interpolates this per fragment and maps it with the same three colours.
    pub fn ramp_position(&self, distance_mm: f64) -> f32 {
        ((distance_mm - self.near_mm) / (self.far_mm - self.near_mm)) as f32
    }

    /// The legend bar spans 0 to this distance (mm): the far distance and a quarter more, so
    /// the swatch beyond it shows.
    pub fn legend_span_mm(&self) -> f64 {
        self.far_mm * 1.25
    }

    /// The legend bar's colour (sRGB) at fraction `x` (0..=1) of its length, left to right.
    pub fn legend_color(&self, x: f64) -> [f32; 3] {
        self.color_at(x * self.legend_span_mm())
            .unwrap_or(LEGEND_BEYOND)
    }

    /// The legend's marks, each a fraction of the bar's length and its caption: 0, the near and
    /// the far distance.
    pub fn legend_marks(&self) -> [(f64, String); 3] {
        let span = self.legend_span_mm();
        [
            (0.0, "0".to_string()),
            (self.near_mm / span, mm_caption(self.near_mm)),
            (self.far_mm / span, mm_caption(self.far_mm)),
        ]
    }

    /// The colour (sRGB) a wall point at `distance_mm` shows, `None` beyond `far_mm` (the wall
    /// keeps its own colour). Colours are mixed in linear light, as the renderer mixes them.
    pub fn color_at(&self, distance_mm: f64) -> Option<[f32; 3]> {
        ramp_color(self.ramp_position(distance_mm))
    }
}

/// `2 mm`, `1.5 mm`.
fn mm_caption(mm: f64) -> String {
    let rounded = (mm * 100.0).round() / 100.0;
    format!("{rounded} mm")
}

/// The colour (sRGB) at ramp position `s` ([`RiskSettings::ramp_position`]), `None` for
/// `s ≥ 1`.
pub fn ramp_color(s: f32) -> Option<[f32; 3]> {
    if s.is_nan() || s >= 1.0 {
        return None;
    }
    if s <= 0.0 {
        return Some(RISK_NEAR_COLOR);
    }
    Some(std::array::from_fn(|k| {
        let (a, b) = (
            srgb_to_linear(RISK_BAND_START[k]),
            srgb_to_linear(RISK_BAND_END[k]),
        );
        linear_to_srgb(a + (b - a) * s)
    }))
}

/// sRGB-encoded component → linear light (the renderer's conversion; the scene layer cannot
/// import the renderer).
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_is_red_near_graded_in_the_band_and_absent_beyond() {
        let risk = RiskSettings::default();
        assert_eq!(risk.color_at(0.0), Some(RISK_NEAR_COLOR));
        assert_eq!(risk.color_at(2.0), Some(RISK_NEAR_COLOR));
        let just_past = risk.color_at(2.001).unwrap();
        assert!(
            (just_past[1] - RISK_BAND_START[1]).abs() < 1e-3,
            "{just_past:?}"
        );
        let mid = risk.color_at(6.0).unwrap();
        assert!(
            mid[1] > RISK_BAND_START[1] && mid[1] < RISK_BAND_END[1],
            "{mid:?}"
        );
        let end = risk.color_at(9.9999).unwrap();
        assert!((end[1] - RISK_BAND_END[1]).abs() < 1e-3, "{end:?}");
        assert_eq!(risk.color_at(10.0), None);
        assert_eq!(risk.color_at(50.0), None);
    }

    #[test]
    fn the_legend_marks_its_distances_where_its_colours_change() {
        let risk = RiskSettings::default();
        let marks = risk.legend_marks();
        assert_eq!(marks[1].1, "2 mm");
        assert_eq!(marks[2].1, "10 mm");
        let (near, far) = (marks[1].0, marks[2].0);
        assert_eq!(risk.legend_color(near - 1e-3), RISK_NEAR_COLOR);
        assert_ne!(risk.legend_color(near + 1e-3), RISK_NEAR_COLOR);
        assert_ne!(risk.legend_color(far - 1e-3), LEGEND_BEYOND);
        assert_eq!(risk.legend_color(far + 1e-3), LEGEND_BEYOND);
        assert_eq!(risk.legend_color(1.0), LEGEND_BEYOND);
    }

    #[test]
    fn distances_are_checked() {
        let ok = RiskSettings::default();
        assert!(ok.check().is_ok());
        for (near, far) in [(-1.0, 10.0), (5.0, 5.0), (2.0, f64::NAN), (2.0, 2000.0)] {
            let bad = RiskSettings {
                near_mm: near,
                far_mm: far,
                ..RiskSettings::default()
            };
            let err = bad.check().unwrap_err();
            assert!(err.contains("near_mm"), "{err}");
        }
    }
}
