//! `cutaway expose SESSION.json --focus NAME [--margin MM] --out OUT.json [--samples N] [--json]`:
//! builds the cutters that open the session camera's view onto a structure (the window's
//! Expose, through the same [`crate::expose::plan`]), writes the session with them (atomically)
//! and reports the focus's exposure before and after.

use std::path::PathBuf;

use anyhow::Context as _;

use crate::expose::scene_expose::{check, expose_named};
use crate::expose::{DEFAULT_MARGIN_MM, ExposeSettings, summary};
use crate::metrics::exposure::DEFAULT_SAMPLES;

#[derive(Debug, clap::Args)]
pub struct ExposeArgs {
    /// A `cutaway-session/1` or `/2` file; its camera is the view that is opened.
    pub session: PathBuf,
    /// The structure (model name) to expose.
    #[arg(long)]
    pub focus: String,
    /// Margin around the structure's silhouette, in mm.
    #[arg(long, default_value_t = DEFAULT_MARGIN_MM, allow_negative_numbers = true)]
    pub margin: f64,
    /// The session written with the new cutters (a `.json` file; may be SESSION itself).
    #[arg(long)]
    pub out: PathBuf,
    /// Surface samples (one ray each) of the exposure estimates.
    #[arg(long, default_value_t = DEFAULT_SAMPLES)]
    pub samples: usize,
    /// Print the result as one JSON object instead of a sentence.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &ExposeArgs) -> anyhow::Result<()> {
    let is_json = args
        .out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if !is_json {
        anyhow::bail!(
            "{}: a session is written as .json, not as this extension",
            args.out.display()
        );
    }
    let settings = ExposeSettings {
        margin_mm: args.margin,
    };
    check(&settings, args.samples)?;
    let before = crate::session::load(&args.session)?;
    let exposure = expose_named(&before, &args.focus, &settings, args.samples)
        .with_context(|| format!("{}", args.session.display()))?;
    let (after, exposed, measured) = (&exposure.scene, &exposure.exposed, &exposure.report);
    crate::session::save(&args.out, after)?;
    if args.json {
        println!("{}", serde_json::to_string(&measured)?);
    } else {
        println!(
            "{}; exposure {:.0}% → {:.0}% (at most {:.0}% from this view); wrote {}",
            summary(after, exposed, measured.removed_volume),
            measured.exposure_before * 100.0,
            measured.exposure_after * 100.0,
            measured.exposure_unoccluded * 100.0,
            args.out.display()
        );
    }
    Ok(())
}
