//! `cutaway export SESSION.json --out SCENE.glb [--critical NAME…] [--risk-mm NEAR,FAR]
//! [--no-risk] [--json]`: the cut scene as glTF 2.0 binary; with a risk map (the session's, or
//! `--critical`), the walls carry its colours ([`crate::export::risk_colors`]).
//! `cutaway export SESSION.json --out SCENE.html [--title T] [--focus NAME] [--critical NAME…]
//! [--samples N] [--json]`: the cut scene as one self-contained web page
//! ([`crate::export::webpage`]); `--critical` there also names the metrics table's critical
//! structures. The format follows `--out`'s extension; another extension is refused before the
//! session is read.

use anyhow::Context as _;

use std::path::PathBuf;

use crate::metrics::{MetricsOptions, exposure::DEFAULT_SAMPLES};

#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// A session file (`cutaway-session/2` or `/1`).
    pub session: PathBuf,
    /// The file to write: `.glb` (glTF 2.0 binary) or `.html` (a web page).
    #[arg(long)]
    pub out: PathBuf,
    /// Web page: its title and heading (default "Cutaway scene").
    #[arg(long)]
    pub title: Option<String>,
    /// Web page: the structure whose exposure the metrics table shows (as `cutaway metrics`).
    #[arg(long)]
    pub focus: Option<String>,
    /// Web page: surface samples of the exposure estimate.
    #[arg(long, default_value_t = DEFAULT_SAMPLES)]
    pub samples: usize,
    /// Print one JSON object: for `.glb` `{"nodes","materials","triangles","lines","bytes",
    /// "exact","notes","cut_ms","write_ms"}`, for `.html` `{"bytes","structures","variants",
    /// "export_ms"}`.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub risk: crate::cli::risk_args::RiskArgs,
}

pub use crate::export::scene_file::ExportFormat;

pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let format = ExportFormat::of(&args.out)?;
    if format == ExportFormat::Glb {
        let page_only = [
            ("--title", args.title.is_some()),
            ("--focus", args.focus.is_some()),
            ("--samples", args.samples != DEFAULT_SAMPLES),
        ];
        if let Some((flag, _)) = page_only.iter().find(|(_, given)| *given) {
            anyhow::bail!(
                "{}: {flag} applies to a web page (.html), not to .glb",
                args.out.display()
            );
        }
    }
    let mut scene = crate::session::load(&args.session)?;
    crate::cli::risk_args::apply(&mut scene, &args.risk)
        .with_context(|| format!("{}", args.session.display()))?;
    let page = crate::export::webpage::WebPageOptions {
        title: args.title.clone(),
        metrics: MetricsOptions {
            focus: args.focus.clone(),
            critical: args.risk.critical.clone(),
            samples: args.samples,
        },
    };
    let summary = crate::export::scene_file::export_scene_file(&scene, &args.out, &page)?;
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}
