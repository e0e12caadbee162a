//! `cutaway export SESSION.json --out SCENE.glb [--critical NAME…] [--risk-mm NEAR,FAR]
//! [--no-risk] [--json]`: the cut scene as glTF 2.0 binary; with a risk map (the session's, or
//! `--critical`), the walls carry its colours ([`crate::export::risk_colors`]).

use anyhow::Context as _;

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// A `cutaway-session/1` file.
    pub session: PathBuf,
    /// The `.glb` file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object: `{"nodes","materials","triangles","lines","bytes","exact","notes","cut_ms","write_ms"}`.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub risk: crate::cli::risk_args::RiskArgs,
}

pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let mut scene = crate::session::load(&args.session)?;
    crate::cli::risk_args::apply(&mut scene, &args.risk)
        .with_context(|| format!("{}", args.session.display()))?;
    let summary = crate::export::export_glb(&scene, &args.out)?;
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}
