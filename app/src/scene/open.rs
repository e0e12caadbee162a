//! Opening files and folders into a scene, as the window's File → Open, dropped files and
//! `cutaway open` do: folders read recursively and grouped by the folders between, one file at
//! a time with progress and cancel; a file that holds an intensity image instead of structures
//! becomes the scene's image (the one place that decides, by the rule of
//! `crate::io::volume::content`); and the structures read become scene models coloured by
//! `crate::anatomy::colors`. egui-free so tests and other front ends use the same rules.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::io::Model;
use crate::io::{FileContent, content_of_file_with};
use crate::platform::jobs::Progress;

use super::{ImageLayer, SceneModel};

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

/// A path as the status line names it: its file name.
pub fn file_label(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Reads files and folders (recursively) as structures, one file at a time, reporting progress
/// per file and stopping between files when cancelled. A folder's files are grouped by the
/// folders between it and them, its own name first. A volume file whose values are not labels
/// becomes the scene's image.
pub fn load_paths(
    paths: &[PathBuf],
    progress: &Progress,
) -> anyhow::Result<(Vec<Model>, Option<ImageLayer>)> {
    let mut files: Vec<(PathBuf, String)> = Vec::new();
    for path in paths {
        // A folder of masks is one volume; any other folder is searched for meshes.
        if path.is_dir() && !crate::io::volume::is_volume(path) {
            let found = crate::io::mesh_files(path)?;
            if found.is_empty() {
                anyhow::bail!(
                    "{}: no .obj, .stl, .ply or .vtk files in this folder",
                    path.display()
                );
            }
            let root = path.parent().unwrap_or(Path::new(""));
            files.extend(found.into_iter().map(|f| {
                let group = crate::io::group_of(&f, root);
                (f, group)
            }));
        } else {
            files.push((path.clone(), String::new()));
        }
    }
    let mut models = Vec::new();
    let mut image = None;
    // Per mille of each file, so a volume's label surfacing moves the bar within its file.
    let total = files.len() as u64 * 1000;
    for (i, (file, group)) in files.iter().enumerate() {
        progress.check()?;
        let start = i as u64 * 1000;
        progress.set(start, total);
        progress.set_message(file_label(file));
        let surfacing = |fraction: f32| {
            progress.set(start + (fraction.clamp(0.0, 1.0) * 1000.0) as u64, total);
            !progress.is_cancelled()
        };
        read_file_into(file, group, &mut models, &mut image, &surfacing)?;
    }
    progress.set(total, total);
    Ok((models, image))
}

/// Whether `paths` is one folder of masks, which the window opens structure by structure as its
/// files are read ([`stream_mask_folder`]).
pub fn is_one_mask_folder(paths: &[PathBuf]) -> bool {
    matches!(paths, [one] if one.is_dir() && crate::io::volume::is_volume(one))
}

/// Surfaces the masks of `dir` as [`crate::io::volume::mask_surfaces`] does, handing each file's
/// outcome to `arrive` as soon as it is known: its number in file order and its structure as a
/// model of `dir` (grouped under the folder's name, as [`load_paths`] groups it; its `index` is
/// set when it is released in order, [`super::arrivals::InOrder`]). `progress` hears the
/// fraction of files done and cancels.
pub fn stream_mask_folder(
    dir: &Path,
    progress: &Progress,
    arrive: &(dyn Fn(usize, Option<Model>) + Sync),
) -> anyhow::Result<usize> {
    let group = file_label(dir);
    let fraction = |f: f32| {
        progress.set((f.clamp(0.0, 1.0) * 1000.0) as u64, 1000);
        !progress.is_cancelled()
    };
    let folder = crate::io::volume::mask_surfaces::surfaces_each(
        dir,
        &[],
        &csg::labels::SurfaceOptions::default(),
        &fraction,
        &|file, surface| {
            arrive(
                file,
                surface.map(|s| Model {
                    source: dir.to_path_buf(),
                    group: group.clone(),
                    ..crate::io::volume::part_of(s)
                }),
            );
            !progress.is_cancelled()
        },
    )?;
    Ok(folder.structures.len())
}

/// `models` as scene models, each coloured as a structure is (its file's colour, else by its
/// anatomical name, else a palette colour by its position `first_index + i` in the scene).
pub fn structures(models: Vec<Model>, first_index: usize) -> Vec<SceneModel> {
    models
        .into_iter()
        .enumerate()
        .map(|(i, model)| {
            let color =
                crate::anatomy::colors::structure_color(&model.name, model.color, first_index + i);
            SceneModel::structure(model, color)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_paths_names_an_empty_folder() {
        let dir = std::env::temp_dir().join(format!("cutaway-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let err = load_paths(std::slice::from_ref(&dir), &Progress::default()).unwrap_err();
        assert!(format!("{err:#}").contains(&dir.display().to_string()));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
