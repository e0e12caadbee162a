//! Export Cut Meshes: every cutter's kept part, walls and removed piece written as mesh files,
//! cut in turn as Preview cuts them.

use std::path::{Path, PathBuf};

use crate::cutting::cut_scene;
use crate::cutting::scene_cuts::cut_each_in_turn;
use crate::platform::jobs::Progress;
use crate::scene::Scene;

/// Which parts of each cut [`write_cut_meshes`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CutMeshParts {
    /// The model outside the cutter (its own surface, no walls).
    pub kept: bool,
    /// The cut's walls.
    pub walls: bool,
    /// The removed piece.
    pub removed: bool,
}

/// Cuts every cutter out of its target (cutters on one model one after another, as Preview does)
/// and writes the chosen parts into `dir` as `cutter<k>_<model>_<part>.<extension>` (the
/// format follows the extension); returns the files written.
pub fn write_cut_meshes(
    scene: &Scene,
    parts: CutMeshParts,
    extension: &str,
    dir: &Path,
    progress: &Progress,
) -> anyhow::Result<Vec<PathBuf>> {
    if scene.cutters.is_empty() {
        anyhow::bail!(
            "{}: there are no cutters to export (make one in Edit mode first)",
            dir.display()
        );
    }
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    let mut written = Vec::new();
    cut_each_in_turn(scene, progress, |step, model| {
        use cut_scene::{SURFACE, select};
        let stem = sanitize(&format!("cutter{}_{}", step.cutter + 1, model.model.name));
        let tags = step.after_tags;
        for (wanted, part) in [
            (parts.kept, "kept"),
            (parts.walls, "walls"),
            (parts.removed, "removed"),
        ] {
            if !wanted {
                continue;
            }
            let mesh = match part {
                "kept" => select(step.after, |t| tags[t] == SURFACE),
                "walls" => select(step.after, |t| tags[t] != SURFACE),
                _ => step.removed.clone(),
            };
            if !mesh.triangles.is_empty() {
                let path = dir.join(format!("{stem}_{part}.{extension}"));
                crate::io::write_mesh(&path, &mesh)?;
                written.push(path);
            }
        }
        Ok(())
    })?;
    Ok(written)
}

/// File-name-safe version of a model name.
fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
