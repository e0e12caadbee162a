//! How long the window's Metrics panel takes to update after a drag is released: one
//! [`cutaway::metrics::measure`] (the code `cutaway metrics` runs) on the embedded knee and on the
//! SPL head atlas, each cut by a box from the front of its skin to its middle, with a focus structure (exposure from the
//! camera) and one critical structure. The peer is the Preview cut of the same scene
//! ([`cutaway::cutting::cut_scene::preview_geometry`]), which the window computes anyway: the
//! ratio says what measuring costs on top of cutting.
//!
//! Run: `cargo bench -p cutaway --bench metrics_update` (add `--profile dev` for the figure of a
//! development build). Prints the median of five runs per scene.

use std::time::Instant;

use cutaway::metrics::{MetricsOptions, measure};
use cutaway::scene::{CutterViews, Scene, SceneCutter, SceneModel};
use cutter::CutKind;
use glam::DVec3;

/// A box cutter through `min`..`max`: three planes across x, each spanning y and z.
fn box_cutter(target: usize, min: DVec3, max: DVec3) -> SceneCutter {
    let plane = |x: f64| {
        cutter::BoundedPlane::from_corners([
            DVec3::new(x, min.y, max.z),
            DVec3::new(x, max.y, max.z),
            DVec3::new(x, max.y, min.z),
            DVec3::new(x, min.y, min.z),
        ])
    };
    SceneCutter {
        target,
        cutter: cutter::Cutter {
            kind: CutKind::Curving,
            smooth: false,
            levels: cutter::subdivision::DEFAULT_LEVELS,
            direction: cutter::CutDirection::Normal,
            planes: vec![plane(min.x), plane((min.x + max.x) * 0.5), plane(max.x)],
        },
        views: CutterViews::default(),
    }
}

/// A scene of `models` cut by a box reaching from outside the front of the skin to its middle, a
/// third of its width and height, seen from the front.
fn cut_scene(models: Vec<cutaway::io::Model>) -> Scene {
    let mut scene = Scene::default();
    for (i, model) in models.into_iter().enumerate() {
        let color = cutaway::anatomy::colors::structure_color(&model.name, model.color, i);
        scene.models.push(SceneModel::structure(model, color));
    }
    let skin = scene
        .models
        .iter()
        .position(|m| m.model.name.contains("skin"))
        .expect("a skin");
    let b = scene.models[skin].model.mesh.bbox();
    let (c, e) = (b.center(), b.max - b.min);
    // The window's guess of the patient's axes: the box reaches from outside the front (anterior,
    // along ±y) to the middle, and the camera looks at the front.
    scene.orientation = cutaway::scene::Orientation::guess(&scene.bbox(), false);
    let front = scene.orientation.anterior.y.signum();
    let (y0, y1) = if front >= 0.0 {
        (c.y, b.max.y + e.y * 0.1)
    } else {
        (b.min.y - e.y * 0.1, c.y)
    };
    let min = DVec3::new(c.x - e.x / 6.0, y0, c.z - e.z / 6.0);
    let max = DVec3::new(c.x + e.x / 6.0, y1, c.z + e.z / 6.0);
    scene.cutters.push(box_cutter(skin, min, max));
    let (toward_eye, up) = (DVec3::Y * front, DVec3::Z);
    scene.camera = cutter::Camera::framing(&b, toward_eye, up, scene.camera.fov_y_deg);
    scene
}

fn median_ms(mut run: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let started = Instant::now();
            run();
            started.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

fn bench(name: &str, scene: &Scene, focus: &str, critical: &str) {
    let pick = |part: &str| {
        scene
            .models
            .iter()
            .find(|m| m.model.name.contains(part))
            .map(|m| m.model.name.clone())
            .unwrap_or_else(|| panic!("{name}: no structure named like '{part}'"))
    };
    let options = MetricsOptions {
        focus: Some(pick(focus)),
        critical: vec![pick(critical)],
        ..MetricsOptions::default()
    };
    let metrics = measure(scene, &options).expect("measure");
    let triangles: usize = scene
        .models
        .iter()
        .map(|m| m.model.mesh.triangle_count())
        .sum();
    let measure_ms = median_ms(|| {
        std::hint::black_box(measure(scene, &options).expect("measure"));
    });
    let cut_ms = median_ms(|| {
        std::hint::black_box(cutaway::cutting::cut_scene::preview_geometry(scene));
    });
    let removed: f64 = metrics
        .structures
        .iter()
        .filter_map(|s| s.removed_volume)
        .sum();
    println!(
        "{name}: {} structures, {triangles} triangles; removed {removed:.0} mm³; \
         metrics panel update {measure_ms:.0} ms (median of 5), Preview cut {cut_ms:.0} ms, \
         ratio {:.1}×",
        scene.models.len(),
        measure_ms / cut_ms.max(1e-9)
    );
}

fn main() {
    let knee = cutaway::anatomy::assets::scene("knee").expect("the knee scene");
    let knee =
        cut_scene(cutaway::anatomy::assets::load_scene_structures(knee).expect("load the knee"));
    bench("knee", &knee, "femur", "popliteal");
    let head = cut_scene(cutaway::anatomy::default_scene::load().expect("load the SPL head"));
    bench("SPL head", &head, "left lateral ventricle", "optic chiasm");
}
