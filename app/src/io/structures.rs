//! Structures: what the model list shows and what a user names. A structure is one mesh file
//! (all its parts and connected regions together) or one label of a segmentation volume; the
//! boolean cuts each of its regions as its own solid, so a scene model can hold a whole structure.
//!
//! [`super::load_models`] still splits files into regions, one model per region: that is the
//! meaning `cutaway-session/1` gives its `target` and `region` indices, kept so old sessions load
//! as they always did.
//!
//! Names come from the file name, as atlases name their files: `Model_17_left_hippocampus.vtk`
//! becomes `left hippocampus` (the `Model_<n>_` prefix that 3D Slicer writes is dropped, and
//! underscores become spaces). Groups are the folders between the opened folder and the file, so
//! the model list can show and hide a folder at once.

use std::path::Path;

use anyhow::Context as _;
use csg::Mesh;
use rayon::prelude::*;

use super::Model;

/// Loads a file, or every mesh file under a directory (recursively, sorted by path), as
/// structures: one [`Model`] per mesh file, with its name from the file name and its group from
/// the folders between `path` and the file (the opened folder's own name first).
pub fn load_structures(path: &Path) -> anyhow::Result<Vec<Model>> {
    let metadata = std::fs::metadata(path).with_context(|| path.display().to_string())?;
    let (files, root) = if metadata.is_dir() && !super::volume::is_volume(path) {
        let files = super::mesh_files(path)?;
        if files.is_empty() {
            anyhow::bail!(
                "{}: no mesh files (.obj, .stl, .ply, .vtk) in this directory",
                path.display()
            );
        }
        (files, path.parent())
    } else {
        (vec![path.to_path_buf()], None)
    };
    // Read in parallel; `collect` keeps the files' order and returns the first error in it.
    let per_file: Vec<Vec<Model>> = files
        .par_iter()
        .map(|file| {
            let group = match root {
                Some(root) => group_of(file, root),
                None => String::new(),
            };
            structures_of_file(file, &group)
        })
        .collect::<anyhow::Result<_>>()?;
    Ok(per_file.into_iter().flatten().collect())
}

/// Reads one file's structures and puts them in `group`.
pub fn structures_of_file(file: &Path, group: &str) -> anyhow::Result<Vec<Model>> {
    let parts = super::read_parts(file)?;
    Ok(structures_of_parts(file, parts, group))
}

/// What one opened file is: its structures, or the intensity image it holds (a volume whose values
/// are not labels, see `super::volume::content`).
#[derive(Debug)]
pub enum FileContent {
    Structures(Vec<Model>),
    Image {
        image: Box<crate::io::intensity::IntensityImage>,
        /// Why it is not a label map.
        reason: String,
    },
}

/// [`structures_of_file`], except that a volume file holding an intensity image is returned as
/// that image (read once) instead of failing as a bad label map.
pub fn content_of_file(file: &Path, group: &str) -> anyhow::Result<FileContent> {
    content_of_file_with(file, group, &|_| true)
}

/// [`content_of_file`] reporting a label volume's surfacing (fraction of its labels' voxels done,
/// 0..=1) to `progress`, which returns false to cancel.
pub fn content_of_file_with(
    file: &Path,
    group: &str,
    progress: &(dyn Fn(f32) -> bool + Sync),
) -> anyhow::Result<FileContent> {
    use super::volume::content::{VolumeContent, read_content};
    if !(file.is_file() && super::volume::is_volume(file)) {
        return structures_of_file(file, group).map(FileContent::Structures);
    }
    Ok(match read_content(file, None)? {
        VolumeContent::Labels(volume) => {
            let parts = super::volume::parts_of_with(&volume, progress)?;
            FileContent::Structures(structures_of_parts(file, parts, group))
        }
        VolumeContent::Image { image, reason } => FileContent::Image { image, reason },
    })
}

/// The structures of one file: for a mesh file the whole file (all parts, welded each on its own,
/// in file order) as one model named by [`structure_name`]; for a label volume (or a folder of
/// masks) one model per label, in ascending label order, with the label's name and colour, in a
/// group named after the volume.
pub fn structures_of_parts(source: &Path, parts: Vec<Model>, group: &str) -> Vec<Model> {
    if super::volume::is_volume(source) {
        let volume_group = source
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let group = if group.is_empty() {
            volume_group
        } else {
            format!("{group}/{volume_group}")
        };
        return parts
            .into_iter()
            .enumerate()
            .map(|(index, part)| Model {
                source: source.to_path_buf(),
                index,
                group: group.clone(),
                ..part
            })
            .collect();
    }
    let stem = source
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".to_owned());
    let mut mesh = Mesh::default();
    for part in &parts {
        mesh.append(&part.mesh);
    }
    vec![Model {
        source: source.to_path_buf(),
        group: group.to_owned(),
        ..Model::part(
            structure_name(&stem),
            parts.iter().find_map(|p| p.color),
            mesh,
        )
    }]
}

/// A structure's display name from a file stem: a leading `Model_<digits>_` (3D Slicer's model
/// export) is dropped and underscores become spaces; an empty result keeps the stem.
pub fn structure_name(stem: &str) -> String {
    let without_prefix = stem
        .strip_prefix("Model_")
        .and_then(|rest| {
            let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
            (digits > 0).then(|| rest[digits..].strip_prefix('_'))?
        })
        .filter(|rest| !rest.is_empty())
        .unwrap_or(stem);
    let name = without_prefix
        .split('_')
        .filter(|w| !w.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    if name.is_empty() {
        stem.to_owned()
    } else {
        name
    }
}

/// The group of `file` under `root` (the opened folder's parent): its folder path with `/`
/// between names (`head_brain_spl_atlas/sub`).
pub fn group_of(file: &Path, root: &Path) -> String {
    let folder = file.parent().unwrap_or(Path::new(""));
    let relative = folder.strip_prefix(root).unwrap_or(folder);
    relative
        .iter()
        .map(|c| c.to_string_lossy())
        .collect::<Vec<_>>()
        .join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_drop_the_slicer_prefix_and_underscores() {
        assert_eq!(
            structure_name("Model_17_left_hippocampus"),
            "left hippocampus"
        );
        assert_eq!(
            structure_name("Model_3004_corpus_callosum"),
            "corpus callosum"
        );
        assert_eq!(
            structure_name("VHF_Left_Bone_Tibia_smooth"),
            "VHF Left Bone Tibia smooth"
        );
        assert_eq!(structure_name("Model_x_y"), "Model x y");
        assert_eq!(structure_name("Model_12_"), "Model 12");
        assert_eq!(structure_name("___"), "___");
        assert_eq!(structure_name("skin"), "skin");
    }

    #[test]
    fn groups_are_folder_paths_from_the_opened_folder() {
        let root = Path::new("/data");
        assert_eq!(group_of(Path::new("/data/atlas/a.vtk"), root), "atlas");
        assert_eq!(
            group_of(Path::new("/data/atlas/deep/b.vtk"), root),
            "atlas/deep"
        );
    }
}
