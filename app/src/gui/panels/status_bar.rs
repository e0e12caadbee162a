//! The status line under the viewport: scene size, what is selected, the last cut time, and the
//! last message (errors stay until the next message so they can be read).

/// What the status line shows; filled by the app each frame.
#[derive(Clone, Debug, Default)]
pub struct StatusInfo {
    /// Number of models (regions) in the scene.
    pub models: usize,
    /// Triangles of all models.
    pub triangles: usize,
    /// Triangles of the visible models.
    pub visible_triangles: usize,
    /// Number of cutters.
    pub cutters: usize,
    /// Triangles of the cut results shown in Preview (kept + walls), 0 when none.
    pub cut_triangles: usize,
    /// Wall time of the last boolean cut, in milliseconds.
    pub last_cut_ms: Option<f64>,
    /// Name of the selected (target) model.
    pub selected: Option<String>,
    /// Last message; `is_error` colours it.
    pub message: String,
    pub is_error: bool,
    /// Why a cut could not be made, or what the editor refused or corrected (shown in the
    /// error colour while it lasts).
    pub cut_problem: Option<String>,
    /// Milliseconds of the last frame (UI + 3D), shown for performance checks.
    pub frame_ms: f32,
}

/// Thousands separators for counts ("1 234 567").
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

pub fn status_bar_ui(ui: &mut egui::Ui, info: &StatusInfo) {
    ui.horizontal(|ui| {
        ui.label(format!("{} models", info.models));
        ui.separator();
        if info.visible_triangles == info.triangles {
            ui.label(format!("{} triangles", grouped(info.triangles)));
        } else {
            ui.label(format!(
                "{} of {} triangles shown",
                grouped(info.visible_triangles),
                grouped(info.triangles)
            ));
        }
        ui.separator();
        ui.label(format!("{} cutters", info.cutters));
        if info.cut_triangles > 0 {
            ui.separator();
            ui.label(format!("cut: {} triangles", grouped(info.cut_triangles)));
        }
        ui.separator();
        match info.last_cut_ms {
            Some(ms) => ui.label(format!("last cut {ms:.1} ms")),
            None => ui.label(egui::RichText::new("no cut yet").weak()),
        };
        if let Some(name) = &info.selected {
            ui.separator();
            ui.label(format!("target: {name}"));
        }
        if let Some(problem) = &info.cut_problem {
            ui.separator();
            ui.label(egui::RichText::new(problem).color(ui.visuals().error_fg_color));
        }
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.label(
                egui::RichText::new(format!("{:.0} ms/frame", info.frame_ms))
                    .weak()
                    .small(),
            );
            ui.separator();
            // A long message is cut to the room left (full text on hover) rather than drawn
            // over the counts on the left.
            let mut text = egui::RichText::new(&info.message);
            if info.is_error {
                text = text.color(ui.visuals().error_fg_color);
            }
            ui.add(egui::Label::new(text).truncate());
        });
    });
}

#[cfg(test)]
mod tests {
    use super::grouped;

    #[test]
    fn counts_are_grouped_by_thousands() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(2_000_000), "2,000,000");
    }
}
