//! A picture of the scene with the annotations a user chose: what the window's Export Image
//! writes when its dialog asks for labels, a scale bar or the orientation marker. The drawing is
//! [`super::labelled::annotate_with`], the code `cutaway render --labels` uses, over the
//! headless renderer's picture.

use std::sync::Arc;

use image::RgbaImage;

use super::labelled::{Annotations, Extras, annotate_with};
use super::visible::is_opaque;
use crate::cutting::cut_scene::preview_geometry;
use crate::render::{HeadlessRenderer, ViewMode};
use crate::scene::Scene;
use crate::view::{RenderPngOptions, render_mode};

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
