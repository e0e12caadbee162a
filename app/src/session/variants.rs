//! The session fields of cut variants ([`crate::scene::variants`]), kept apart from the rest of the
//! session format so they can grow without touching it:
//!
//! ```json
//! "cutters": [ …the active variant's cutters… ],
//! "variants": [{"name": "straight", "cutters": [ … ]}, {"name": "wedge", "cutters": [ … ]}],
//! "active_variant": 1
//! ```
//!
//! - Both fields are optional: a file without them (every file written before variants existed)
//!   has one implicit variant, its `cutters`.
//! - `cutters` stays the active variant's cutters, so a reader that knows no variants (an older
//!   Cutaway) opens the active variant. The active variant's entry repeats them when Cutaway
//!   writes the file; on load the top-level `cutters` are what counts for the active variant.
//! - Variant names are 1 to 80 characters, distinct, without control characters;
//!   `active_variant` (default 0) indexes `variants`. Every variant's cutters obey the rules and
//!   limits of `cutters` ([`crate::session::limits`]); errors name the variant.

use serde::{Deserialize, Serialize};

use crate::scene::Scene;
use crate::scene::variants::{Variant, Variants};
use crate::session::cutters::{CutterEntry, cutter_entry, cutter_from_entry};

/// One variant as stored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariantEntry {
    pub name: String,
    #[serde(default)]
    pub cutters: Vec<CutterEntry>,
}

/// serde's `skip_serializing_if` for `active_variant`.
pub fn is_zero(value: &usize) -> bool {
    *value == 0
}

/// The variants a parsed session describes (empty when it has none). The active variant's
/// cutters are the top-level `cutters`, which the caller has loaded into the scene.
pub fn from_entries(variants: &[VariantEntry], active: usize) -> anyhow::Result<Variants> {
    if variants.is_empty() {
        if active != 0 {
            anyhow::bail!(
                "active_variant {} given but the session has no variants",
                active
            );
        }
        return Ok(Variants::default());
    }
    if active >= variants.len() {
        anyhow::bail!(
            "active_variant {} does not exist (there are {} variants)",
            active,
            variants.len()
        );
    }
    let mut list = Vec::with_capacity(variants.len());
    for (k, entry) in variants.iter().enumerate() {
        let cutters = if k == active {
            Vec::new()
        } else {
            entry
                .cutters
                .iter()
                .enumerate()
                .map(|(i, c)| cutter_from_entry(i, c))
                .collect::<anyhow::Result<Vec<_>>>()
                .map_err(|e| anyhow::anyhow!("variant {k} ('{}'): {e}", entry.name))?
        };
        list.push(Variant {
            name: entry.name.clone(),
            cutters,
        });
    }
    Ok(Variants { list, active })
}

/// The `variants` and `active_variant` fields describing `scene`'s variants (none when it
/// defines none); the active entry repeats the scene's cutters.
pub fn entries(scene: &Scene) -> (Vec<VariantEntry>, usize) {
    if scene.variants.is_empty() {
        return (Vec::new(), 0);
    }
    let list = crate::scene::variants::all(scene)
        .into_iter()
        .map(|(name, cutters)| VariantEntry {
            name,
            cutters: cutters.iter().map(cutter_entry).collect(),
        })
        .collect();
    (list, scene.variants.active)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::scene::ModelUnit;
    use crate::session::{file_from_scene, parse, scene_from_file};

    fn one_sphere(path: &Path, _: ModelUnit) -> anyhow::Result<Vec<crate::io::Model>> {
        Ok(vec![crate::io::Model {
            name: "ball".into(),
            source: path.to_path_buf(),
            index: 0,
            color: None,
            group: String::new(),
            mesh: csg::testkit::icosphere(1, 1.0).into(),
        }])
    }

    const PLANE_A: &str = "[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]";
    const PLANE_B: &str = "[[0.5,0,0],[0.5,1,0],[0.5,1,-1],[0.5,0,-1]]";

    fn text(variants: &str, active: usize) -> String {
        format!(
            r#"{{"format": "cutaway-session/2", "models": [{{"path": "ball.obj"}}],
               "cutters": [{{"target": 0, "kind": "straight", "planes": [{PLANE_A}]}}],
               "variants": {variants}, "active_variant": {active}}}"#
        )
    }

    #[test]
    fn variants_load_save_and_load_again_unchanged() {
        let variants = format!(
            r#"[{{"name": "straight", "cutters": [{{"target": 0, "kind": "straight", "planes": [{PLANE_A}]}}]}},
                {{"name": "wedge", "cutters": [{{"target": 0, "kind": "wedge", "planes": [{PLANE_B}]}}]}}]"#
        );
        let file = parse(&text(&variants, 0)).unwrap();
        let scene = scene_from_file(&file, Path::new("/s"), &mut one_sphere).unwrap();
        assert_eq!(crate::scene::variants::names(&scene), ["straight", "wedge"]);
        let all = crate::scene::variants::all(&scene);
        assert_eq!(all[1].1[0].cutter.kind, cutter::CutKind::Wedge);
        assert_eq!(all[1].1[0].cutter.planes[0].front_top.x, 0.5);
        let saved = file_from_scene(&scene, Path::new("/s"));
        assert_eq!(saved.variants.len(), 2);
        assert_eq!(saved.variants[0].cutters, saved.cutters);
        let again = scene_from_file(&saved, Path::new("/s"), &mut one_sphere).unwrap();
        assert_eq!(again.variants, scene.variants);
        assert_eq!(again.cutters, scene.cutters);
    }

    #[test]
    fn a_file_without_variants_saves_without_them() {
        let text = format!(
            r#"{{"format": "cutaway-session/2", "models": [{{"path": "ball.obj"}}],
               "cutters": [{{"target": 0, "planes": [{PLANE_A}]}}]}}"#
        );
        let file = parse(&text).unwrap();
        let scene = scene_from_file(&file, Path::new("/s"), &mut one_sphere).unwrap();
        assert!(scene.variants.is_empty());
        let json = serde_json::to_string(&file_from_scene(&scene, Path::new("/s"))).unwrap();
        assert!(!json.contains("variants"), "{json}");
    }

    #[test]
    fn bad_variants_are_one_error_naming_the_variant() {
        let error = |variants: &str, active: usize| {
            let load = parse(&text(variants, active)).and_then(|file| {
                scene_from_file(&file, Path::new("/s"), &mut one_sphere).map(|_| ())
            });
            format!("{:#}", load.unwrap_err())
        };
        let e = error(r#"[{"name": "a"}]"#, 3);
        assert!(e.contains("active_variant 3"), "{e}");
        let e = error(
            r#"[{"name": "a"}, {"name": "b", "cutters": [{"target": 4, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]]}]}]"#,
            0,
        );
        assert!(e.contains("variant 1 ('b'): cutter 0: target 4"), "{e}");
        let e = error(
            r#"[{"name": "a"}, {"name": "b", "cutters": [{"target": 0, "kind": "spiral", "planes": []}]}]"#,
            0,
        );
        assert!(e.contains("variant 1 ('b'): cutter 0: kind"), "{e}");
        let e = error(r#"[{"name": "a"}, {"name": "a"}]"#, 0);
        assert!(e.contains("used twice"), "{e}");
        let many = vec![r#"{"name": "x"}"#; crate::session::limits::MAX_VARIANTS + 1].join(",");
        let e = error(&format!("[{many}]"), 0);
        assert!(e.contains("variants: 65 variants"), "{e}");
        let e = error(&text_plane_flood(), 0);
        assert!(e.contains("variant 0: cutter 0: planes[0]"), "{e}");
    }

    fn text_plane_flood() -> String {
        r#"[{"name": "a", "cutters": [{"target": 0, "planes": [[[0,0,0],[0,1e300,0],[0,1,-1],[0,0,-1]]]}]}]"#
            .to_string()
    }
}
