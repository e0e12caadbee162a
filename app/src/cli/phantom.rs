//! `cutaway phantom --out assets/`: regenerates the embedded synthetic phantoms. OWNER: phantom helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct PhantomArgs {
    /// Output folder (the repository's `assets/`).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(args: &PhantomArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: phantom is not implemented yet", args.out.display())
}
