//! `cutaway scalpel TARGET --path P.json --out OUT.obj --json`. OWNER: scalpel helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ScalpelArgs {
    /// The surface to cut.
    pub target: PathBuf,
    /// A `cutaway-path/1` file.
    #[arg(long)]
    pub path: PathBuf,
    /// Where to write the cut mesh.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &ScalpelArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: scalpel is not implemented yet", args.path.display())
}
