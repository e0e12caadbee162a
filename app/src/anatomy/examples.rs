//! The embedded example scenes as the window's File → Examples opens them: the default scene,
//! the whole atlas (its surfacing reported and cancelled through a [`Progress`]) and the
//! phantoms.

use std::path::Path;

use crate::platform::jobs::Progress;

/// An embedded example scene by name. Models keep the virtual `assets/<scene>/<part>.ply`
/// source unless the source tree's copy exists, whose absolute path is used instead so that a
/// session saved from the example opens anywhere on this machine.
pub fn example_models(name: &str, progress: &Progress) -> anyhow::Result<Vec<crate::io::Model>> {
    progress.set_message(name.to_string());
    let mut models = if name == crate::anatomy::default_scene::NAME {
        crate::anatomy::default_scene::load()?
    } else if name == crate::anatomy::default_scene::ALL_NAME {
        crate::anatomy::default_scene::load_all(&|fraction| {
            progress.set((fraction.clamp(0.0, 1.0) * 1000.0) as u64, 1000);
            !progress.is_cancelled()
        })?
    } else {
        let scene = crate::anatomy::assets::scene(name)
            .ok_or_else(|| anyhow::anyhow!("{name}: no such example scene"))?;
        crate::anatomy::assets::load_scene_structures(scene)?
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for model in &mut models {
        let on_disk = root.join(&model.source);
        if on_disk.is_file()
            && let Ok(absolute) = std::fs::canonicalize(&on_disk)
        {
            model.source = absolute;
        }
    }
    Ok(models)
}
