//! Finding a structure by the name a user types (`metrics --focus`, `--critical`, `render
//! --labels`): one rule for every command.
//!
//! The name is the model's as the list shows it. A model read from a file with a single region
//! was once named with a region number (`organ 1`); scripts written then still name it so, and
//! that older name finds the model when no model carries it.

use crate::scene::{ModelUnit, Scene};

/// The index of the model named `name`, or an error listing every structure (`what` leads the
/// message: the option that named it).
pub fn model_named(scene: &Scene, name: &str, what: &str) -> anyhow::Result<usize> {
    find(scene, name).ok_or_else(|| {
        let names: Vec<&str> = scene.models.iter().map(|m| m.model.name.as_str()).collect();
        anyhow::anyhow!(
            "{what}no structure named '{name}' (structures: {})",
            names.join(", ")
        )
    })
}

fn find(scene: &Scene, name: &str) -> Option<usize> {
    let models = &scene.models;
    if let Some(i) = models.iter().position(|m| m.model.name == name) {
        return Some(i);
    }
    // `organ 1`: the region-numbered name of a single-region file's model `organ`.
    let plain = name.strip_suffix(" 1")?;
    models
        .iter()
        .position(|m| m.model.name == plain && m.unit == ModelUnit::Region)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneModel;
    use std::sync::Arc;

    fn scene(names: &[(&str, ModelUnit)]) -> Scene {
        let mut scene = Scene::default();
        for (name, unit) in names {
            let cube = csg::testkit::cube(glam::DVec3::ZERO, glam::DVec3::ONE);
            let mut model = SceneModel::new(*name, "m.obj", Arc::new(cube), [0.5; 3]);
            model.unit = *unit;
            scene.models.push(model);
        }
        scene
    }

    #[test]
    fn a_name_finds_its_model_and_the_old_region_number_still_does() {
        let s = scene(&[
            ("skin", ModelUnit::Region),
            ("organ", ModelUnit::Region),
            ("pair 1", ModelUnit::Region),
            ("pair 2", ModelUnit::Region),
        ]);
        assert_eq!(model_named(&s, "organ", "").unwrap(), 1);
        assert_eq!(model_named(&s, "organ 1", "").unwrap(), 1);
        assert_eq!(model_named(&s, "pair 2", "").unwrap(), 3);
        let err = model_named(&s, "pair", "--focus: ")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("--focus: no structure named 'pair'") && err.contains("pair 1, pair 2"),
            "{err}"
        );
    }

    #[test]
    fn a_structure_named_with_a_number_is_not_an_alias() {
        // A structure really named "lesion 1" is found by that name; "lesion" (a structure) is
        // never reached through "lesion 1" (structures were never numbered).
        let s = scene(&[("lesion", ModelUnit::Structure)]);
        assert!(model_named(&s, "lesion 1", "").is_err());
        let s = scene(&[
            ("lesion", ModelUnit::Region),
            ("lesion 1", ModelUnit::Region),
        ]);
        assert_eq!(model_named(&s, "lesion 1", "").unwrap(), 1);
    }
}
