//! `cutaway phantom --out assets/`: regenerates the embedded synthetic phantoms.
//!
//! Maintainers only (hidden from `--help`): writes `OUT/<scene>/<part>.ply` for every scene of
//! [`crate::anatomy::phantom`], checking closedness, budgets and clearances on the way, and prints one line
//! per part. The app embeds the committed files (`crate::anatomy::assets`), so after changing a shape run
//! `cargo run --release -- phantom --out assets` and commit the files with the code.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct PhantomArgs {
    /// Output folder (the repository's `assets/`).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(args: &PhantomArgs) -> anyhow::Result<()> {
    crate::anatomy::phantom::write_all(&args.out)
}
