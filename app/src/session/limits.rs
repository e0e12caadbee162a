//! Bounds on what a session file may ask for, checked when it is parsed, before any model is
//! loaded or any geometry is built.
//!
//! Why: a count in a session is a request for work and memory. `"ribbons": {"count": 1000000000}`
//! once allocated 6 GB before failing. Each limit below is far above what the GUI can make (it
//! offers at most 50 ribbons) and far below what would exhaust a desktop:
//!
//! | field | limit |
//! |---|---|
//! | `models` entries | [`MAX_MODELS`] |
//! | `cutters` | [`MAX_CUTTERS`] |
//! | `variants` | [`MAX_VARIANTS`], each with at most [`MAX_CUTTERS`] cutters checked as `cutters` |
//! | `planes` of one cutter | [`MAX_PLANES_PER_CUTTER`] |
//! | `views.ribbons.count`, `views.slices.count` | [`MAX_SUB_CUTTERS`] |
//! | `views.*.width`, plane and camera coordinates | finite, magnitude ≤ [`crate::io::MAX_ABS_COORDINATE`] |
//! | `risk.critical` names | [`MAX_MODELS`] |
//!
//! Errors are one line naming the field (`cutter 2: views.ribbons.count 1000000000 is more than
//! the limit of 1000`); the caller adds the file name.

use crate::io::MAX_ABS_COORDINATE;
use crate::session::format::{CutterEntry, SessionFile, SubCutterEntry};

/// Most model entries in one session.
pub const MAX_MODELS: usize = 10_000;
/// Most cutters in one session.
pub const MAX_CUTTERS: usize = 1_000;
/// Most cut variants in one session (the window compares up to four side by side).
pub const MAX_VARIANTS: usize = 64;
/// Most planes of one cutter (a cutter gains one per ω·δ of extrusion).
pub const MAX_PLANES_PER_CUTTER: usize = 10_000;
/// Most ribbons or slices of one cutter.
pub const MAX_SUB_CUTTERS: u32 = 1_000;

/// Checks every count and size of a parsed session against the limits of the module doc.
pub fn check(file: &SessionFile) -> anyhow::Result<()> {
    if file.models.len() > MAX_MODELS {
        anyhow::bail!(
            "models: {} entries, more than the limit of {MAX_MODELS}",
            file.models.len()
        );
    }
    if file.cutters.len() > MAX_CUTTERS {
        anyhow::bail!(
            "cutters: {} cutters, more than the limit of {MAX_CUTTERS}",
            file.cutters.len()
        );
    }
    check_cutters(&file.cutters, "")?;
    crate::session::rulers::check(&file.rulers)?;
    if let Some(risk) = &file.risk
        && risk.critical.len() > MAX_MODELS
    {
        anyhow::bail!(
            "risk.critical: {} names, more than the limit of {MAX_MODELS}",
            risk.critical.len()
        );
    }
    if file.variants.len() > MAX_VARIANTS {
        anyhow::bail!(
            "variants: {} variants, more than the limit of {MAX_VARIANTS}",
            file.variants.len()
        );
    }
    for (k, variant) in file.variants.iter().enumerate() {
        if variant.cutters.len() > MAX_CUTTERS {
            anyhow::bail!(
                "variant {k}: cutters: {} cutters, more than the limit of {MAX_CUTTERS}",
                variant.cutters.len()
            );
        }
        check_cutters(&variant.cutters, &format!("variant {k}: "))?;
    }
    if let Some(camera) = &file.camera {
        for (what, point) in [
            ("eye", camera.eye),
            ("target", camera.target),
            ("up", camera.up),
        ] {
            check_coordinate(&point, || format!("camera.{what}"))?;
        }
    }
    Ok(())
}

/// Checks plane counts, coordinates and sub-cutter counts of `cutters`; errors start with
/// `prefix` (which variant).
fn check_cutters(cutters: &[CutterEntry], prefix: &str) -> anyhow::Result<()> {
    for (i, cutter) in cutters.iter().enumerate() {
        if cutter.planes.len() > MAX_PLANES_PER_CUTTER {
            anyhow::bail!(
                "{prefix}cutter {i}: planes: {} planes, more than the limit of {MAX_PLANES_PER_CUTTER}",
                cutter.planes.len()
            );
        }
        for (p, plane) in cutter.planes.iter().enumerate() {
            for corner in plane {
                check_coordinate(corner, || format!("{prefix}cutter {i}: planes[{p}]"))?;
            }
        }
        for (what, view) in [
            ("ribbons", &cutter.views.ribbons),
            ("slices", &cutter.views.slices),
        ] {
            // Placement and relative width are checked where the views are built.
            if let Some(&SubCutterEntry {
                count,
                width,
                placement: _,
                relative: _,
            }) = view.as_ref()
            {
                if count > MAX_SUB_CUTTERS {
                    anyhow::bail!(
                        "{prefix}cutter {i}: views.{what}.count {count} is more than the limit of {MAX_SUB_CUTTERS}"
                    );
                }
                if !(width.is_finite() && width > 0.0 && width <= MAX_ABS_COORDINATE) {
                    anyhow::bail!(
                        "{prefix}cutter {i}: views.{what}.width {width} must be positive and at most {MAX_ABS_COORDINATE:e}"
                    );
                }
            }
        }
    }
    Ok(())
}

fn check_coordinate(point: &[f64; 3], field: impl Fn() -> String) -> anyhow::Result<()> {
    if point.iter().all(|c| c.abs() <= MAX_ABS_COORDINATE) {
        return Ok(());
    }
    anyhow::bail!(
        "{}: {point:?} is not finite or beyond ±{MAX_ABS_COORDINATE:e}",
        field()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn session_with_cutter(views: &str, planes: usize) -> String {
        let plane = "[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]";
        let planes = vec![plane; planes].join(",");
        format!(
            r#"{{"format": "cutaway-session/1", "models": [{{"path": "knee.obj"}}],
              "cutters": [{{"target": 0, "planes": [{planes}], "views": {views}}}]}}"#
        )
    }

    fn error(text: &str) -> String {
        format!("{:#}", crate::session::parse(text).unwrap_err())
    }

    #[test]
    fn absurd_counts_are_refused_naming_the_field() {
        let text = session_with_cutter(r#"{"ribbons": {"count": 1000000000, "width": 2}}"#, 1);
        let e = error(&text);
        assert!(
            e.contains("cutter 0: views.ribbons.count 1000000000"),
            "{e}"
        );
        let text = session_with_cutter(r#"{"slices": {"count": 5, "width": 1e300}}"#, 1);
        assert!(error(&text).contains("views.slices.width"));
        let text = session_with_cutter("{}", MAX_PLANES_PER_CUTTER + 1);
        assert!(error(&text).contains("cutter 0: planes: 10001 planes"));
        let text = session_with_cutter(r#"{"ribbons": {"count": 1000, "width": 2}}"#, 3);
        crate::session::parse(&text).unwrap();
    }

    #[test]
    fn absurd_coordinates_and_too_many_entries_are_refused() {
        let text = session_with_cutter("{}", 1).replace("[0,1,-1]", "[0,3e38,-1]");
        assert!(error(&text).contains("cutter 0: planes[0]"));
        let models = vec![r#"{"path": "a.obj"}"#; MAX_MODELS + 1].join(",");
        let text = format!(r#"{{"format": "cutaway-session/1", "models": [{models}]}}"#);
        assert!(error(&text).contains("models: 10001 entries"));
        let text = r#"{"format": "cutaway-session/1", "models": [],
            "camera": {"eye": [0, -1e13, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30}}"#;
        assert!(error(text).contains("camera.eye"));
    }
}
