//! Files opened as structures that turn out to be the image: the one place the window's open
//! paths (File → Open, dropped files, `cutaway open CT.nrrd`) decide between a segmentation and
//! an intensity image, by the rule of `crate::io::volume::content`. egui-free so tests and other
//! front ends use the same rule.

use std::path::Path;
use std::sync::Arc;

use crate::io::Model;
use crate::io::{FileContent, content_of_file_with};

use super::ImageLayer;

/// Reads `file` and adds its structures to `models`, or, when it holds an intensity image, puts
/// that image in `image` (one image per open: a second one is an error naming both files).
/// `progress` hears a label volume's surfacing (fraction of its labels' voxels done, 0..=1) and
/// returns false to cancel it.
pub fn read_file_into(
    file: &Path,
    group: &str,
    models: &mut Vec<Model>,
    image: &mut Option<ImageLayer>,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<()> {
    match content_of_file_with(file, group, progress)? {
        FileContent::Structures(found) => models.extend(found),
        FileContent::Image { image: read, .. } => {
            if let Some(first) = image {
                anyhow::bail!(
                    "{}: a second intensity image (the first is {}); open one image at a time",
                    file.display(),
                    first.image.source.display()
                );
            }
            *image = Some(ImageLayer::new(Arc::new(*read)));
        }
    }
    Ok(())
}
