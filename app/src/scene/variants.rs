//! Cut variants: named cutter sets on the same models, so a planner can try a straight cut, a
//! wedge and a rounded cut on one case and compare them (`cutaway compare`, the window's compare
//! view).
//!
//! The scene's own `cutters` are always the cutters of the **active** variant, so every command
//! and view that knows nothing of variants (render, export, metrics, the editor) works on the
//! active one unchanged. [`Variants`] keeps the names and the cutters of the others; switching
//! stores the scene's cutters into the variant being left and takes those of the variant
//! switched to. A scene with no variants has one implicit variant, its cutters, named
//! [`DEFAULT_NAME`].

use crate::scene::{Scene, SceneCutter};

/// One named cutter set (`scene/variants.rs` switches and creates them).
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    pub name: String,
    /// The variant's cutters; for the active variant this copy is stale: the scene's `cutters`
    /// are its cutters.
    pub cutters: Vec<SceneCutter>,
}

/// The variants of a scene: empty (one implicit variant, the scene's cutters) or every variant,
/// the active one included, in the order they are shown.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Variants {
    pub list: Vec<Variant>,
    /// Index into `list` of the variant whose cutters the scene holds (0 when `list` is empty).
    pub active: usize,
}

impl Variants {
    /// Longest variant name, in characters.
    pub const MAX_NAME_CHARS: usize = 80;

    /// Whether the scene defines variants of its own.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// A variant name is 1..=[`Self::MAX_NAME_CHARS`] characters without control characters.
    pub fn check_name(name: &str) -> Result<(), String> {
        if name.trim().is_empty() {
            return Err("a variant name cannot be empty".to_string());
        }
        if name.chars().count() > Self::MAX_NAME_CHARS {
            return Err(format!(
                "variant name '{}…' is longer than {} characters",
                name.chars().take(20).collect::<String>(),
                Self::MAX_NAME_CHARS
            ));
        }
        if name.chars().any(char::is_control) {
            return Err(format!("variant name {name:?} holds a control character"));
        }
        Ok(())
    }
}

impl Scene {
    /// Checks the variants: names usable and distinct, the active index inside the list, every
    /// other variant's cutters valid for the models (the same rules as the scene's cutters).
    pub fn check_variants(&self) -> Result<(), String> {
        let v = &self.variants;
        if v.is_empty() {
            return Ok(());
        }
        if v.active >= v.list.len() {
            return Err(format!(
                "active variant {} does not exist (there are {})",
                v.active,
                v.list.len()
            ));
        }
        for (k, variant) in v.list.iter().enumerate() {
            Variants::check_name(&variant.name).map_err(|e| format!("variant {k}: {e}"))?;
            if v.list[..k].iter().any(|w| w.name == variant.name) {
                return Err(format!(
                    "variant {k}: the name '{}' is used twice",
                    variant.name
                ));
            }
            if k != v.active {
                let mut shown = self.clone();
                shown.cutters = variant.cutters.clone();
                shown.variants = Variants::default();
                shown
                    .sanity_check()
                    .map_err(|e| format!("variant {k} ('{}'): {e}", variant.name))?;
            }
        }
        Ok(())
    }
}

/// The name of the one variant of a scene that defines none.
pub const DEFAULT_NAME: &str = "current";
/// Longest variant name, in characters.
pub const MAX_NAME_CHARS: usize = Variants::MAX_NAME_CHARS;

/// Every variant of `scene` as (name, cutters), the active one with the scene's live cutters; a
/// scene without variants gives one, [`DEFAULT_NAME`].
pub fn all(scene: &Scene) -> Vec<(String, Vec<SceneCutter>)> {
    if scene.variants.is_empty() {
        return vec![(DEFAULT_NAME.to_string(), scene.cutters.clone())];
    }
    scene
        .variants
        .list
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let cutters = if k == scene.variants.active {
                scene.cutters.clone()
            } else {
                v.cutters.clone()
            };
            (v.name.clone(), cutters)
        })
        .collect()
}

/// Names of the variants of `scene` in order (one, [`DEFAULT_NAME`], when it defines none).
pub fn names(scene: &Scene) -> Vec<String> {
    if scene.variants.is_empty() {
        return vec![DEFAULT_NAME.to_string()];
    }
    scene.variants.list.iter().map(|v| v.name.clone()).collect()
}

/// The scene showing variant `k` (its cutters as the scene's cutters), without variants: what a
/// viewport of the compare view or one image of `cutaway compare` draws and measures.
pub fn variant_scene(scene: &Scene, k: usize) -> Option<Scene> {
    let (_, cutters) = all(scene).into_iter().nth(k)?;
    let mut out = scene.clone();
    out.cutters = cutters;
    out.variants = Variants::default();
    Some(out)
}

/// Makes variant `k` the active one: the scene's cutters go to the variant left, the cutters of
/// `k` become the scene's.
pub fn switch(scene: &mut Scene, k: usize) -> Result<(), String> {
    let count = scene.variants.list.len().max(1);
    if k >= count {
        return Err(format!("variant {k} does not exist (there are {count})"));
    }
    if scene.variants.is_empty() || k == scene.variants.active {
        return Ok(());
    }
    let active = scene.variants.active;
    let left = std::mem::take(&mut scene.cutters);
    scene.variants.list[active].cutters = left;
    scene.cutters = scene.variants.list[k].cutters.clone();
    scene.variants.active = k;
    Ok(())
}

/// Adds a variant named `name` holding a copy of the active variant's cutters and makes it
/// active; a scene without variants first names its cutters [`DEFAULT_NAME`]. Returns its index.
pub fn create(scene: &mut Scene, name: &str) -> Result<usize, String> {
    let name = checked_name(scene, name, None)?;
    if scene.variants.is_empty() {
        if name == DEFAULT_NAME {
            return Err(format!("a variant named '{name}' exists already"));
        }
        scene.variants = Variants {
            list: vec![Variant {
                name: DEFAULT_NAME.to_string(),
                cutters: Vec::new(),
            }],
            active: 0,
        };
    }
    let active = scene.variants.active;
    scene.variants.list[active].cutters = scene.cutters.clone();
    scene.variants.list.push(Variant {
        name,
        cutters: scene.cutters.clone(),
    });
    scene.variants.active = scene.variants.list.len() - 1;
    Ok(scene.variants.active)
}

/// Renames variant `k` (a scene without variants first gets its one variant as a named one).
pub fn rename(scene: &mut Scene, k: usize, name: &str) -> Result<(), String> {
    let name = checked_name(scene, name, Some(k))?;
    if scene.variants.is_empty() {
        if k != 0 {
            return Err(format!("variant {k} does not exist (there is 1)"));
        }
        scene.variants = Variants {
            list: vec![Variant {
                name,
                cutters: Vec::new(),
            }],
            active: 0,
        };
        return Ok(());
    }
    let count = scene.variants.list.len();
    let variant = scene
        .variants
        .list
        .get_mut(k)
        .ok_or_else(|| format!("variant {k} does not exist (there are {count})"))?;
    variant.name = name;
    Ok(())
}

/// Removes variant `k` (not the last one); the active variant moves to its neighbour when it is
/// the one removed.
pub fn remove(scene: &mut Scene, k: usize) -> Result<(), String> {
    let count = scene.variants.list.len();
    if count <= 1 {
        return Err("the last variant cannot be removed".to_string());
    }
    if k >= count {
        return Err(format!("variant {k} does not exist (there are {count})"));
    }
    if k == scene.variants.active {
        let next = if k + 1 < count { k + 1 } else { k - 1 };
        switch(scene, next)?;
    }
    scene.variants.list.remove(k);
    if scene.variants.active > k {
        scene.variants.active -= 1;
    }
    Ok(())
}

/// `name` trimmed, when it is a usable new name for variant `k` (`None`: a new variant).
fn checked_name(scene: &Scene, name: &str, k: Option<usize>) -> Result<String, String> {
    let name = name.trim();
    check_name(name)?;
    let taken = scene
        .variants
        .list
        .iter()
        .enumerate()
        .any(|(i, v)| Some(i) != k && v.name == name);
    if taken {
        return Err(format!("a variant named '{name}' exists already"));
    }
    Ok(name.to_string())
}

/// A variant name is 1..=[`MAX_NAME_CHARS`] characters without control characters.
pub fn check_name(name: &str) -> Result<(), String> {
    Variants::check_name(name)
}

/// Checks the variants of `scene`: names usable and distinct, the active index inside the list,
/// every variant's cutters valid for the scene's models (the same rules as the scene's cutters).
pub fn check(scene: &Scene) -> Result<(), String> {
    scene.check_variants()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CutterViews, SceneModel};
    use cutter::CutKind;
    use glam::DVec3;

    fn cutter(x: f64) -> SceneCutter {
        SceneCutter {
            target: 0,
            cutter: cutter::Cutter {
                kind: CutKind::Straight,
                smooth: false,
                levels: cutter::subdivision::DEFAULT_LEVELS,
                direction: cutter::CutDirection::Normal,
                planes: vec![cutter::BoundedPlane::from_corners([
                    DVec3::X * x,
                    DVec3::Y,
                    DVec3::Z,
                    DVec3::ONE,
                ])],
            },
            views: CutterViews::default(),
        }
    }

    fn scene() -> Scene {
        let mut scene = Scene::default();
        scene.models.push(SceneModel::new(
            "a",
            "a.obj",
            std::sync::Arc::new(csg::testkit::icosphere(1, 1.0)),
            [1.0, 0.0, 0.0],
        ));
        scene.cutters.push(cutter(1.0));
        scene
    }

    #[test]
    fn a_scene_without_variants_has_one_implicit_variant() {
        let s = scene();
        assert_eq!(names(&s), [DEFAULT_NAME]);
        assert_eq!(all(&s), [(DEFAULT_NAME.to_string(), vec![cutter(1.0)])]);
        assert_eq!(variant_scene(&s, 0).unwrap().cutters, s.cutters);
        assert!(variant_scene(&s, 1).is_none());
    }

    #[test]
    fn create_switch_rename_and_remove_keep_each_variant_s_cutters() {
        let mut s = scene();
        assert_eq!(create(&mut s, " wedge "), Ok(1));
        assert_eq!(names(&s), ["current", "wedge"]);
        // The new variant starts as a copy and is edited on its own.
        s.cutters[0] = cutter(2.0);
        assert_eq!(all(&s)[0].1, [cutter(1.0)]);
        assert_eq!(all(&s)[1].1, [cutter(2.0)]);
        switch(&mut s, 0).unwrap();
        assert_eq!(s.cutters, [cutter(1.0)]);
        switch(&mut s, 1).unwrap();
        assert_eq!(s.cutters, [cutter(2.0)]);
        assert!(create(&mut s, "wedge").unwrap_err().contains("exists"));
        assert!(create(&mut s, "  ").is_err());
        assert!(switch(&mut s, 2).is_err());
        rename(&mut s, 0, "straight").unwrap();
        assert!(rename(&mut s, 0, "wedge").unwrap_err().contains("exists"));
        assert_eq!(names(&s), ["straight", "wedge"]);
        check(&s).unwrap();
        // Removing the active variant activates its neighbour with its own cutters.
        remove(&mut s, 1).unwrap();
        assert_eq!((names(&s), s.variants.active), (vec!["straight".into()], 0));
        assert_eq!(s.cutters, [cutter(1.0)]);
        assert!(remove(&mut s, 0).is_err());
    }

    #[test]
    fn check_refuses_bad_variants_naming_them() {
        let mut s = scene();
        create(&mut s, "b").unwrap();
        s.variants.list[0].cutters[0].target = 5;
        let e = check(&s).unwrap_err();
        assert!(
            e.contains("variant 0 ('current'): cutter 0: target 5"),
            "{e}"
        );
        s.variants.list[0].cutters[0].target = 0;
        s.variants.list[0].name = "b".into();
        assert!(check(&s).unwrap_err().contains("used twice"));
        s.variants.list[0].name = "a\u{1b}".into();
        assert!(check(&s).unwrap_err().contains("control"));
        s.variants.list[0].name = "a".into();
        s.variants.active = 7;
        assert!(check(&s).unwrap_err().contains("active variant 7"));
    }
}
