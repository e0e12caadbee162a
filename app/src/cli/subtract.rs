//! `cutaway subtract TARGET CUTTER --out DIR --json`. OWNER: boolean helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct SubtractArgs {
    /// The anatomy to cut (every region of it).
    pub target: PathBuf,
    /// The closed cutter (quads or triangles).
    pub cutter: PathBuf,
    /// Output folder for kept.obj, walls.obj, removed.obj, contour.obj.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &SubtractArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: subtract is not implemented yet", args.target.display())
}
