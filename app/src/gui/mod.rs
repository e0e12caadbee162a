//! # The window
//!
//! The ExtrusionCutter user interface of the thesis (section 3.5) on eframe/egui with a wgpu 3D
//! view: File and Rendering menus, mode buttons (Camera, Edit, Preview, Scalpel), the Models list,
//! the cutter Initialization / Visualization tabs, a key reference above the viewport and a status
//! line below it. One panel per file; every function that draws takes `&mut egui::Ui` and ends in
//! `_ui`.
//!
//! The UI thread only draws and translates input. Loads, index builds, cuts, exports and native
//! file dialogs run on worker threads ([`jobs`]) with a progress window and Cancel for anything
//! longer than half a second, so a 2M-triangle model never freezes the window. While a cutter is
//! painted in Edit mode, [`viewport::live_cut`] has [`crate::cutting::live_cut`] re-cut it on its own worker
//! (latest request wins) and the view shows the result under the translucent cutter. What is
//! cut, picked and edited lives in [`crate::cutting`]; this module maps input to it and draws.

use std::path::PathBuf;

pub mod action;
pub mod app;
pub mod app_jobs;
pub mod apply;
pub mod atlas_arrival;
pub mod bridge;
pub mod dialogs;
pub mod expose_job;
#[cfg(test)]
mod first_press_tests;
pub mod folder_arrival;
#[cfg(test)]
mod folder_arrival_tests;
pub mod job_output;
pub mod jobs;
pub mod panels;
pub mod risk_map;
#[cfg(test)]
mod smoothness_tests;
pub mod state;
#[cfg(test)]
pub mod test_window;
pub mod viewport;
#[cfg(test)]
mod volume_jobs_tests;

pub use app::{CutawayApp, Mode, StartOptions};
pub use state::AppState;

/// Opens the window on `paths` (meshes, directories of meshes, or one session file); no paths
/// opens the embedded default scene. Returns when the window is closed.
pub fn run(paths: &[PathBuf]) -> anyhow::Result<()> {
    run_with_image(paths, None)
}

/// [`run`], with an intensity image shown on the walls once it is read.
pub fn run_with_image(paths: &[PathBuf], image: Option<PathBuf>) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("Cutaway")
            .with_app_id("cutaway")
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([640.0, 400.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: crate::render::device_memory::with_memory_hints(
                egui_wgpu::WgpuSetup::without_display_handle(),
            ),
            ..Default::default()
        },
        ..Default::default()
    };
    let start = StartOptions::new(paths.to_vec());
    eframe::run_native(
        "Cutaway",
        options,
        Box::new(move |cc| {
            let mut app = CutawayApp::new(cc, start);
            if let Some(image) = image {
                app.apply(&cc.egui_ctx, app::Action::OpenImage(image));
            }
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("could not open the window: {e}"))
}
