//! The structures a session names in a file, as the window opens a session on a worker: a label
//! volume is surfaced with its progress reported (the fraction of its labels' voxels done), so
//! the progress bar moves and Cancel stops it between labels; the default scene's files come from
//! the binary when they are not on disk; any other file is read as `io::load_structures` reads it.

use std::path::Path;

use crate::io::{FileContent, Model};

/// The structures of `file` for a session entry. `only`: the positions the session picks, when
/// it picks some (the embedded atlas then surfaces just those). `progress` hears a volume's
/// surfacing (0..=1) and returns false to cancel it.
pub fn structures(
    file: &Path,
    only: Option<&[usize]>,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<Vec<Model>> {
    if !(file.is_file() && crate::io::volume::is_volume(file)) {
        return crate::anatomy::assets::load_or_embedded_picking(
            file,
            crate::scene::ModelUnit::Structure,
            only,
        );
    }
    match crate::io::content_of_file_with(file, "", progress)? {
        FileContent::Structures(models) => Ok(models),
        FileContent::Image { reason, .. } => anyhow::bail!(
            "{}: an intensity image ({reason}), not a segmentation",
            file.display()
        ),
    }
}
