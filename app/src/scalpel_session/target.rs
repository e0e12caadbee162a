//! Which size a tool's default lengths follow, and the scalpel's lengths kept in step with it.
//!
//! A scene in metres may hold a 1.8 m body and a 20 mm gland; a length sized from the scene's
//! box is a thousand times too big for the gland. So every default a tool starts with follows
//! the **target**: the model the tool works on (the selected model, or the one a stroke starts
//! on), the scene only when there is none ([`target_box`], [`defaults_for`]). The cutter's δ
//! follows the same box ([`cutter::EditorSettings::delta_for_target`]), and with it the ribbons
//! and slices, which are fractions of the cutter's spacing.
//!
//! The scalpel's depth and opening are settings the user edits in the panel, so they follow a
//! new target only while they still hold the lengths given for the previous one
//! ([`ScalpelSizing`]): a length the user chose stays until the next scene.

use std::sync::Arc;

use csg::{Aabb, Mesh};

use crate::scalpel_session::ScalpelSettings;
use crate::scene::Scene;
use crate::scene::units::SizeDefaults;

/// The box a tool on `model` is sized from: that model's, else (no model, or an empty one) the
/// scene's ([`Scene::bbox`]: the models shown).
pub fn target_box(scene: &Scene, model: Option<usize>) -> Aabb {
    model
        .and_then(|m| scene.models.get(m))
        .map(|m| m.model.mesh.bbox())
        .filter(|b| !b.is_empty() && b.diagonal() > 0.0)
        .unwrap_or_else(|| scene.bbox())
}

/// The default lengths of a tool working on `model` ([`target_box`]).
pub fn defaults_for(scene: &Scene, model: Option<usize>) -> SizeDefaults {
    SizeDefaults::of(&target_box(scene, model))
}

/// What the scalpel's lengths were last sized for.
#[derive(Clone, Debug, Default)]
pub struct ScalpelSizing {
    /// The target: its model index and mesh (a replaced mesh is a new target), or `None` for
    /// the whole scene.
    target: Option<(usize, Arc<Mesh>)>,
    /// Depth and opening given for it; `None` before the first sizing.
    given: Option<(f64, f64)>,
}

impl ScalpelSizing {
    /// Gives `settings` the depth and opening of `model` (else the scene) when the target is
    /// new and the lengths are still the ones given for the previous target (or none were
    /// given yet). Returns true when it changed them.
    pub fn follow(
        &mut self,
        scene: &Scene,
        model: Option<usize>,
        settings: &mut ScalpelSettings,
    ) -> bool {
        let target = model.and_then(|m| scene.models.get(m).map(|s| (m, s.model.mesh.clone())));
        let same = match (&self.target, &target) {
            (Some((a, m)), Some((b, n))) => a == b && Arc::ptr_eq(m, n),
            (None, None) => self.given.is_some(),
            _ => false,
        };
        if same {
            return false;
        }
        let untouched = self
            .given
            .is_none_or(|given| given == (settings.depth, settings.opening));
        self.target = target;
        if !untouched {
            return false;
        }
        self.resize(scene, model, settings);
        true
    }

    /// Gives `settings` the lengths of `model` (else the scene) whatever they were: a new scene.
    pub fn resize(&mut self, scene: &Scene, model: Option<usize>, settings: &mut ScalpelSettings) {
        let d = defaults_for(scene, model);
        settings.depth = d.scalpel_depth;
        settings.opening = d.scalpel_opening;
        self.target = model.and_then(|m| scene.models.get(m).map(|s| (m, s.model.mesh.clone())));
        self.given = Some((settings.depth, settings.opening));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneModel;
    use glam::DVec3;

    /// A 1.8 m body in metres and a 20 mm structure inside it.
    fn body_and_gland() -> Scene {
        let mut scene = Scene::default();
        let body = csg::testkit::cube(DVec3::new(-0.25, 0.0, -0.15), DVec3::new(0.25, 1.8, 0.15));
        let gland = csg::testkit::cube(DVec3::new(0.05, 1.0, 0.0), DVec3::new(0.07, 1.02, 0.02));
        scene.models.push(SceneModel::new(
            "body",
            "body.obj",
            Arc::new(body),
            [1.0; 3],
        ));
        scene.models.push(SceneModel::new(
            "gland",
            "gland.obj",
            Arc::new(gland),
            [1.0; 3],
        ));
        scene
    }

    #[test]
    fn lengths_follow_the_target_not_the_scene() {
        let scene = body_and_gland();
        let whole = defaults_for(&scene, None);
        let gland = defaults_for(&scene, Some(1));
        assert!((whole.size - scene.bbox().diagonal()).abs() < 1e-12);
        // The gland's diagonal is 34.6 mm: a 1 mm blade, not the body's 56 mm.
        assert!((gland.scalpel_depth - 0.03 * 0.02 * 3f64.sqrt()).abs() < 1e-12);
        assert!(gland.scalpel_depth < 0.1 * 0.02, "{}", gland.scalpel_depth);
        assert!(whole.scalpel_depth > 25.0 * gland.scalpel_depth);
        assert!(gland.min_camera_distance < 1e-4);
        // A model index that does not exist is the scene.
        assert_eq!(defaults_for(&scene, Some(7)), whole);
    }

    #[test]
    fn the_scalpel_follows_a_new_target_until_the_user_sets_a_length() {
        let scene = body_and_gland();
        let mut settings = ScalpelSettings::default();
        let mut sizing = ScalpelSizing::default();
        sizing.resize(&scene, None, &mut settings);
        let whole = settings;
        assert!(!sizing.follow(&scene, None, &mut settings), "same target");
        assert!(sizing.follow(&scene, Some(1), &mut settings));
        assert!(settings.depth < 0.05 * whole.depth, "{}", settings.depth);
        assert!(settings.opening > 0.0 && settings.opening < settings.depth);
        // Back to the body: the gland's lengths were untouched, so they follow.
        assert!(sizing.follow(&scene, Some(0), &mut settings));
        assert_eq!(settings.depth, defaults_for(&scene, Some(0)).scalpel_depth);
        // The user sets a depth: it stays when the target changes.
        settings.depth = 0.004;
        assert!(!sizing.follow(&scene, Some(1), &mut settings));
        assert_eq!(settings.depth, 0.004);
        // A new scene sizes them again.
        sizing.resize(&scene, Some(1), &mut settings);
        assert_eq!(settings.depth, defaults_for(&scene, Some(1)).scalpel_depth);
    }
}
