//! Cut variants compared: each variant measured ([`crate::metrics::variants`]) and drawn from the same
//! camera, one sheet with the pictures side by side and the metrics table under them
//! ([`sheet`]), and the measures as JSON and CSV ([`crate::metrics::table`]). `cutaway compare` writes all of it
//! as one output set; the window's compare view shows the same measures under its viewports.
//! Egui-free.

pub mod sheet;

use std::sync::Arc;

use crate::cutting::cut_scene::preview_geometry;
use crate::render::HeadlessRenderer;
use crate::scene::Scene;
use crate::view::RenderPngOptions;

/// Renders every variant of `scene` from the scene camera at `width` × `height` (cuts executed,
/// as `cutaway render` draws them). A cut the boolean refuses is an error naming the variant.
pub fn render_variants(
    renderer: &mut HeadlessRenderer,
    scene: &Scene,
    width: u32,
    height: u32,
) -> anyhow::Result<Vec<image::RgbaImage>> {
    let names = crate::scene::variants::names(scene);
    let mut images = Vec::with_capacity(names.len());
    for (k, name) in names.iter().enumerate() {
        let shown = crate::scene::variants::variant_scene(scene, k).expect("k < variant count");
        let options = RenderPngOptions::new(width, height);
        let preview = Arc::new(preview_geometry(&shown));
        if let Some(note) = preview.notes.first() {
            anyhow::bail!("variant '{name}': {note}");
        }
        let image = crate::annotate::risk_legend::render_with_legend(
            renderer,
            &shown,
            &options,
            Some(preview),
        )
        .map_err(|e| anyhow::anyhow!("variant '{name}': {e}"))?;
        images.push(image);
    }
    Ok(images)
}
