//! Input and looking helpers shared by the window tests that drive the default scene and real
//! anatomy (`window.rs`, `navigation.rs`, `scale.rs`): a private folder, settling
//! background jobs, switching modes, mouse drags and wheel turns, the 3D view's pixel rectangle,
//! colour counts, and where the real anatomy is. A test file that does not use every helper
//! includes this module with `#[allow(dead_code)]`.

use csg::testkit::{Resource, skip};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cutaway::gui::app::Action;
use cutaway::gui::{CutawayApp, Mode};
use egui_kittest::Harness;

use crate::harness::apply;

/// A fresh private folder for one test.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cutaway-window-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Steps the window until its background jobs are done, then three frames more.
pub fn settle(h: &mut Harness<'_, CutawayApp>) {
    let deadline = Instant::now() + Duration::from_secs(300);
    while h.state().busy() {
        assert!(Instant::now() < deadline, "background jobs did not finish");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(3);
}

/// Switches to `mode` as the mode buttons do.
pub fn click_mode(h: &mut Harness<'_, CutawayApp>, mode: Mode) {
    apply(h, Action::SetMode(mode));
}

/// Pixels in `rect` close to the colour `rgb` (within 40 per channel).
pub fn count_colour(image: &image::RgbaImage, rect: egui::Rect, rgb: [u8; 3]) -> usize {
    let mut n = 0;
    for y in rect.min.y as u32..rect.max.y as u32 {
        for x in rect.min.x as u32..rect.max.x as u32 {
            let p = image.get_pixel(x, y);
            if (0..3).all(|k| (p[k] as i32 - rgb[k] as i32).abs() < 40) {
                n += 1;
            }
        }
    }
    n
}

/// The pixel rectangle of the 3D view.
pub fn view_px(h: &Harness<'_, CutawayApp>) -> egui::Rect {
    let ppp = h.ctx.pixels_per_point();
    let r = h.state().viewport.rect;
    egui::Rect::from_min_max(
        (r.min.to_vec2() * ppp).to_pos2(),
        (r.max.to_vec2() * ppp).to_pos2(),
    )
}

/// Press, drag through five steps and release from `a` to `b` (points).
pub fn drag(h: &mut Harness<'_, CutawayApp>, a: egui::Pos2, b: egui::Pos2) {
    drag_steps(h, a, b, 5);
}

/// Press at `a`, move to `b` in `steps` frames, release (points).
pub fn drag_steps(h: &mut Harness<'_, CutawayApp>, a: egui::Pos2, b: egui::Pos2, steps: usize) {
    h.hover_at(a);
    h.step();
    h.drag_at(a);
    h.step();
    for k in 1..=steps {
        h.hover_at(a + (b - a) * (k as f32 / steps as f32));
        h.step();
    }
    h.drop_at(b);
    h.run_steps(2);
}

/// Hovers `at` and turns the wheel by `lines` (positive zooms in), then two frames.
pub fn wheel_at(h: &mut Harness<'_, CutawayApp>, at: egui::Pos2, lines: f32) {
    h.hover_at(at);
    h.step();
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Line,
        delta: egui::vec2(0.0, lines),
        modifiers: Default::default(),
        phase: egui::TouchPhase::Move,
        source: egui::MouseWheelSource::Wheel,
    });
    h.run_steps(2);
}

/// `CUTAWAY_ANATOMY/<folder>` (default `../shared/anatomy`) or `None` with the reason printed.
pub fn anatomy(folder: &str) -> Option<PathBuf> {
    let root = std::env::var_os("CUTAWAY_ANATOMY")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/anatomy"));
    let path = root.join(folder);
    if !path.is_dir() {
        skip(
            Resource::Data,
            format!("{} not found (set CUTAWAY_ANATOMY)", path.display()),
        );
        return None;
    }
    Some(path)
}
