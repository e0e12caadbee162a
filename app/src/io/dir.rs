//! Loading a file or a directory of mesh files as scene models (one per region).

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use rayon::prelude::*;

use super::{Format, Model};

/// How deep [`mesh_files`] descends into sub-folders (a guard against pathological trees).
const MAX_DEPTH: usize = 16;

pub(crate) fn load_models(path: &Path) -> anyhow::Result<Vec<Model>> {
    let metadata = std::fs::metadata(path).with_context(|| path.display().to_string())?;
    let files = if metadata.is_dir() && !super::volume::is_volume(path) {
        let files = mesh_files(path)?;
        if files.is_empty() {
            anyhow::bail!(
                "{}: no mesh files (.obj, .stl, .ply, .vtk) in this directory",
                path.display()
            );
        }
        files
    } else {
        vec![path.to_path_buf()]
    };
    // Read in parallel; `collect` keeps the files' order and returns the first error in it.
    let per_file: Vec<Vec<Model>> = files
        .par_iter()
        .map(|file| {
            let parts = super::read_parts(file)?;
            Ok(super::models_of_parts(file, &parts))
        })
        .collect::<anyhow::Result<_>>()?;
    Ok(per_file.into_iter().flatten().collect())
}

/// Every file with a mesh extension under `dir` (recursively, not following links to folders),
/// sorted by path so that the order is the same on every machine.
pub fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    collect(dir, 0, &mut files)?;
    files.sort();
    Ok(files)
}

fn collect(dir: &Path, depth: usize, files: &mut Vec<PathBuf>) -> anyhow::Result<()> {
    let context = || format!("{}: cannot list directory", dir.display());
    for entry in std::fs::read_dir(dir).with_context(context)? {
        let entry = entry.with_context(context)?;
        let path = entry.path();
        let kind = entry.file_type().with_context(context)?;
        if kind.is_dir() {
            if depth < MAX_DEPTH {
                collect(&path, depth + 1, files)?;
            }
        } else if Format::from_path(&path).is_some() && !is_hidden(&path) {
            files.push(path);
        }
    }
    Ok(())
}

/// Hidden files (`.name`) are skipped: among them our own temporary files of atomic writes.
fn is_hidden(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.starts_with('.'))
}
