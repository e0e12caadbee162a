//! `cutaway metrics SESSION.json [--focus NAME] [--critical NAME…] [--samples N] --json`: exact
//! per-structure removal, exposure of a focus structure, distances to critical structures.

use std::path::PathBuf;

use anyhow::Context as _;

use crate::metrics::{MetricsOptions, exposure::DEFAULT_SAMPLES, measure};

#[derive(Debug, clap::Args)]
pub struct MetricsArgs {
    /// A `cutaway-session/1` file.
    pub session: PathBuf,
    /// Structure (model name) whose exposure to the camera is measured.
    #[arg(long)]
    pub focus: Option<String>,
    /// Structures (model names) whose distance to the cut walls is measured.
    #[arg(long, num_args = 1..)]
    pub critical: Vec<String>,
    /// Surface samples (one ray each) of the exposure estimate.
    #[arg(long, default_value_t = DEFAULT_SAMPLES)]
    pub samples: usize,
    /// Print the measures as one JSON object (the only output format).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &MetricsArgs) -> anyhow::Result<()> {
    let scene = crate::session::load(&args.session)?;
    let options = MetricsOptions {
        focus: args.focus.clone(),
        critical: args.critical.clone(),
        samples: args.samples,
    };
    let metrics =
        measure(&scene, &options).with_context(|| format!("{}", args.session.display()))?;
    println!("{}", serde_json::to_string(&metrics)?);
    Ok(())
}
