//! `cutaway [open PATH…]`: the GUI. OWNER: GUI helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct OpenArgs {
    /// Meshes, directories of meshes, or one session file. None: the embedded default scene.
    pub paths: Vec<PathBuf>,
}

pub fn run(args: &OpenArgs) -> anyhow::Result<()> {
    let _ = args;
    anyhow::bail!("the GUI is not implemented yet")
}
