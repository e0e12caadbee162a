//! Which model the pointer is over: the first hit of a ray through the scene's visible models,
//! each through its own [`PickIndex`] (an `obvhs` BVH with csg's watertight `f64` triangle test
//! on its candidates), built the first time the model is picked and kept while its mesh lives.
//!
//! A pick is one ray per click, but over millions of triangles a scan costs tens of
//! milliseconds on every click; the tree makes each pick microseconds after a one-off build.

use std::sync::{Arc, Weak};

use csg::{Mesh, PickIndex};

use crate::scene::Scene;

/// The ray-pick trees of the models picked so far (see the module documentation).
#[derive(Default)]
pub struct ScenePicks {
    trees: Vec<(Weak<Mesh>, Arc<PickIndex>)>,
}

impl ScenePicks {
    /// The visible model `ray` hits first, with the ray parameter of the hit.
    pub fn pick(&mut self, scene: &Scene, ray: &cutter::Ray) -> Option<(usize, f64)> {
        self.trees.retain(|(mesh, _)| mesh.strong_count() > 0);
        let mut best: Option<(usize, f64)> = None;
        for (i, model) in scene.models.iter().enumerate() {
            if !model.visible || model.opacity <= 0.0 || model.mesh.triangles.is_empty() {
                continue;
            }
            let t_max = best.map_or(f64::INFINITY, |(_, t)| t);
            let tree = self.tree(&model.mesh);
            if let Some(hit) = tree.ray_cast(&model.mesh, ray.origin, ray.direction, t_max)
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

    fn tree(&mut self, mesh: &Arc<Mesh>) -> Arc<PickIndex> {
        if let Some((_, tree)) = self
            .trees
            .iter()
            .find(|(m, _)| m.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
        {
            return tree.clone();
        }
        let tree = Arc::new(PickIndex::build(mesh));
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
        scene.models[0].mesh = cube(DVec3::new(-1.0, 2.0, -1.0), DVec3::new(1.0, 3.0, 1.0));
        let (_, t) = picks.pick(&scene, &ray).expect("a hit");
        assert!((t - 12.0).abs() < 1e-12, "{t}");
        assert_eq!(picks.len(), 2, "one tree per live mesh");
    }
}
