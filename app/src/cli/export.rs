//! `cutaway export SESSION.json --out SCENE.glb [--critical NAME…] [--risk-mm NEAR,FAR]
//! [--no-risk] [--json]`: the cut scene as glTF 2.0 binary; with a risk map (the session's, or
//! `--critical`), the walls carry its colours ([`crate::export::risk_colors`]).
//! `cutaway export SESSION.json --out SCENE.html [--title T] [--focus NAME] [--critical NAME…]
//! [--samples N] [--json]`: the cut scene as one self-contained web page
//! ([`crate::export::webpage`]); `--critical` there also names the metrics table's critical
//! structures. The format follows `--out`'s extension; another extension is refused before the
//! session is read.

use anyhow::Context as _;

use std::path::{Path, PathBuf};

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

/// What `--out` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    Glb,
    WebPage,
}

impl ExportFormat {
    /// The format of `out` by its extension (case-insensitive), or a one-line error naming it.
    pub fn of(out: &Path) -> anyhow::Result<ExportFormat> {
        let extension = out
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            Some("glb") => Ok(ExportFormat::Glb),
            Some("html" | "htm") => Ok(ExportFormat::WebPage),
            Some(other) => anyhow::bail!(
                "{}: cannot write '.{other}' files (export writes .glb or .html)",
                out.display()
            ),
            None => anyhow::bail!(
                "{}: no extension (export writes .glb or .html)",
                out.display()
            ),
        }
    }
}

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
    match format {
        ExportFormat::Glb => {
            let summary = crate::export::export_glb(&scene, &args.out)?;
            if args.json {
                println!("{}", serde_json::to_string(&summary)?);
            }
        }
        ExportFormat::WebPage => {
            let options = crate::export::webpage::WebPageOptions {
                title: args.title.clone(),
                metrics: MetricsOptions {
                    focus: args.focus.clone(),
                    critical: args.risk.critical.clone(),
                    samples: args.samples,
                },
            };
            let summary = crate::export::webpage::export_webpage(
                &scene,
                &args.out,
                &options,
                &crate::export::webpage::Quiet,
            )?;
            if args.json {
                println!("{}", serde_json::to_string(&summary)?);
            }
        }
    }
    Ok(())
}
