//! Expose on the default head: a few deep structures from standard views are seen after the
//! exact cuts as well as they are with everything else hidden (the whole table of structures ×
//! views is `tests/expose.rs`'s ignored test), the cutters are valid and aimed at what hides the
//! focus, and the summary says so.

use std::sync::OnceLock;

use super::*;
use crate::metrics::{exposure_as_drawn, exposure_unoccluded};
use crate::scene::SceneModel;
use crate::scene::{Orientation, ViewPreset};

/// Rays per exposure estimate: standard error at most 0.5/√4000 ≈ 0.008.
const SAMPLES: usize = 4000;

/// The default scene as the window opens it (skin, then the deep structures), RAS.
fn head() -> &'static Scene {
    static HEAD: OnceLock<Scene> = OnceLock::new();
    HEAD.get_or_init(|| {
        let models = crate::anatomy::default_scene::load().expect("the default scene loads");
        let mut scene = Scene::default();
        for (i, model) in models.into_iter().enumerate() {
            let color = crate::anatomy::colors::structure_color(&model.name, model.color, i);
            scene.models.push(SceneModel::structure(model, color));
        }
        scene.orientation = Orientation::RAS;
        scene.unit = LengthUnit::guess(&scene.bbox(), true);
        scene
    })
}

/// The head seen from `preset`, as View → that preset frames it.
fn seen_from(preset: ViewPreset) -> Scene {
    let mut scene = head().clone();
    scene.camera = scene.preset_camera(preset);
    scene
}

fn model(scene: &Scene, name: &str) -> usize {
    crate::metrics::structure_index(scene, name).unwrap()
}

/// Exposes `focus` from `preset` and checks the goal: seen after the cuts at least 0.9 × as
/// much as with everything else hidden. Returns the scenes before and after and the exposure.
fn exposed(focus: &str, preset: ViewPreset) -> (Scene, Scene, Exposed) {
    let before = seen_from(preset);
    let f = model(&before, focus);
    let exposed = plan(&before, f, &ExposeSettings::default(), &Progress::default()).unwrap();
    assert!(exposed.notes.is_empty(), "{:?}", exposed.notes);
    let mut after = before.clone();
    apply(&mut after, &exposed);
    for c in &after.cutters {
        c.cutter.validate().unwrap();
    }
    let free = exposure_unoccluded(&after, f, SAMPLES).unwrap();
    let was = exposure_as_drawn(&before, f, SAMPLES).unwrap();
    let seen = exposure_as_drawn(&after, f, SAMPLES).unwrap();
    assert!(
        seen >= 0.9 * free,
        "{focus} from {preset:?}: {was:.3} → {seen:.3}, unoccluded {free:.3}"
    );
    assert!(
        was < 0.5 * free,
        "{focus} from {preset:?} was hidden: {was:.3}"
    );
    (before, after, exposed)
}

#[test]
fn the_left_lateral_ventricle_from_the_front_is_opened_through_the_skin_first() {
    let (before, after, exposed) = exposed("left lateral ventricle", ViewPreset::Anterior);
    let skin = model(&before, "skin");
    assert_eq!(exposed.cutters[0].target, skin, "the skin is nearest");
    assert_eq!(exposed.opened[0], skin);
    assert_eq!(after.cutters.len(), exposed.cutters.len());
    // Every cutter is aimed at a structure that is not the focus, and only the new cutters are
    // in the scene after.
    assert!(exposed.cutters.iter().all(|c| c.target != exposed.focus));
    let removed = report::removed_volume_mm3(&after, 0).unwrap().unwrap();
    assert!(removed > 1000.0, "{removed} mm³ of skin and more");
    let line = summary(&after, &exposed, Some(removed));
    assert!(
        line.starts_with("Exposed left lateral ventricle: ") && line.contains(" through skin"),
        "{line}"
    );
    assert!(line.contains(" mm³ removed"), "{line}");
}

#[test]
fn the_left_caudate_from_the_left_and_the_third_ventricle_from_above_are_seen() {
    exposed("left caudate nucleus", ViewPreset::Left);
    exposed("third ventricle", ViewPreset::Superior);
}

#[test]
fn a_wider_margin_removes_more() {
    let before = seen_from(ViewPreset::Anterior);
    let f = model(&before, "left hippocampus");
    let volume = |margin_mm: f64| {
        let e = plan(
            &before,
            f,
            &ExposeSettings { margin_mm },
            &Progress::default(),
        )
        .unwrap();
        let mut after = before.clone();
        apply(&mut after, &e);
        report::removed_volume_mm3(&after, 0).unwrap().unwrap()
    };
    let (narrow, wide) = (volume(1.0), volume(8.0));
    assert!(wide > narrow * 1.3, "{narrow} → {wide} mm³");
}

#[test]
fn bad_margins_and_foci_are_refused_and_a_structure_in_view_needs_nothing() {
    let scene = seen_from(ViewPreset::Anterior);
    for margin_mm in [-1.0, f64::NAN, 1000.0] {
        let err = plan(
            &scene,
            1,
            &ExposeSettings { margin_mm },
            &Progress::default(),
        )
        .unwrap_err();
        assert!(err.to_string().contains("margin"), "{err}");
    }
    assert!(
        plan(
            &scene,
            10_000,
            &ExposeSettings::default(),
            &Progress::default()
        )
        .is_err()
    );
    let stop = Progress::default();
    stop.cancel();
    let cancelled = plan(&scene, 1, &ExposeSettings::default(), &stop).unwrap_err();
    assert!(crate::platform::jobs::is_cancelled(&cancelled));
    // The skin from the front hides behind nothing.
    let skin = model(&scene, "skin");
    let e = plan(
        &scene,
        skin,
        &ExposeSettings::default(),
        &Progress::default(),
    )
    .unwrap();
    assert!(e.cutters.is_empty());
    assert_eq!(
        summary(&scene, &e, None),
        "skin is in full view: nothing to open"
    );
}
