//! A scene rendered headless, as `cutaway render` and every export draw it: the frame made from
//! the scene ([`super::frame`]), its cut computed here when the mode shows one (the renderer
//! runs no boolean), then drawn by a [`HeadlessRenderer`].

use std::sync::Arc;

use super::frame::frame_of;
use crate::cutting::cut_scene::{PreviewGeometry, preview_geometry};
use crate::render::{HeadlessRenderer, ViewMode};
use crate::scene::Scene;

/// Options of [`render_png`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderPngOptions {
    /// Image size in pixels, each 1..=16384.
    pub width: u32,
    pub height: u32,
    /// Clear to a fully transparent background instead of the scene's background colour.
    /// Default: false.
    pub transparent_background: bool,
    /// No supersampling whatever the scene says (golden images). Default: false.
    pub deterministic: bool,
    /// Default: Preview (cuts executed) when the scene has cutters, else Camera.
    pub mode: Option<ViewMode>,
}

impl RenderPngOptions {
    pub fn new(width: u32, height: u32) -> RenderPngOptions {
        RenderPngOptions {
            width,
            height,
            transparent_background: false,
            deterministic: false,
            mode: None,
        }
    }
}

/// Renders `scene` as `cutaway render` does: Preview (cuts executed) when it has cutters, from
/// the scene camera, at the requested size.
pub fn render_png(scene: &Scene, options: &RenderPngOptions) -> anyhow::Result<image::RgbaImage> {
    let mut renderer = HeadlessRenderer::new()?;
    render_with(&mut renderer, scene, options)
}

/// [`render_png`] with an existing headless renderer (tests render several images with one).
pub fn render_with(
    renderer: &mut HeadlessRenderer,
    scene: &Scene,
    options: &RenderPngOptions,
) -> anyhow::Result<image::RgbaImage> {
    render_with_preview(renderer, scene, options, None)
}

/// The mode [`render_png`] draws `scene` in with `options`.
pub fn render_mode(scene: &Scene, options: &RenderPngOptions) -> ViewMode {
    options.mode.unwrap_or(if scene.cutters.is_empty() {
        ViewMode::Camera
    } else {
        ViewMode::Preview
    })
}

/// [`render_with`] with the cut parts already computed (`None`: computed here when the mode
/// needs them), so a caller can report on the cuts it shows. In Edit mode, given parts are drawn
/// under the cutter overlays (the GUI's live cut). With the scene's risk map on, the walls are
/// coloured by distance ([`crate::cutting::wall_risk`], computed once per preview).
pub fn render_with_preview(
    renderer: &mut HeadlessRenderer,
    scene: &Scene,
    options: &RenderPngOptions,
    preview: Option<Arc<PreviewGeometry>>,
) -> anyhow::Result<image::RgbaImage> {
    let mode = render_mode(scene, options);
    let mut frame = frame_of(scene, [options.width, options.height], mode);
    if options.transparent_background {
        frame.look.background[3] = 0.0;
    }
    frame.deterministic = options.deterministic;
    let shown = if mode == ViewMode::Preview {
        // The cut is computed here, not by the renderer.
        Some(preview.unwrap_or_else(|| Arc::new(preview_geometry(scene))))
    } else if mode == ViewMode::Edit {
        // Edit mode with the cut parts drawn under the cutters, as the GUI's live cut does.
        preview
    } else {
        None
    };
    let (risk_maps, drawn_risk) = renderer.risk_maps();
    frame.risk = shown.as_ref().and_then(|cut| risk_maps.map(scene, cut));
    *drawn_risk = frame.risk.clone();
    frame.show_cut(shown);
    if mode == ViewMode::Edit {
        frame.overlays = scene
            .cutters
            .iter()
            .map(crate::cutting::overlay::cutter_overlay)
            .collect();
    }
    renderer.render(&frame)
}
