//! `cutaway [open PATH… [--image CT.nrrd]]`: the GUI, with the scan shown on the cut walls.
//!
//! Paths are checked before the window opens, so a typo gives the usual one-line error instead of
//! a window with an error in its status line.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct OpenArgs {
    /// Meshes, label volumes (a folder of masks is shown structure by structure as it is read),
    /// directories of meshes, or one session file. None: the embedded default scene.
    pub paths: Vec<PathBuf>,
    /// The intensity image (CT, MR) the segmentation was drawn on, shown on the cut walls.
    #[arg(long)]
    pub image: Option<PathBuf>,
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
        .filter(|p| crate::io::dropped::is_session_path(p))
        .count();
    if sessions > 0 && args.paths.len() > 1 {
        anyhow::bail!(
            "{}: a session file must be opened on its own",
            args.paths[0].display()
        );
    }
    if let Some(image) = &args.image
        && !image.is_file()
    {
        anyhow::bail!("{}: no such image file", image.display());
    }
    crate::gui::run_with_image(&args.paths, args.image.clone())
}
