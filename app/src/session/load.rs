//! A session read with progress and cancel, as the window's worker reads one: each model file
//! named in the status line, a label volume's surfacing reported as it goes.

use std::path::Path;

use crate::platform::jobs::Progress;
use crate::scene::Scene;

/// Reads a session, models included, reporting each file and its surfacing to `progress` and
/// stopping between files when it is cancelled; the scene is checked before it is returned.
pub fn load_with_progress(path: &Path, progress: &Progress) -> anyhow::Result<Scene> {
    progress.set_message(
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
    );
    let mut files = 0u64;
    let scene = crate::session::load_with(path, |file, unit, only| {
        progress.check()?;
        files += 1;
        progress.set_message(
            file.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
        );
        match unit {
            crate::scene::ModelUnit::Region => crate::io::load_models(file),
            crate::scene::ModelUnit::Structure => {
                crate::session::volumes::structures(file, only, &|f| {
                    progress.set((f.clamp(0.0, 1.0) * 1000.0) as u64, 1000);
                    !progress.is_cancelled()
                })
            }
        }
    })?;
    scene
        .sanity_check()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(scene)
}
