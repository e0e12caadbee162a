//! The window in unit tests: a kittest harness around [`CutawayApp`] on the software renderer,
//! and waiting until its background jobs (loads, index builds) are done, so each test starts
//! from a settled window instead of repeating the set-up.

use egui_kittest::Harness;

use super::{CutawayApp, StartOptions};

/// A window of `width` × `height` points opened with `start`, settled.
pub fn open(start: StartOptions, width: f32, height: f32) -> Harness<'static, CutawayApp> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(width, height))
        .with_max_steps(10_000)
        .with_accessibility_check(false)
        .build_eframe(move |cc| CutawayApp::new(cc, start));
    settle(&mut h);
    h
}

/// Steps the window (two frames, then) until no job runs (at most a minute, then the test fails), then two frames
/// more so their results are drawn.
pub fn settle(h: &mut Harness<'_, CutawayApp>) {
    // Two frames first, so a job the first frames start is seen running.
    h.run_steps(2);
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while h.state().busy() {
        assert!(std::time::Instant::now() < deadline, "a job did not finish");
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    h.run_steps(2);
}
