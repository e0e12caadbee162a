//! End-to-end tests of the window: the real `CutawayApp` driven headless by egui_kittest with its
//! wgpu renderer (the 3D view's paint callback runs too), no display needed.
//!
//! Skipped, with the reason printed, when no wgpu adapter exists (install `mesa-vulkan-drivers`
//! and set `WGPU_BACKEND=vulkan`; CI does). This file holds the scaffolding every test uses; the
//! tests are in `gui/`, one file per concern.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cutaway::gui::{CutawayApp, Mode, StartOptions};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use crate::harness::no_adapter;
use crate::image_compare;
use crate::input::{settle, temp_dir};

fn harness(
    state_dir: &Path,
    paths: Vec<PathBuf>,
    offer_recovery: bool,
) -> Harness<'static, CutawayApp> {
    let start = StartOptions {
        paths,
        state_dir: state_dir.to_path_buf(),
        offer_recovery,
    };
    Harness::builder()
        .wgpu()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_max_steps(10_000)
        // The slider value boxes of egui 0.37 carry no accessible name of their own.
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start))
}

/// Clicks the mode button `label` (the toggle button, not a menu of the same name).
fn click_mode(h: &mut Harness<'_, CutawayApp>, label: &str) {
    h.query_all_by_label(label)
        .find(|n| n.accesskit_node().toggled().is_some())
        .unwrap_or_else(|| panic!("no mode button {label}"))
        .click();
    h.run_steps(2);
}

/// Clicks the menu item whose label starts with `text` (a shortcut may follow) and does not
/// contain `not`.
fn click_menu_item(h: &mut Harness<'_, CutawayApp>, text: &str, not: &str) {
    h.query_all_by_label_contains(text)
        .find(|n| {
            let label = n
                .accesskit_node()
                .label()
                .map(|l| l.to_string())
                .unwrap_or_default();
            label.starts_with(text) && !label.contains(not)
        })
        .unwrap_or_else(|| panic!("no menu item {text}"))
        .click();
    h.run_steps(2);
}

mod big_load;
mod export_image;
mod expose;
mod live_cut;
mod models_list;
/// Steps until `done()` or the deadline; returns the frames stepped.
fn step_until(
    h: &mut Harness<'_, CutawayApp>,
    what: &str,
    mut done: impl FnMut(&Harness<'_, CutawayApp>) -> bool,
) -> usize {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut frames = 0;
    while !done(h) {
        assert!(Instant::now() < deadline, "{what}: not within 120 s");
        h.step();
        frames += 1;
        std::thread::sleep(Duration::from_millis(5));
    }
    frames
}

mod window_basics;
