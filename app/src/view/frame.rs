//! A scene as the renderer draws it: the one place a [`Scene`] becomes a
//! [`FrameInputs`] (its models with their colour, opacity, style and wall faces; the Rendering
//! menu's look; the image), and where a computed cut ([`PreviewGeometry`]) is handed to the
//! renderer as a [`CutDrawing`]. The window's paint callback and every headless render
//! (`cutaway render`, exports, the compare sheet) make their frames here, so they draw the same.

use std::sync::Arc;

use crate::cutting::cut_scene::{PartKind, PreviewGeometry};
use crate::cutting::wall_risk::WallRisk;
use crate::render::{
    CutDrawing, DrawStyle, FrameInputs, ImageDraw, Look, ModelDraw, PartDraw, PartLook, ViewMode,
};
use crate::scene::wall_faces::WallFaces;
use crate::scene::{ModelStyle, Scene, Stereo};

/// A frame of `scene` from its own camera, in `mode`, with no cut, overlays or deltas.
pub fn frame_of(scene: &Scene, size: [u32; 2], mode: ViewMode) -> FrameInputs {
    let mut frame = FrameInputs::new(model_draws(scene), scene.camera, size, mode);
    frame.look = Look {
        background: scene.render.background,
        antialias: scene.render.antialias,
        anaglyph: scene.render.stereo == Stereo::Anaglyph,
    };
    frame.image = scene.image.as_ref().map(|layer| ImageDraw {
        image: layer.image.clone(),
        window: layer.window,
        on_walls: layer.on_walls,
        on_slices: layer.on_slices,
        image_weight: layer.display.image_weight(),
    });
    frame
}

/// The scene's models as the renderer draws them, in scene order.
pub fn model_draws(scene: &Scene) -> Vec<ModelDraw> {
    scene
        .models
        .iter()
        .map(|model| ModelDraw {
            name: model.model.name.clone(),
            mesh: model.model.mesh.clone(),
            walls: WallFaces::shared_for_mesh(&model.walls, &model.model.mesh),
            color: model.color,
            opacity: model.opacity,
            style: match model.style {
                ModelStyle::Solid => DrawStyle::Solid,
                ModelStyle::Wireframe => DrawStyle::Wireframe,
            },
            visible: model.visible,
        })
        .collect()
}

/// How each kind of cut part is drawn.
pub fn part_look(kind: PartKind) -> PartLook {
    match kind {
        PartKind::Kept => PartLook::Kept,
        PartKind::Wall => PartLook::Wall,
        PartKind::Removed => PartLook::Removed,
        PartKind::Ribbon => PartLook::Ribbon,
        PartKind::SliceWall => PartLook::SliceWall,
    }
}

impl CutDrawing for PreviewGeometry {
    fn replaced(&self, model: usize) -> bool {
        self.replaced.get(model).copied().unwrap_or(false)
    }

    fn part_count(&self) -> usize {
        self.parts.len()
    }

    fn part(&self, index: usize) -> PartDraw<'_> {
        let part = &self.parts[index];
        // The wall part of no cutter holds what a cut left of the model's scalpel incisions.
        let incisions = part.kind == PartKind::Wall && part.cutter == usize::MAX;
        PartDraw {
            model: part.model,
            look: if incisions {
                PartLook::Incisions
            } else {
                part_look(part.kind)
            },
            opacity: part.opacity,
            mesh: &part.mesh,
        }
    }

    fn contours(&self) -> &[(usize, Vec<glam::DVec3>)] {
        &self.contours
    }

    fn risk_wall(&self, risk: &WallRisk, index: usize) -> Option<usize> {
        let part = self.parts.get(index)?;
        risk.walls.iter().position(|w| w.matches(part))
    }
}

/// `cut` as the renderer takes it (the same allocation, so the renderer keeps its uploads).
pub fn drawn_cut(cut: Arc<PreviewGeometry>) -> Arc<dyn CutDrawing> {
    cut
}
