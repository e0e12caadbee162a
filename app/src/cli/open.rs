//! `cutaway [open PATH…]`: the GUI.
//!
//! Paths are checked before the window opens, so a typo gives the usual one-line error instead of
//! a window with an error in its status line.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct OpenArgs {
    /// Meshes, directories of meshes, or one session file. None: the embedded default scene.
    pub paths: Vec<PathBuf>,
}

pub fn run(args: &OpenArgs) -> anyhow::Result<()> {
    for path in &args.paths {
        if !path.exists() {
            anyhow::bail!("{}: no such file or directory", path.display());
        }
    }
    let sessions = args
        .paths
        .iter()
        .filter(|p| crate::gui::app::is_session_path(p))
        .count();
    if sessions > 0 && args.paths.len() > 1 {
        anyhow::bail!(
            "{}: a session file must be opened on its own",
            args.paths[0].display()
        );
    }
    crate::gui::run(&args.paths)
}
