//! Scalpel mode in the real window (egui_kittest on the wgpu renderer, lavapipe without a GPU,
//! 1280×800): an opened incision shows its groove walls in the wall colour while the stroke is
//! drawn (the live patch over the uploaded model) and after it. Screenshots go to the test's
//! temporary folder (`CARGO_TARGET_TMPDIR`).
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (set `WGPU_BACKEND=vulkan` with
//! Mesa's lavapipe installed).

use crate::harness::{apply, harness, no_adapter, shot};
use csg::testkit::{Resource, skip};
use cutaway::gui::app::Action;
use cutaway::gui::{CutawayApp, Mode};
use cutaway::render::{WALL_MIX, WALL_TINT};
use egui_kittest::Harness;
use glam::DVec2;

/// The model's colour (sRGB): red, so its walls (the mix toward the cream wall tint) differ from
/// it in hue, not only in brightness.
const RED: [f32; 3] = [0.8, 0.2, 0.2];

fn linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear green/red of a colour given in sRGB components.
fn green_over_red(c: [f64; 3]) -> f64 {
    linear(c[1]) / linear(c[0])
}

/// Pixels of `image` inside the disc (`centre`, `radius`, image pixels: the sphere drawn less
/// its silhouette, whose edge blends red with the background) with the walls' hue: diffuse
/// light scales the channels alike, so green/red is the base colour's (0.055 for the model,
/// 0.45 for its walls; the white highlight lifts the model's to 0.3 at most).
fn wall_pixels(image: &image::RgbaImage, centre: DVec2, radius: f64) -> usize {
    let wall = RED.map(f64::from);
    let wall = std::array::from_fn(|k| {
        wall[k] + (f64::from(WALL_TINT[k]) - wall[k]) * f64::from(WALL_MIX)
    });
    let (model, walls) = (green_over_red(RED.map(f64::from)), green_over_red(wall));
    assert!(model < 0.1 && walls > 0.4, "{model} {walls}");
    let low = (walls + 0.3) / 2.0;
    image
        .enumerate_pixels()
        .filter(|&(x, y, p)| {
            let c = [p[0], p[1], p[2]].map(|v| v as f64 / 255.0);
            DVec2::new(x as f64, y as f64).distance(centre) < radius
                && linear(c[0]) > 0.02
                && (low..0.7).contains(&green_over_red(c))
        })
        .count()
}

/// A red sphere of radius 10 cut in Scalpel mode with a 1.5 deep groove opened 1.2 wide: the
/// first stroke (horizontal) shows walls once released; the second (lower, with the same
/// opening, so the window draws it as a patch over the uploaded mesh) shows more walls while
/// its button is still held, and the walls stay when it is released.
#[test]
fn an_opened_incision_shows_its_walls_while_drawn_and_after() {
    if let Some(why) = no_adapter() {
        return skip(Resource::Gpu, why);
    }
    let dir = std::env::temp_dir().join(format!("cutaway-window-scalpel-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let sphere = dir.join("sphere.obj");
    cutaway::io::write_mesh(&sphere, &csg::testkit::icosphere(5, 10.0)).unwrap();
    let mut h = harness(&dir.join("state"), vec![sphere]);
    h.run_steps(3);
    assert_eq!(
        h.state().scene.models.len(),
        1,
        "{}",
        h.state().status.message
    );
    h.state_mut().scene.models[0].color = RED;
    h.state_mut().selected_model = None;
    apply(&mut h, Action::SetMode(Mode::Scalpel));
    h.run_steps(3);
    {
        let settings = &mut h.state_mut().viewport.scalpel.settings;
        settings.depth = 1.5;
        settings.opening = 1.2;
        settings.window = 0.05;
    }
    h.run_steps(1);

    // Aim through the camera at points of the sphere's front.
    let app = h.state();
    let rect = app.viewport.scalpel.rect;
    let ppp = h.ctx.pixels_per_point() as f64;
    let camera = app.scene.camera;
    let size = app.viewport.size_px;
    // The sphere's disc in the screenshot, less its rim.
    let origin = DVec2::new(rect.min.x as f64, rect.min.y as f64) * ppp;
    let centre: DVec2 = camera.project(size, glam::DVec3::ZERO).expect("in front") + origin;
    let rim = camera
        .project(size, camera.up.normalize() * 10.0)
        .expect("in front")
        + origin;
    let disc = 0.9 * centre.distance(rim);
    let walls_in = |image: &image::RgbaImage| wall_pixels(image, centre, disc);
    let uncut = shot(&mut h, "scalpel-walls-uncut");
    assert_eq!(walls_in(&uncut), 0, "walls before any cut");
    let toward_eye = (camera.eye - camera.target).normalize();
    let right = camera.forward().cross(camera.up).normalize();
    let up = right.cross(camera.forward());
    let at = |dx: f64, dy: f64| {
        let p = (toward_eye * (1.0 - dx * dx - dy * dy).sqrt() + right * dx + up * dy) * 10.0;
        let px: DVec2 = camera.project(size, p).expect("in front");
        rect.min + egui::vec2((px.x / ppp) as f32, (px.y / ppp) as f32)
    };
    let stroke = |h: &mut Harness<'_, CutawayApp>, dy: f64, release: bool| {
        h.hover_at(at(-0.5, dy));
        h.step();
        h.drag_at(at(-0.5, dy));
        h.step();
        for k in 1..=20 {
            h.hover_at(at(-0.5 + k as f64 / 20.0, dy));
            h.step();
        }
        // Hold still a few frames: the opening's time window runs out behind the blade.
        h.run_steps(6);
        if release {
            h.drop_at(at(0.5, dy));
            h.run_steps(3);
        }
    };
    stroke(&mut h, 0.25, true);
    let state = h.state();
    assert!(!state.status.is_error, "{}", state.status.message);
    assert!(
        !state.scene.models[0].wall_faces().is_empty(),
        "no wall faces"
    );
    let first = shot(&mut h, "scalpel-walls-first");
    let after_first = walls_in(&first);
    assert!(
        after_first > 300,
        "{after_first} wall pixels after the first stroke"
    );

    stroke(&mut h, -0.25, false);
    assert!(
        h.state().viewport.scalpel.delta().is_some(),
        "the second stroke is drawn as a patch"
    );
    let during = shot(&mut h, "scalpel-walls-during");
    let while_drawn = walls_in(&during);
    assert!(
        while_drawn > after_first + 300,
        "{while_drawn} wall pixels while the second stroke is drawn ({after_first} before it)"
    );
    h.drop_at(at(0.5, -0.25));
    h.run_steps(3);
    assert!(h.state().viewport.scalpel.delta().is_none());
    let released = shot(&mut h, "scalpel-walls-released");
    let after = walls_in(&released);
    assert!(
        after * 10 >= while_drawn * 9,
        "{after} wall pixels after the release, {while_drawn} while drawn"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
