//! Which model the pointer is over: the first hit of a ray through the scene's visible models,
//! each through its own [`PickIndex`] (an `obvhs` BVH with csg's watertight `f64` triangle test
//! on its candidates), kept while its mesh lives.
//!
//! A pick is one ray per click, but over millions of triangles a scan costs tens of
//! milliseconds on every click; the tree makes each pick microseconds after a one-off build.
//! That build is itself tens of milliseconds on a large model, so the window does not leave it
//! to the first press: [`ScenePicks::prepare`] (called every frame, cheap when nothing changed)
//! builds the trees of models that have none on a worker thread as soon as a scene is loaded or
//! a mesh is replaced. A press that comes before a tree is ready waits for that worker instead of
//! building a second copy; callers that never prepare (the CLI, tests) build on first use.

use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::sync::{Arc, Weak};

use csg::{Mesh, PickIndex};

use crate::scene::Scene;

/// A tree built by a worker, for the mesh it was built from.
type Built = (Weak<Mesh>, Arc<PickIndex>);

/// Trees a worker is building: the meshes it was given, and where the trees arrive.
struct InFlight {
    meshes: Vec<Weak<Mesh>>,
    results: Receiver<Built>,
}

/// The ray-pick trees of the scene's models (see the module documentation).
#[derive(Default)]
pub struct ScenePicks {
    trees: Vec<Built>,
    in_flight: Vec<InFlight>,
    /// Trees built on the calling thread because nobody prepared them (see [`Self::prepare`]).
    built_by_caller: usize,
}

/// A model a pick can hit: visible, not fully transparent, not empty.
pub fn is_pickable(model: &crate::scene::SceneModel) -> bool {
    model.visible && model.opacity > 0.0 && !model.model.mesh.triangles.is_empty()
}

fn pickable(scene: &Scene) -> impl Iterator<Item = &crate::scene::SceneModel> {
    scene.models.iter().filter(|m| is_pickable(m))
}

fn same_mesh(weak: &Weak<Mesh>, mesh: &Arc<Mesh>) -> bool {
    std::ptr::eq(weak.as_ptr(), Arc::as_ptr(mesh)) && weak.strong_count() > 0
}

impl ScenePicks {
    /// Pick trees held (the memory test prints it per step).
    pub fn tree_count(&self) -> usize {
        self.trees.len()
    }

    /// Bytes the trees held hold (the memory test prints it per step).
    pub fn tree_bytes(&self) -> u64 {
        self.trees.iter().map(|(_, t)| t.heap_bytes() as u64).sum()
    }

    /// Starts building, on a worker thread, the trees of the scene's pickable models that have
    /// none and are not being built; collects the trees workers finished. Cheap when every model
    /// has its tree: the window calls it once per frame.
    pub fn prepare(&mut self, scene: &Scene) {
        self.collect();
        let missing: Vec<Arc<Mesh>> = pickable(scene)
            .map(|m| m.model.mesh.clone())
            .filter(|mesh| !self.has_tree(mesh) && !self.is_building(mesh))
            .collect();
        if missing.is_empty() {
            return;
        }
        let (tx, rx) = channel();
        let meshes: Vec<Weak<Mesh>> = missing.iter().map(Arc::downgrade).collect();
        let work = meshes.clone();
        drop(missing);
        let spawned = std::thread::Builder::new()
            .name("cutaway pick trees".into())
            .spawn(move || {
                for weak in work {
                    // A mesh replaced meanwhile needs no tree.
                    let Some(mesh) = weak.upgrade() else { continue };
                    let tree = Arc::new(PickIndex::build(&mesh));
                    drop(mesh);
                    if tx.send((weak, tree)).is_err() {
                        return;
                    }
                }
            });
        if spawned.is_ok() {
            self.in_flight.push(InFlight {
                meshes,
                results: rx,
            });
        }
    }

    /// True when every pickable model of `scene` has its tree (none left to build or wait for).
    pub fn ready_for(&self, scene: &Scene) -> bool {
        pickable(scene).all(|m| self.has_tree(&m.model.mesh))
    }

    /// Trees built on the calling thread so far (none when the scene was prepared in time).
    pub fn built_by_caller(&self) -> usize {
        self.built_by_caller
    }

    /// The visible model `ray` hits first, with the ray parameter of the hit.
    pub fn pick(&mut self, scene: &Scene, ray: &cutter::Ray) -> Option<(usize, f64)> {
        self.trees.retain(|(mesh, _)| mesh.strong_count() > 0);
        let mut best: Option<(usize, f64)> = None;
        for (i, model) in scene.models.iter().enumerate() {
            if !is_pickable(model) {
                continue;
            }
            let t_max = best.map_or(f64::INFINITY, |(_, t)| t);
            let tree = self.tree(&model.model.mesh);
            if let Some(hit) = tree.ray_cast(&model.model.mesh, ray.origin, ray.direction, t_max)
                && best.is_none_or(|(_, b)| hit.t < b)
            {
                best = Some((i, hit.t));
            }
        }
        best
    }

    /// True when `ray` hits `mesh` at all (visible or not; through the same tree as [`Self::pick`]).
    pub fn hits(&mut self, mesh: &Arc<Mesh>, ray: &cutter::Ray) -> bool {
        !mesh.triangles.is_empty()
            && self
                .tree(mesh)
                .ray_cast(mesh, ray.origin, ray.direction, f64::INFINITY)
                .is_some()
    }

    fn has_tree(&self, mesh: &Arc<Mesh>) -> bool {
        self.trees.iter().any(|(m, _)| same_mesh(m, mesh))
    }

    fn is_building(&self, mesh: &Arc<Mesh>) -> bool {
        self.in_flight
            .iter()
            .any(|f| f.meshes.iter().any(|m| same_mesh(m, mesh)))
    }

    /// Takes the trees workers have finished, without waiting.
    fn collect(&mut self) {
        let mut finished = Vec::new();
        for (k, flight) in self.in_flight.iter().enumerate() {
            loop {
                match flight.results.try_recv() {
                    Ok(built) => self.trees.push(built),
                    Err(TryRecvError::Empty) => break,
                    Err(TryRecvError::Disconnected) => {
                        finished.push(k);
                        break;
                    }
                }
            }
        }
        for k in finished.into_iter().rev() {
            self.in_flight.remove(k);
        }
        self.trees.retain(|(mesh, _)| mesh.strong_count() > 0);
    }

    /// Waits for the worker building `mesh`'s tree, keeping every tree it delivers meanwhile.
    fn wait_for(&mut self, mesh: &Arc<Mesh>) {
        let Some(k) = self
            .in_flight
            .iter()
            .position(|f| f.meshes.iter().any(|m| same_mesh(m, mesh)))
        else {
            return;
        };
        while let Ok(built) = self.in_flight[k].results.recv() {
            let done = same_mesh(&built.0, mesh);
            self.trees.push(built);
            if done {
                return;
            }
        }
        // The worker ended without it (it panicked): whatever it had is taken, the rest is
        // built where it is needed.
        self.in_flight.remove(k);
    }

    /// The ray-pick tree of `mesh`: kept, waited for when a worker builds it, else built here.
    pub fn tree(&mut self, mesh: &Arc<Mesh>) -> Arc<PickIndex> {
        self.collect();
        if !self.has_tree(mesh) && self.is_building(mesh) {
            self.wait_for(mesh);
        }
        if let Some((_, tree)) = self.trees.iter().find(|(m, _)| same_mesh(m, mesh)) {
            return tree.clone();
        }
        let tree = Arc::new(PickIndex::build(mesh));
        self.built_by_caller += 1;
        self.trees.push((Arc::downgrade(mesh), tree.clone()));
        tree
    }

    /// Number of trees kept.
    pub fn len(&self) -> usize {
        self.trees.len()
    }

    /// True when no tree is kept.
    pub fn is_empty(&self) -> bool {
        self.trees.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneModel;
    use glam::DVec3;

    fn cube(min: DVec3, max: DVec3) -> Arc<Mesh> {
        Arc::new(csg::testkit::cube(min, max))
    }

    #[test]
    fn the_front_visible_model_is_picked_and_trees_follow_the_meshes() {
        let mut scene = Scene::default();
        let far = cube(DVec3::new(-1.0, 5.0, -1.0), DVec3::new(1.0, 7.0, 1.0));
        let near = cube(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0));
        scene
            .models
            .push(SceneModel::new("far", "far.obj", far, [1.0; 3]));
        scene
            .models
            .push(SceneModel::new("near", "near.obj", near, [1.0; 3]));
        let ray = cutter::Ray {
            origin: DVec3::new(0.1, -10.0, 0.2),
            direction: DVec3::Y,
        };
        let mut picks = ScenePicks::default();
        let (model, t) = picks.pick(&scene, &ray).expect("a hit");
        assert_eq!(model, 1);
        assert!((t - 9.0).abs() < 1e-12, "{t}");
        scene.models[1].visible = false;
        let (model, t) = picks.pick(&scene, &ray).expect("a hit");
        assert_eq!(model, 0);
        assert!((t - 15.0).abs() < 1e-12, "{t}");
        let miss = cutter::Ray {
            origin: DVec3::new(5.0, -10.0, 0.2),
            direction: DVec3::Y,
        };
        assert_eq!(picks.pick(&scene, &miss), None);
        assert_eq!(picks.len(), 2);
        // A model replaced by another mesh: the old tree goes with the old mesh.
        scene.models[0].model.mesh = cube(DVec3::new(-1.0, 2.0, -1.0), DVec3::new(1.0, 3.0, 1.0));
        let (_, t) = picks.pick(&scene, &ray).expect("a hit");
        assert!((t - 12.0).abs() < 1e-12, "{t}");
        assert_eq!(picks.len(), 2, "one tree per live mesh");
        assert_eq!(
            picks.built_by_caller(),
            3,
            "nobody prepared: built where picked"
        );
    }

    /// Prepared trees are built by a worker: a pick right after `prepare` (before or after the
    /// worker is done) builds none on the calling thread and gives the same answer.
    #[test]
    fn prepared_trees_are_built_off_the_calling_thread() {
        let mut scene = Scene::default();
        let sphere = Arc::new(csg::testkit::geodesic_sphere(40, 10.0));
        scene
            .models
            .push(SceneModel::new("sphere", "sphere.ply", sphere, [1.0; 3]));
        let far = cube(DVec3::new(-1.0, 20.0, -1.0), DVec3::new(1.0, 22.0, 1.0));
        scene
            .models
            .push(SceneModel::new("far", "far.obj", far, [1.0; 3]));
        let ray = cutter::Ray {
            origin: DVec3::new(0.5, -50.0, 0.3),
            direction: DVec3::Y,
        };
        let mut cold = ScenePicks::default();
        let expected = cold.pick(&scene, &ray).expect("the sphere");
        assert_eq!(cold.built_by_caller(), 2);

        // At once: the press waits for the worker instead of building.
        let mut picks = ScenePicks::default();
        picks.prepare(&scene);
        assert_eq!(picks.pick(&scene, &ray), Some(expected));
        assert_eq!(picks.built_by_caller(), 0);

        // Prepared in time: every tree is there before the first press.
        let mut picks = ScenePicks::default();
        picks.prepare(&scene);
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        while !picks.ready_for(&scene) {
            assert!(std::time::Instant::now() < deadline, "the trees never came");
            std::thread::sleep(std::time::Duration::from_millis(2));
            picks.prepare(&scene);
        }
        assert_eq!(picks.len(), 2);
        assert_eq!(picks.pick(&scene, &ray), Some(expected));
        assert_eq!(picks.built_by_caller(), 0);

        // A replaced mesh is prepared again, by the worker.
        scene.models[0].model.mesh = cube(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0));
        assert!(!picks.ready_for(&scene));
        picks.prepare(&scene);
        assert_eq!(picks.pick(&scene, &ray).map(|(m, _)| m), Some(0));
        assert_eq!(picks.built_by_caller(), 0);
    }
}
