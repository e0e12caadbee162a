//! A picture of the scene with the annotations a user chose: what the window's Export Image
//! writes when its dialog asks for labels, a scale bar or the orientation marker. The drawing is
//! [`super::labelled::annotate_with`], the code `cutaway render --labels` uses, over the
//! headless renderer's picture.

use std::sync::Arc;

use image::RgbaImage;

use super::labelled::{Annotations, Extras, annotate_with};
use super::visible::is_opaque;
use crate::cutting::cut_scene::{CutReport, preview_geometry};
use crate::render::{HeadlessRenderer, ViewMode};
use crate::scene::Scene;
use crate::view::{RenderPngOptions, render_mode};

/// The picture `cutaway render` writes (and the Python `Session.render` returns): the scene in
/// Preview when it has cutters, the risk legend, the rulers and the labels of `labelled` drawn
/// over it, with one report per cutter of the scene.
#[derive(Debug)]
pub struct SessionPicture {
    pub image: RgbaImage,
    /// One per cutter of the scene, in order; a cutter with no view shown is not cut (exact, 0 ms).
    pub reports: Vec<CutReport>,
    /// Wall time from the loaded scene to the finished image (cuts and drawing).
    pub render_ms: f64,
    /// Why a cut was refused (the first refusal): the picture must not be written then.
    pub refused: Option<String>,
}

/// Renders `scene` as `cutaway render` does, with `renderer` (one renderer for many pictures).
pub fn render_session_picture(
    renderer: &mut HeadlessRenderer,
    scene: &Scene,
    options: &RenderPngOptions,
    labelled: Option<&[usize]>,
) -> anyhow::Result<SessionPicture> {
    let started = std::time::Instant::now();
    let preview = (render_mode(scene, options) == ViewMode::Preview)
        .then(|| Arc::new(preview_geometry(scene)));
    let mut image =
        super::risk_legend::render_with_legend(renderer, scene, options, preview.clone())?;
    super::rulers::draw_rulers(&mut image, scene);
    if let Some(models) = labelled {
        super::labelled::annotate(&mut image, scene, preview.as_deref(), models);
    }
    let render_ms = started.elapsed().as_secs_f64() * 1000.0;
    let not_cut = CutReport {
        exact: true,
        cut_ms: 0.0,
    };
    let reports = (0..scene.cutters.len())
        .map(|c| {
            preview
                .as_ref()
                .and_then(|p| p.reports.iter().find(|(i, _)| *i == c))
                .map_or(not_cut, |(_, r)| *r)
        })
        .collect();
    Ok(SessionPicture {
        image,
        reports,
        render_ms,
        refused: preview.as_ref().and_then(|p| p.notes.first().cloned()),
    })
}

/// What to draw over an exported picture.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AnnotationChoice {
    /// Label structures by name with leader lines.
    pub labels: bool,
    /// Structures the user switched off (every other opaque, visible structure is labelled).
    pub unlabelled: Vec<String>,
    pub extras: Extras,
}

impl AnnotationChoice {
    /// Whether anything is drawn over the picture.
    pub fn any(&self) -> bool {
        self.labels || self.extras.scale_bar || self.extras.marker
    }

    /// The structures to label in `scene` (model indices).
    pub fn models(&self, scene: &Scene) -> Vec<usize> {
        if !self.labels {
            return Vec::new();
        }
        (0..scene.models.len())
            .filter(|&m| {
                is_opaque(scene, m) && !self.unlabelled.contains(&scene.models[m].model.name)
            })
            .collect()
    }
}

/// Renders `scene` with `options` and draws its rulers and `choice` over it; returns the picture and what was
/// drawn (`None` when nothing was asked for).
pub fn render_annotated(
    scene: &Scene,
    options: &RenderPngOptions,
    choice: &AnnotationChoice,
) -> anyhow::Result<(RgbaImage, Option<Annotations>)> {
    let mut renderer = HeadlessRenderer::new()?;
    let preview = (render_mode(scene, options) == ViewMode::Preview)
        .then(|| Arc::new(preview_geometry(scene)));
    let mut image =
        super::risk_legend::render_with_legend(&mut renderer, scene, options, preview.clone())?;
    super::rulers::draw_rulers(&mut image, scene);
    if !choice.any() {
        return Ok((image, None));
    }
    let drawn = annotate_with(
        &mut image,
        scene,
        preview.as_deref(),
        &choice.models(scene),
        choice.extras,
    );
    Ok((image, Some(drawn)))
}
