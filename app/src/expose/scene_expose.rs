//! An exposure of a named structure from start to report, as `cutaway expose`, `cutaway batch`
//! and the Python `Session.expose` do it: the settings checked, the focus found by name, the
//! cutters planned, applied to a copy of the scene and measured.

use crate::expose::report::{ExposeReport, report};
use crate::expose::{ExposeSettings, Exposed, apply, plan};
use crate::metrics::structure_index;
use crate::platform::jobs::Progress;
use crate::scene::Scene;

/// Largest number of surface samples an exposure estimate takes.
pub const MAX_SAMPLES: usize = 10_000_000;

/// The outcome of [`expose_named`]: the scene with the new cutters, what was planned, and its
/// report.
#[derive(Debug)]
pub struct Exposure {
    pub scene: Scene,
    pub exposed: Exposed,
    pub report: ExposeReport,
}

/// Checks the margin and the sample count (errors name the CLI's flags).
pub fn check(settings: &ExposeSettings, samples: usize) -> anyhow::Result<()> {
    use anyhow::Context as _;
    settings.check().context("--margin")?;
    if !(1..=MAX_SAMPLES).contains(&samples) {
        anyhow::bail!("--samples {samples} is outside 1..{MAX_SAMPLES}");
    }
    Ok(())
}

/// Opens `before`'s camera view onto the structure named `focus` ([`check`] first; an unknown focus is an
/// error naming it).
pub fn expose_named(
    before: &Scene,
    focus: &str,
    settings: &ExposeSettings,
    samples: usize,
) -> anyhow::Result<Exposure> {
    check(settings, samples)?;
    let focus = structure_index(before, focus)?;
    let exposed = plan(before, focus, settings, &Progress::default())?;
    let mut scene = before.clone();
    apply(&mut scene, &exposed);
    let report = report(before, &scene, &exposed, samples)?;
    Ok(Exposure {
        scene,
        exposed,
        report,
    })
}
