//! The cut scene in every mode: Camera and Scalpel modes show the cuts the cutters make (the kept
//! parts, the walls and the contour), Preview adds the removed-piece views (transparency,
//! ribbons, slices), Edit shows the live cut under the cutters.
//!
//! The cut parts are the Preview computation's ([`crate::cutting::cut_scene::PreviewGeometry`]);
//! the outside-Preview picture is the same geometry without the removed-piece parts, derived once
//! per computed preview and kept while the preview stays the same.

use std::sync::{Arc, Weak};

use crate::cutting::cut_scene::PreviewGeometry;

use crate::gui::action::Mode;
use crate::gui::state::AppState;

/// True in the modes that show the computed cut (the preview job runs in them).
pub fn shows_cut(mode: Mode) -> bool {
    matches!(mode, Mode::Camera | Mode::Preview | Mode::Scalpel)
}

thread_local! {
    /// The last preview [`cut_without_views`] derived from, and what it derived (a copy of every
    /// cut model's kept part and walls).
    static DERIVED: std::cell::RefCell<Option<(Weak<PreviewGeometry>, Arc<PreviewGeometry>)>> =
        const { std::cell::RefCell::new(None) };
}

/// Drops what [`cut_without_views`] derived: the modes that do not draw it call this every
/// frame, so the copy lives only while Camera or Scalpel mode shows it (deriving it again costs
/// a copy of the parts, no cut).
pub fn drop_derived() {
    DERIVED.with(|last| {
        last.borrow_mut().take();
    });
}

/// True while a derived copy is held (the memory test prints it per step).
pub fn holds_derived() -> bool {
    DERIVED.with(|last| last.borrow().is_some())
}

/// What Camera and Scalpel modes draw for the current preview: kept parts, walls and contours.
pub fn cut_without_views(app: &AppState) -> Option<Arc<PreviewGeometry>> {
    let full = app.viewport.preview.as_ref()?;
    if app.scene.cutters.is_empty() {
        return None;
    }
    DERIVED.with(|last| {
        let mut last = last.borrow_mut();
        if let Some((source, derived)) = last.as_ref()
            && source.upgrade().is_some_and(|s| Arc::ptr_eq(&s, full))
        {
            return Some(derived.clone());
        }
        let derived = Arc::new(full.without_views());
        *last = Some((Arc::downgrade(full), derived.clone()));
        Some(derived)
    })
}

/// The selected model's tint: a warm highlight that reads on every anatomy colour.
const HIGHLIGHT: [f32; 3] = [1.0, 0.78, 0.22];
/// How far the selected model's colour moves toward [`HIGHLIGHT`].
const HIGHLIGHT_MIX: f32 = 0.3;

/// Tints the selected model in the frame's models (never in the scene itself, so
/// exports and sessions keep its colour). Not in Edit mode, where the selection is the target
/// being painted and the live cut must look like the committed one.
pub fn highlight_selection(app: &AppState, drawn: &mut [crate::render::ModelDraw]) {
    if app.mode == Mode::Edit {
        return;
    }
    if let Some(model) = app.selected_model.and_then(|i| drawn.get_mut(i)) {
        model.color = highlighted(model.color);
    }
}

/// `color` moved toward the highlight colour.
pub fn highlighted(color: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|k| color[k] + (HIGHLIGHT[k] - color[k]) * HIGHLIGHT_MIX)
}
