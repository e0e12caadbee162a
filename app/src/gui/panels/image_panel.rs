//! The Image section of the side panel: what the walls show (structure colour, image, blend),
//! where (walls, slices and ribbons), the window/level with its presets, and removing the image.
//! The image itself is read on a worker (`Action::OpenImage`); [`image_loaded`] puts it in the
//! scene.

use crate::io::intensity::WindowPreset;
use crate::scene::{ImageLayer, WallDisplay};

use crate::gui::state::AppState;

/// A freshly read image joins the scene, unless it lies outside the models.
pub fn image_loaded(app: &mut AppState, layer: ImageLayer) {
    if let Err(e) = crate::io::intensity::check_overlap(&layer.image, app.scene.bbox()) {
        app.complain(&e.context(layer.image.source.display().to_string()));
        return;
    }
    let (lo, hi) = layer.image.range();
    let alone = if app.scene.models.is_empty() {
        "; no segmentation yet: open it with Open… in the File menu to cut it and see the image on the walls"
    } else {
        ""
    };
    // The renderer shows an image over the GPU's 3-D texture limit at reduced resolution: say so.
    let reduced = app
        .wgpu
        .as_ref()
        .map(|rs| rs.device.limits().max_texture_dimension_3d as usize)
        .and_then(|limit| crate::io::intensity::fit::notice(&layer.image, limit))
        .map(|notice| format!("; {notice}"))
        .unwrap_or_default();
    app.say(format!(
        "Image {}: {} × {} × {} {} voxels, values {lo} to {hi}{reduced}{alone}",
        layer.image.source.display(),
        layer.image.dims[0],
        layer.image.dims[1],
        layer.image.dims[2],
        layer.image.kind().name()
    ));
    app.scene.image = Some(layer);
}

/// The image to keep when files replace the scene: the scene's image when the scene has no
/// models (an image opened alone waits for its segmentation), else none.
pub fn image_kept(app: &AppState, replace: bool) -> Option<ImageLayer> {
    (replace && app.scene.models.is_empty())
        .then(|| app.scene.image.clone())
        .flatten()
}

fn preset_label(preset: WindowPreset) -> &'static str {
    match preset {
        WindowPreset::SoftTissue => "Soft tissue",
        WindowPreset::Lung => "Lung",
        WindowPreset::Bone => "Bone",
        WindowPreset::Brain => "Brain",
        WindowPreset::Auto => "Auto",
    }
}

/// The Image section (nothing without an image).
pub fn image_panel_ui(ui: &mut egui::Ui, app: &mut AppState) {
    let Some(layer) = app.scene.image.as_mut() else {
        return;
    };
    let mut remove = false;
    egui::CollapsingHeader::new(crate::gui::panels::tools_panel::title("Image"))
        .id_salt("tools-image")
        .default_open(true)
        .show(ui, |ui| {
            let name = layer
                .image
                .source
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            ui.label(name);
            ui.horizontal(|ui| {
                for display in WallDisplay::ALL {
                    let label = match display {
                        WallDisplay::Color => "Colour",
                        WallDisplay::Image => "Image",
                        WallDisplay::Blend => "Blend",
                    };
                    ui.selectable_value(&mut layer.display, display, label);
                }
            });
            ui.horizontal(|ui| {
                ui.checkbox(&mut layer.on_walls, "Walls");
                ui.checkbox(&mut layer.on_slices, "Slices and ribbons");
            });
            ui.horizontal_wrapped(|ui| {
                for preset in WindowPreset::ALL {
                    if ui.button(preset_label(preset)).clicked() {
                        layer.window = preset.window(&layer.image);
                    }
                }
            });
            let (lo, hi) = layer.image.range();
            let speed = ((hi - lo) / 500.0).max(0.01);
            ui.horizontal(|ui| {
                ui.label("Level");
                ui.add(egui::DragValue::new(&mut layer.window.level).speed(speed));
                ui.label("Width");
                ui.add(
                    egui::DragValue::new(&mut layer.window.width)
                        .speed(speed)
                        .range(crate::io::intensity::Window::MIN_WIDTH..=f64::MAX),
                );
            });
            ui.weak("Shift + right drag on a wall: sideways width, up and down level");
            remove = ui.button("Remove Image").clicked();
            ui.add_space(6.0);
        });
    ui.separator();
    if remove {
        app.scene.image = None;
    }
}

/// Shift + secondary-button drag that starts on a wall showing the image adjusts the window like
/// a radiology viewer: right widens, down raises the level; one undo step per drag. A drag that
/// starts elsewhere keeps its navigation meaning. Returns true when it took the drag.
pub fn window_drag(app: &mut AppState, response: &egui::Response, ui: &egui::Ui) -> bool {
    let id = egui::Id::unique("cutaway image window drag");
    let shift = ui.input(|i| i.modifiers.shift);
    if response.drag_started_by(egui::PointerButton::Secondary) {
        let on_wall = shift
            && response.interact_pointer_pos().is_some_and(|pos| {
                let ppp = ui.ctx().pixels_per_point() as f64;
                let rect = response.rect;
                let px = glam::DVec2::new(
                    (pos.x - rect.left()) as f64 * ppp,
                    (pos.y - rect.top()) as f64 * ppp,
                );
                let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
                crate::cutting::wall_pick::image_wall_under(
                    &app.scene,
                    app.viewport.preview.as_deref(),
                    &ray,
                )
            });
        ui.ctx().data_mut(|d| d.insert_temp(id, on_wall));
        if on_wall {
            app.begin_edit("window/level");
        }
    }
    let taken = ui.ctx().data(|d| d.get_temp::<bool>(id)).unwrap_or(false);
    if !taken {
        return false;
    }
    if !response.dragged_by(egui::PointerButton::Secondary) {
        ui.ctx().data_mut(|d| d.insert_temp(id, false));
        return response.drag_stopped();
    }
    let Some(layer) = app.scene.image.as_mut() else {
        return false;
    };
    let delta = response.drag_delta();
    let (lo, hi) = layer.image.range();
    let scale = ((hi - lo) / 1000.0).max(1e-3);
    layer.window = layer.window.dragged(delta.x as f64, delta.y as f64, scale);
    true
}

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable as _;
    use glam::DVec3;

    use crate::gui::app::Action;
    use crate::gui::{CutawayApp, StartOptions};

    /// An int16 NRRD ramp along x over [-1, 3]³ (RAS), `shift` mm along x.
    fn write_image(path: &std::path::Path, shift: f64) {
        let n = 5;
        let mut bytes = format!(
            "NRRD0004\ntype: short\ndimension: 3\nspace: RAS\nsizes: {n} {n} {n}\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: raw\nspace origin: ({},-1,-1)\n\n",
            shift - 1.0
        )
        .into_bytes();
        for _k in 0..n {
            for _j in 0..n {
                for i in 0..n {
                    bytes.extend_from_slice(&(i as i16 * 500 - 1000).to_le_bytes());
                }
            }
        }
        std::fs::write(path, bytes).unwrap();
    }

    /// A CT opened as structures (File → Open, a dropped file, `cutaway open CT.nrrd`) becomes
    /// the image of a scene without models; the segmentation opened next keeps it.
    #[test]
    fn a_ct_opened_alone_is_the_image_and_waits_for_its_segmentation() {
        let dir = std::env::temp_dir().join(format!("cutaway-image-alone-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let cube = dir.join("cube.ply");
        crate::io::write_mesh(
            &cube,
            &crate::gui::app::box_mesh(DVec3::ZERO, DVec3::splat(2.0)),
        )
        .unwrap();
        let ct = dir.join("ct.nrrd");
        write_image(&ct, 0.0);
        let start = StartOptions {
            paths: vec![ct.clone()],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = crate::gui::test_window::open(start, 1024.0, 900.0);
        let message = h.state().status.message.clone();
        assert!(h.state().scene.models.is_empty(), "{message}");
        let layer = h.state().scene.image.clone().expect("the CT is the image");
        assert_eq!(layer.image.kind(), crate::io::intensity::SampleKind::I16);
        assert!(message.contains("no segmentation yet"), "{message}");

        // The segmentation, opened next, replaces the empty scene and keeps the image.
        let ctx = h.ctx.clone();
        h.state_mut().apply(&ctx, Action::Open(vec![cube.clone()]));
        crate::gui::test_window::settle(&mut h);
        assert_eq!(h.state().scene.models.len(), 1);
        let kept = h.state().scene.image.clone().expect("the image stays");
        assert!(std::sync::Arc::ptr_eq(&kept.image, &layer.image));

        // Opening another segmentation over models drops the image with the old scene; both
        // together in one open give both.
        h.state_mut().apply(&ctx, Action::Open(vec![cube.clone()]));
        crate::gui::test_window::settle(&mut h);
        assert!(h.state().scene.image.is_none());
        h.state_mut()
            .apply(&ctx, Action::Open(vec![ct.clone(), cube]));
        crate::gui::test_window::settle(&mut h);
        assert_eq!(h.state().scene.models.len(), 1);
        assert!(h.state().scene.image.is_some());
        // Two images in one open are refused with both names.
        let ct2 = dir.join("ct2.nrrd");
        write_image(&ct2, 0.0);
        h.state_mut().apply(&ctx, Action::Open(vec![ct, ct2]));
        crate::gui::test_window::settle(&mut h);
        let message = h.state().status.message.clone();
        assert!(message.contains("a second intensity image"), "{message}");
    }

    /// Shift + right drag from a point: press, four moves, release, with Shift held throughout.
    fn shift_right_drag(h: &mut Harness<'_, CutawayApp>, from: egui::Pos2) {
        let shift = egui::Modifiers::SHIFT;
        h.event(egui::Event::ModifiersChanged(shift));
        h.hover_at(from);
        h.step();
        let to = from + egui::vec2(80.0, 40.0);
        for (pressed, at) in [(true, from), (false, to)] {
            if !pressed {
                for k in 1..=4 {
                    h.hover_at(from + (to - from) * (k as f32 / 4.0));
                    h.step();
                }
            }
            h.event(egui::Event::PointerButton {
                pos: at,
                button: egui::PointerButton::Secondary,
                pressed,
                modifiers: shift,
            });
            h.step();
        }
        h.event(egui::Event::ModifiersChanged(egui::Modifiers::NONE));
        h.run_steps(2);
    }

    /// The window drag works only from a wall that shows the image, is one undo step per drag,
    /// and leaves the camera alone; from off the walls the same drag orbits as always.
    #[test]
    fn window_drag_starts_only_on_an_image_wall_and_is_one_undo_step() {
        let dir = std::env::temp_dir().join(format!("cutaway-window-drag-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let cube = dir.join("cube.ply");
        crate::io::write_mesh(
            &cube,
            &crate::gui::app::box_mesh(DVec3::ZERO, DVec3::splat(2.0)),
        )
        .unwrap();
        let ct = dir.join("ct.nrrd");
        write_image(&ct, 0.0);
        let start = StartOptions {
            paths: vec![cube, ct],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = crate::gui::test_window::open(start, 1024.0, 800.0);
        assert!(
            h.state().scene.image.is_some(),
            "{}",
            h.state().status.message
        );
        // A box cut from the front to y = 1: the wall at y = 1 faces a camera looking along +y.
        {
            let app = h.state_mut();
            app.scene.cutters.push(crate::scene::SceneCutter {
                target: 0,
                cutter: cutter::Cutter {
                    kind: cutter::CutKind::Straight,
                    smooth: false,
                    levels: cutter::subdivision::DEFAULT_LEVELS,
                    direction: cutter::CutDirection::Normal,
                    planes: crate::test_support::box_cutter(0.4, 1.6, -1.0, 1.0, 0.4, 1.6),
                },
                views: Default::default(),
            });
            app.scene.camera = cutter::Camera {
                eye: DVec3::new(1.0, -12.0, 1.0),
                target: DVec3::new(1.0, 1.0, 1.0),
                up: DVec3::Z,
                fov_y_deg: 20.0,
            };
        }
        crate::gui::test_window::settle(&mut h);
        assert!(h.state().viewport.preview.is_some(), "no cut preview");
        let undo_before = h.state().history.undo_label().map(str::to_owned);
        let window = h.state().scene.image.as_ref().unwrap().window;
        let camera = h.state().scene.camera;
        let center = h.state().viewport.rect.center();

        shift_right_drag(&mut h, center);
        let dragged = h.state().scene.image.as_ref().unwrap().window;
        assert!(dragged.width > window.width, "{window:?} → {dragged:?}");
        assert!(dragged.level != window.level, "{window:?} → {dragged:?}");
        assert_eq!(h.state().scene.camera.eye, camera.eye, "the drag orbited");
        assert_eq!(h.state().history.undo_label(), Some("window/level"));
        let ctx = h.ctx.clone();
        h.state_mut().apply(&ctx, Action::Undo);
        h.run_steps(2);
        assert_eq!(h.state().scene.image.as_ref().unwrap().window, window);
        assert_eq!(
            h.state().history.undo_label().map(str::to_owned),
            undo_before,
            "one drag, one undo step"
        );

        // Off the model (a corner of the view) the same drag orbits and leaves the window.
        let corner = h.state().viewport.rect.left_top() + egui::vec2(30.0, 30.0);
        shift_right_drag(&mut h, corner);
        assert_eq!(h.state().scene.image.as_ref().unwrap().window, window);
        assert!(
            (h.state().scene.camera.eye - camera.eye).length() > 0.1,
            "no orbit"
        );
    }

    #[test]
    fn open_image_presets_and_the_session_keep_the_window() {
        let dir = std::env::temp_dir().join(format!("cutaway-image-panel-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let cube = dir.join("cube.ply");
        crate::io::write_mesh(
            &cube,
            &crate::gui::app::box_mesh(DVec3::ZERO, DVec3::splat(2.0)),
        )
        .unwrap();
        let (near, far) = (dir.join("ct.nrrd"), dir.join("far.nrrd"));
        write_image(&near, 0.0);
        write_image(&far, 500.0);
        let start = StartOptions {
            paths: vec![cube],
            state_dir: dir.join("state"),
            offer_recovery: false,
        };
        let mut h = crate::gui::test_window::open(start, 1024.0, 900.0);
        let ctx = h.ctx.clone();
        // An image beside the models, not on them, is refused with the reason.
        h.state_mut().apply(&ctx, Action::OpenImage(far));
        crate::gui::test_window::settle(&mut h);
        assert!(h.state().scene.image.is_none());
        assert!(
            h.state().status.message.contains("disjoint"),
            "{}",
            h.state().status.message
        );

        h.state_mut().apply(&ctx, Action::OpenImage(near.clone()));
        crate::gui::test_window::settle(&mut h);
        let layer = h
            .state()
            .scene
            .image
            .clone()
            .expect("the image is in the scene");
        // Values -1000..=1000, air included: a CT, so soft tissue first.
        assert_eq!(layer.window.level, 40.0);
        h.get_by_label("Lung").click();
        h.run_steps(2);
        assert_eq!(h.state().scene.image.as_ref().unwrap().window.level, -600.0);
        h.get_by_label("Blend").click();
        h.run_steps(2);
        let layer = h.state().scene.image.clone().unwrap();
        assert_eq!(layer.display, crate::scene::WallDisplay::Blend);

        let session = dir.join("s.json");
        h.state_mut()
            .apply(&ctx, Action::SaveSessionTo(session.clone()));
        let back = crate::session::load(&session).unwrap();
        let image = back.image.expect("the session keeps the image");
        assert_eq!(image.window, layer.window);
        assert_eq!(image.display, layer.display);
        assert_eq!(
            std::fs::canonicalize(&image.image.source).unwrap(),
            std::fs::canonicalize(&near).unwrap()
        );
        let text = std::fs::read_to_string(&session).unwrap();
        assert!(
            text.contains("\"path\": \"ct.nrrd\""),
            "relative path: {text}"
        );

        h.get_by_label("Remove Image").click();
        h.run_steps(2);
        assert!(h.state().scene.image.is_none());
    }
}
