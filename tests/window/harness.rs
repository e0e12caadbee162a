//! The window opened headless for the window tests (`window.rs`, `tools.rs` and the others of this binary): egui_kittest
//! on the real wgpu renderer at 1280×800 with real frame times (two clicks a frame apart are a
//! double-click), screenshots saved for a person to look at, and the skip reason when no adapter
//! exists.

use std::path::{Path, PathBuf};

use cutaway::gui::app::Action;
use cutaway::gui::{CutawayApp, StartOptions};
use egui_kittest::Harness;

/// Why the window tests cannot run here, or `None` when a wgpu adapter exists.
pub fn no_adapter() -> Option<String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    match pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())) {
        Ok(_) => None,
        Err(e) => Some(format!(
            "no wgpu adapter ({e}); install mesa-vulkan-drivers and set WGPU_BACKEND=vulkan"
        )),
    }
}

/// The window opening `paths` (none: the default scene), its state kept in `state_dir`, no
/// recovery prompt.
pub fn harness(state_dir: &Path, paths: Vec<PathBuf>) -> Harness<'static, CutawayApp> {
    harness_sized(state_dir, paths, egui::vec2(1280.0, 800.0))
}

/// [`harness`] with a window of `size` points.
pub fn harness_sized(
    state_dir: &Path,
    paths: Vec<PathBuf>,
    size: egui::Vec2,
) -> Harness<'static, CutawayApp> {
    let start = StartOptions {
        paths,
        state_dir: state_dir.to_path_buf(),
        offer_recovery: false,
    };
    Harness::builder()
        .wgpu()
        .with_size(size)
        .with_max_steps(10_000)
        // Real frame times, so two clicks a frame apart are a double-click.
        .with_step_dt(1.0 / 60.0)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start))
}

/// Renders the window, saves it as `name` in the test's temporary folder, returns it.
pub fn shot(h: &mut Harness<'_, CutawayApp>, name: &str) -> image::RgbaImage {
    let image = h.render().expect("render the window");
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("window-{name}.png"));
    image.save(&path).expect("save screenshot");
    println!("screenshot: {}", path.display());
    image
}

/// Applies a menu action as the window would, then draws two frames.
pub fn apply(h: &mut Harness<'_, CutawayApp>, action: Action) {
    let ctx = h.ctx.clone();
    h.state_mut().apply(&ctx, action);
    h.run_steps(2);
}
