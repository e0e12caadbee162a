//! Labels or intensities: what a volume file holds, decided from its samples, so a CT or MR
//! opened on its own (`cutaway open CT.nrrd`, File → Open, a dropped file, `info`) becomes the
//! scene's image instead of failing as a broken label map.
//!
//! The rule is in [`super::content_rule`].

use std::path::Path;

use anyhow::Context as _;

pub use super::content_rule::MAX_LABEL_VALUES;
use super::content_rule::RawContent;
use super::{LabelVolume, VolumeFormat};
use crate::io::intensity::IntensityImage;

/// A volume file or mask folder, read once, as what it holds.
#[derive(Debug)]
pub enum VolumeContent {
    Labels(LabelVolume),
    /// An intensity image, with the reason it is not a label map (for messages).
    Image {
        image: Box<IntensityImage>,
        reason: String,
    },
}

/// Reads `path` as labels or as an intensity image by [the rule](super::content_rule). Errors name the file.
/// `labels`: a colour table for a label map (ignored for an image).
pub fn read_content(path: &Path, labels: Option<&Path>) -> anyhow::Result<VolumeContent> {
    let metadata = std::fs::metadata(path).with_context(|| path.display().to_string())?;
    if metadata.is_dir() {
        return super::read_volume_labels(path, labels, None).map(VolumeContent::Labels);
    }
    let raw = match super::file_format(path).with_context(|| path.display().to_string())? {
        VolumeFormat::Nrrd => super::nrrd::read_content(path),
        VolumeFormat::Nifti => super::nifti::read_content(path),
    }
    .with_context(|| path.display().to_string())?;
    match raw {
        RawContent::Labels(raw) => {
            let volume = super::read_volume_labels(path, labels, Some(raw))?;
            if !has_too_many_values(&volume) {
                return Ok(VolumeContent::Labels(volume));
            }
            // Whole non-negative values, few of them in the rule's sample but more than the
            // limit in the file: an image after all (rare), read again at its own type.
            drop(volume);
            let raw = match super::file_format(path)? {
                VolumeFormat::Nrrd => super::nrrd::read_samples(path),
                VolumeFormat::Nifti => super::nifti::read_samples(path),
            }
            .with_context(|| path.display().to_string())?;
            let reason = format!(
                "more than {MAX_LABEL_VALUES} distinct {} values",
                raw.sample.name()
            );
            let image = super::intensity::from_samples(path, raw)
                .with_context(|| path.display().to_string())?;
            Ok(VolumeContent::Image {
                image: Box::new(image),
                reason,
            })
        }
        RawContent::Image(raw, reason) => {
            let image = super::intensity::from_samples(path, raw)
                .with_context(|| path.display().to_string())?;
            Ok(VolumeContent::Image {
                image: Box::new(image),
                reason,
            })
        }
    }
}

/// Whether a one-layer label map holds more distinct values (background included) than
/// [`MAX_LABEL_VALUES`]: by the rule, an intensity image.
fn has_too_many_values(volume: &LabelVolume) -> bool {
    if volume.layers.len() != 1 {
        return false;
    }
    let voxels: u64 = volume.dims.iter().map(|&d| d as u64).product();
    let labelled: u64 = volume.structures.iter().map(|s| s.voxels).sum();
    volume.structures.len() + usize::from(labelled < voxels) > MAX_LABEL_VALUES
}

/// Whether a file opened as structures is an intensity image instead: `Some(reason)`. Reads the
/// whole file; use [`read_content`] to keep what was read.
pub fn intensity_reason_of_file(path: &Path) -> anyhow::Result<Option<String>> {
    Ok(match read_content(path, None)? {
        VolumeContent::Labels(_) => None,
        VolumeContent::Image { reason, .. } => Some(reason),
    })
}
