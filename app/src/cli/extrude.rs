//! `cutaway extrude TARGET --gesture G.json --out CUTTER.obj --json`. OWNER: editor helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ExtrudeArgs {
    /// The anatomy the gesture paints on.
    pub target: PathBuf,
    /// A `cutaway-gesture/1` file.
    #[arg(long)]
    pub gesture: PathBuf,
    /// Where to write the cutter (OBJ quads).
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &ExtrudeArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: extrude is not implemented yet", args.gesture.display())
}
