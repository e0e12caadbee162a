//! Every cut variant of a scene measured with the same options: the measures the compare sheet,
//! the window's compare view and the web page export show in one table ([`super::table`]).

use crate::metrics::{Metrics, MetricsOptions, measure};
use crate::scene::Scene;

/// One variant's measures.
#[derive(Clone, Debug, PartialEq)]
pub struct VariantMetrics {
    pub name: String,
    pub metrics: Metrics,
}

/// Measures every variant of `scene` ([`crate::scene::variants::all`]) with the same options; errors
/// name the variant.
pub fn measure_variants(
    scene: &Scene,
    options: &MetricsOptions,
) -> anyhow::Result<Vec<VariantMetrics>> {
    let names = crate::scene::variants::names(scene);
    names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let shown = crate::scene::variants::variant_scene(scene, k).expect("k < variant count");
            let metrics =
                measure(&shown, options).map_err(|e| anyhow::anyhow!("variant '{name}': {e}"))?;
            Ok(VariantMetrics {
                name: name.clone(),
                metrics,
            })
        })
        .collect()
}
