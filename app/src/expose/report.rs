//! What an exposure achieved, measured as `cutaway metrics` measures: the focus's exposure
//! (the share of its surface the camera sees, [`crate::metrics::exposure`]) before, after, and
//! with every other structure hidden (the most any cut can show from this view), and the volume
//! the new cutters remove (exact, as Preview cuts).

use crate::expose::Exposed;
use crate::metrics::removal::cut_models;
use crate::metrics::{exposure_as_drawn, exposure_unoccluded};
use crate::scene::LengthUnit;
use crate::scene::Scene;

/// What `cutaway expose --json` prints.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ExposeReport {
    /// The focus's name.
    pub focus: String,
    /// Cutters added.
    pub cutters: usize,
    /// Share (0..=1) of the focus's surface seen in the session as it was (with its cuts).
    pub exposure_before: f64,
    /// The same with the new cutters.
    pub exposure_after: f64,
    /// The same with every other structure hidden.
    pub exposure_unoccluded: f64,
    /// mm³ the new cutters remove (each cutting what the cutters before it left); `None` when no
    /// structure they cut is closed.
    pub removed_volume: Option<f64>,
    /// Wall time of building and checking the cutters, in ms.
    pub expose_ms: f64,
    /// The structures opened, nearest first.
    pub opened: Vec<String>,
}

/// The volume (mm³) the cutters of `after` from index `first_new` on remove, each in turn after
/// those before it; `None` when none of them cuts a closed structure. Fails when a cut is not
/// exact.
pub fn removed_volume_mm3(after: &Scene, first_new: usize) -> anyhow::Result<Option<f64>> {
    let cuts = cut_models(after)?;
    let volumes: Vec<f64> = cuts
        .iter()
        .flat_map(|c| &c.cutters)
        .filter(|c| c.index >= first_new)
        .filter_map(|c| c.removed_volume)
        .collect();
    if volumes.is_empty() {
        return Ok(None);
    }
    let mm = LengthUnit::guess(&after.bbox(), false).mm_per_unit();
    Ok(Some(volumes.iter().sum::<f64>() * mm * mm * mm))
}

/// Measures the exposure of `exposed` on `before` (the scene it was planned on) and `after`
/// (with it applied), each exposure from `samples` rays.
pub fn report(
    before: &Scene,
    after: &Scene,
    exposed: &Exposed,
    samples: usize,
) -> anyhow::Result<ExposeReport> {
    let focus = exposed.focus;
    Ok(ExposeReport {
        focus: after.models[focus].model.name.clone(),
        cutters: exposed.cutters.len(),
        exposure_before: exposure_as_drawn(before, focus, samples)?,
        exposure_after: exposure_as_drawn(after, focus, samples)?,
        exposure_unoccluded: exposure_unoccluded(after, focus, samples)?,
        removed_volume: removed_volume_mm3(after, before.cutters.len())?,
        expose_ms: exposed.expose_ms,
        opened: exposed
            .opened
            .iter()
            .map(|&m| after.models[m].model.name.clone())
            .collect(),
    })
}
