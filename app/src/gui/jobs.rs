//! The progress window of the window's background jobs (the jobs themselves, with progress and
//! cancel, are egui-free in [`crate::platform::jobs`], so the cutting layer and the CLI use them too).

use std::time::Duration;

pub use crate::platform::jobs::*;

/// The progress window of the running jobs: label, bar, current step, Cancel. Returns the indices
/// of jobs whose Cancel button was pressed.
pub fn progress_window_ui<T: Send + 'static>(ctx: &egui::Context, jobs: &[Job<T>]) -> Vec<usize> {
    let mut cancel = Vec::new();
    let shown: Vec<usize> = (0..jobs.len())
        .filter(|&i| jobs[i].wants_progress_window())
        .collect();
    if shown.is_empty() {
        return cancel;
    }
    egui::Window::new("Working…")
        .id(egui::Id::unique("cutaway-progress"))
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
        .show(ctx, |ui| {
            ui.set_min_width(320.0);
            for &i in &shown {
                let job = &jobs[i];
                ui.strong(&job.label);
                let bar = match job.progress.fraction() {
                    Some(f) => egui::ProgressBar::new(f).show_percentage(),
                    None => egui::ProgressBar::new(0.0).animate(true),
                };
                ui.add(bar.desired_width(300.0));
                ui.horizontal(|ui| {
                    let message = job.progress.message();
                    ui.label(
                        egui::RichText::new(format!(
                            "{message}  ({:.1} s)",
                            job.started.elapsed().as_secs_f32()
                        ))
                        .weak(),
                    );
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        if job.progress.is_cancelled() {
                            ui.label("cancelling…");
                        } else if ui.button("Cancel").clicked() {
                            cancel.push(i);
                        }
                    });
                });
                ui.add_space(6.0);
            }
        });
    // Keep the elapsed time and spinner moving.
    ctx.request_repaint_after(Duration::from_millis(100));
    cancel
}

/// The status bar's line for structures arriving in the background: `text`, a bar with the
/// fraction done, and Cancel. True when Cancel was clicked. Keeps the bar moving.
pub fn arrival_line_ui(ui: &mut egui::Ui, text: &str, fraction: f32) -> bool {
    let mut cancel = false;
    ui.horizontal(|ui| {
        ui.label(text);
        ui.add(
            egui::ProgressBar::new(fraction)
                .show_percentage()
                .desired_width(180.0),
        );
        cancel = ui.button("Cancel").clicked();
    });
    ui.ctx().request_repaint_after(Duration::from_millis(100));
    cancel
}
