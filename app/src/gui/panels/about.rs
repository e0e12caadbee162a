//! Help → About: what Cutaway is and where the embedded anatomy comes from (the 3D Slicer
//! licence asks that the atlas's origin and licence travel with it).

/// Where the window's open flag lives (egui memory: nothing in the scene or the session).
fn open_id() -> egui::Id {
    egui::Id::unique("about-window-open")
}

/// Opens the About window.
pub fn open(ctx: &egui::Context) {
    ctx.data_mut(|d| d.insert_temp(open_id(), true));
}

/// The About window, when open.
pub fn about_window_ui(ctx: &egui::Context) {
    let mut open = ctx.data(|d| d.get_temp::<bool>(open_id())).unwrap_or(false);
    if !open {
        return;
    }
    egui::Window::new("About Cutaway")
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        .default_width(460.0)
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(ctx.content_rect().center_top() + egui::vec2(0.0, 72.0))
        .show(ctx, |ui| {
            ui.label(format!(
                "Cutaway {}: context-preserving cutaways of segmented anatomy.",
                env!("CARGO_PKG_VERSION")
            ));
            ui.separator();
            ui.label(egui::RichText::new("Default scene").strong());
            ui.label(
                "The head is real anatomy from the SPL-PNL Brain Atlas (Surgical Planning \
                 Laboratory and Psychiatry Neuroimaging Laboratory, Brigham and Women's \
                 Hospital; NIH P41 EB015902, P41 RR013218, R01 MH050740), distributed with \
                 3D Slicer under the 3D Slicer License. The structures are surfaces of the \
                 atlas's label map (hncma-atlas.nrrd), named and coloured by its colour table; \
                 the skin is a surface derived from the same atlas and simplified. Research use \
                 only, not for clinical use.",
            );
            ui.hyperlink_to(
                "3D Slicer License",
                "https://github.com/Slicer/Slicer/blob/main/License.txt",
            );
            ui.hyperlink_to(
                "SPL-PNL Brain Atlas",
                "http://www.spl.harvard.edu/publications/item/view/1265",
            );
            ui.label(
                "Structure colours follow 3D Slicer's GenericAnatomyColors table. The knee, \
                 lumbar and head examples are synthetic phantoms made by Cutaway.",
            );
        });
    ctx.data_mut(|d| d.insert_temp(open_id(), open));
}
