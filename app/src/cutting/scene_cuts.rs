//! The whole scene cut at once, off the UI thread: Preview's parts, "Remove All Cut Geometry",
//! the export of cut meshes, and the key that says when a computed preview is stale.

use std::sync::Arc;
use std::time::Instant;

use csg::Mesh;

use super::cut_scene::{self, PreviewGeometry};
use crate::platform::jobs::Progress;
use crate::scene::{Scene, SceneCutter, SceneModel};

/// Cuts every model by its cutters in turn ([`cut_scene::cut_in_turn`]: each cutter cuts
/// the closed result of the ones before it, so overlapping cutters give T ∖ (K1 ∪ … ∪ Kn), with
/// no wall of one cutter left inside another). `visit(step, model)` sees every cutter's step
/// (its `after` is kept part and walls so far, closed). Returns per model the closed result (None
/// when no cutter targets it). Each cutter's kind and smoothing are honoured.
pub fn cut_each_in_turn(
    scene: &Scene,
    progress: &Progress,
    mut visit: impl FnMut(&cut_scene::Step, &SceneModel) -> anyhow::Result<()>,
) -> anyhow::Result<Vec<Option<Arc<Mesh>>>> {
    let mut out = vec![None; scene.models.len()];
    let mut cache = cut_scene::CutCache::default();
    let total = scene.cutters.len() as u64;
    let mut done = 0u64;
    for (m, model) in scene.models.iter().enumerate() {
        let cutters: Vec<(usize, &SceneCutter)> = scene
            .cutters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.target == m)
            .collect();
        if cutters.is_empty() {
            continue;
        }
        progress.check()?;
        let mut failure = None;
        let sequence = cut_scene::cut_in_turn(
            &mut cache,
            &model.model.mesh,
            &cutters,
            |_| false,
            |step| {
                if failure.is_some() {
                    return;
                }
                done += 1;
                progress.set(done, total);
                if let Err(e) = progress.check().and_then(|()| visit(step, model)) {
                    failure = Some(e);
                }
            },
        );
        if let Some(e) = failure {
            return Err(e);
        }
        out[m] = Some(sequence.closed);
    }
    Ok(out)
}

/// The cut parts Preview shows, computed in a worker; returns them with the wall time in ms.
pub fn compute_preview(scene: &Scene) -> (Arc<PreviewGeometry>, f64) {
    let started = Instant::now();
    let geometry = cut_scene::preview_geometry(scene);
    let ms = started.elapsed().as_secs_f64() * 1000.0;
    // The cut's indexes and intermediate meshes were freed on this thread as its cache went:
    // hand their pages back now rather than leave them resident in this thread's arena.
    crate::platform::free_pages::trim_now();
    (Arc::new(geometry), ms)
}

/// "Remove All Cut Geometry": each cut model replaced by its kept part closed by the walls, so
/// later cuts reach the structures behind. Returns (model index, new mesh) pairs.
pub fn apply_all_cuts(
    scene: &Scene,
    progress: &Progress,
) -> anyhow::Result<Vec<(usize, Arc<Mesh>)>> {
    let current = cut_each_in_turn(scene, progress, |_, _| Ok(()))?;
    Ok(current
        .into_iter()
        .enumerate()
        .filter_map(|(i, m)| m.map(|m| (i, m)))
        .collect())
}

/// Preview's dependency on the scene: the cutters and their targets' meshes. When this changes,
/// the preview is recomputed.
#[derive(Clone, Debug, PartialEq)]
pub struct PreviewKey {
    cutters: Vec<SceneCutter>,
    targets: Vec<usize>,
}

impl PreviewKey {
    pub fn of(scene: &Scene) -> PreviewKey {
        PreviewKey {
            cutters: scene.cutters.clone(),
            targets: scene
                .cutters
                .iter()
                .filter_map(|c| scene.models.get(c.target))
                .map(|m| Arc::as_ptr(&m.model.mesh) as usize)
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::CutterViews;
    use crate::test_support::scene_with_cube_cut;

    #[test]
    fn remove_all_cut_geometry_leaves_the_closed_kept_part() {
        // A 2-unit cube with a 1-unit corner cut away.
        let scene = scene_with_cube_cut(CutterViews::default());
        let applied = apply_all_cuts(&scene, &Progress::default()).unwrap();
        assert_eq!(applied.len(), 1);
        let (model, mesh) = &applied[0];
        assert_eq!(*model, 0);
        let report = mesh.report();
        assert!(report.closed, "{report:?}");
        assert!((mesh.volume() - 7.0).abs() < 1e-9, "{}", mesh.volume());
    }
}
