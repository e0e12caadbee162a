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
    mesh_files_listed(dir, list_dir)
}

/// Lists one folder: the path of each entry and whether it is a folder (links are not followed).
/// A parameter of the walk so that a test can make a folder fail to list the way a mode-000
/// folder does for a user who is not root.
type ListDir = fn(&Path) -> std::io::Result<Vec<(PathBuf, bool)>>;

fn list_dir(dir: &Path) -> std::io::Result<Vec<(PathBuf, bool)>> {
    std::fs::read_dir(dir)?
        .map(|entry| {
            let entry = entry?;
            Ok((entry.path(), entry.file_type()?.is_dir()))
        })
        .collect()
}

fn mesh_files_listed(dir: &Path, list: ListDir) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    collect(dir, 0, &mut files, list)?;
    files.sort();
    Ok(files)
}

fn collect(
    dir: &Path,
    depth: usize,
    files: &mut Vec<PathBuf>,
    list: ListDir,
) -> anyhow::Result<()> {
    let entries = list(dir).with_context(|| format!("{}: cannot list directory", dir.display()))?;
    for (path, is_dir) in entries {
        if is_dir {
            if depth < MAX_DEPTH {
                collect(&path, depth + 1, files, list)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A folder that cannot be listed (the listing fails for the folder `locked`, as it does for
    /// a mode-000 folder when the user is not root; the error is injected so the test checks the
    /// same thing for every user) is an error naming that folder and the reason, at the top and
    /// inside the tree: never a shorter list of files.
    #[test]
    fn a_folder_that_cannot_be_listed_is_an_error_naming_it() {
        let root = std::env::temp_dir().join(format!("cutaway-list-dir-{}", std::process::id()));
        let locked = root.join("inner").join("locked");
        std::fs::create_dir_all(&locked).unwrap();
        std::fs::write(root.join("a.stl"), "solid a\nendsolid a\n").unwrap();
        std::fs::write(locked.join("b.stl"), "solid b\nendsolid b\n").unwrap();
        let failing: ListDir = |dir| {
            if dir.file_name().is_some_and(|n| n == "locked") {
                Err(std::io::Error::from(std::io::ErrorKind::PermissionDenied))
            } else {
                list_dir(dir)
            }
        };
        // Listed normally, both files are found (the injection is what fails below).
        let all = mesh_files_listed(&root, list_dir).unwrap();
        assert_eq!(all, vec![root.join("a.stl"), locked.join("b.stl")]);
        let line = format!("{:#}", mesh_files_listed(&root, failing).unwrap_err());
        assert!(
            line.starts_with(&format!("{}: cannot list directory", locked.display())),
            "{line}"
        );
        assert!(line.contains("permission denied"), "{line}");
        let line = format!("{:#}", mesh_files_listed(&locked, failing).unwrap_err());
        assert!(
            line.starts_with(&format!("{}: cannot list directory", locked.display())),
            "{line}"
        );
        std::fs::remove_dir_all(&root).ok();
    }
}
