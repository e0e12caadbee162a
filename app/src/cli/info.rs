//! `cutaway info MESH --json`. OWNER: IO helper (foundation issue).

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// The mesh file (.obj, .stl, .ply, .vtk).
    pub mesh: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: info is not implemented yet", args.mesh.display())
}
