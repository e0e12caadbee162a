//! `cutaway export SESSION.json --out SCENE.glb [--json]`: the cut scene as glTF 2.0 binary.

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
}

pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let scene = crate::session::load(&args.session)?;
    let summary = crate::export::export_glb(&scene, &args.out)?;
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}
