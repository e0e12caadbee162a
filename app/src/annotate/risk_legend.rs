//! The risk map's legend drawn into an exported picture: a title naming the critical structures
//! and the closest wall, a colour bar (red to the near distance, graded to the far one, then the
//! wall colour) with its distances marked under it. Bottom centre, in the band the labels leave
//! free between the orientation marker and the scale bar. The window draws the same bar
//! (`gui/viewport/risk_legend.rs`) from the same [`crate::scene::risk::RiskSettings`] helpers.
//!
//! [`render_with_legend`] is the headless render every exporter of pictures uses (`cutaway
//! render`, turntables, compare sheets, the window's Export Image): the picture and, when the
//! risk map was drawn, its legend.

use std::sync::Arc;

use image::RgbaImage;

use super::labelled::{fill_rect, line_segment};
use super::layout::Rect;
use super::text::{Face, TextPainter};
use crate::cutting::cut_scene::PreviewGeometry;
use crate::cutting::wall_risk::WallRisk;
use crate::render::HeadlessRenderer;
use crate::scene::Scene;
use crate::view::RenderPngOptions;

const INK: [u8; 4] = [20, 22, 26, 255];
const BOX: [u8; 4] = [255, 255, 255, 225];

/// [`crate::view::render_with_preview`] and, when it drew the scene's risk map, the map's
/// legend over the picture.
pub fn render_with_legend(
    renderer: &mut HeadlessRenderer,
    scene: &Scene,
    options: &RenderPngOptions,
    preview: Option<Arc<PreviewGeometry>>,
) -> anyhow::Result<RgbaImage> {
    let mut image = crate::view::render_with_preview(renderer, scene, options, preview)?;
    if let Some(risk) = renderer.drawn_risk() {
        draw_risk_legend(&mut image, &risk);
    }
    Ok(image)
}

/// Draws the legend of `risk` at the bottom centre of `image`; returns the bar's rectangle.
pub fn draw_risk_legend(image: &mut RgbaImage, risk: &WallRisk) -> Rect {
    let [w, h] = [image.width() as f32, image.height() as f32];
    let px = (w.min(h) / 45.0).clamp(11.0, 28.0);
    let painter = TextPainter::new();
    let line = painter.line_height(Face::Sans, px);
    let small = px * 0.85;
    let small_line = painter.line_height(Face::Sans, small);
    let pad = px * 0.45;
    let margin = px * 0.8;
    let title = risk.caption();
    let title_w = painter.width(Face::Sans, px, &title);
    let bar_w = (w * 0.3).max(px * 12.0).min(w - 2.0 * margin - 2.0 * pad);
    let bar_h = (px * 0.8).round();
    let box_w = title_w.max(bar_w) + 2.0 * pad;
    let box_h = pad + line + px * 0.3 + bar_h + px * 0.25 + small_line + pad;
    let left = ((w - box_w) / 2.0).max(0.0);
    let top = h - margin - box_h;
    fill_rect(
        image,
        Rect {
            x: left,
            y: top,
            w: box_w,
            h: box_h,
        },
        BOX,
    );
    painter.draw(
        image,
        Face::Sans,
        px,
        left + (box_w - title_w) / 2.0,
        top + pad,
        &title,
        INK,
    );
    let bar = Rect {
        x: (left + (box_w - bar_w) / 2.0).round(),
        y: (top + pad + line + px * 0.3).round(),
        w: bar_w.round(),
        h: bar_h,
    };
    let settings = &risk.settings;
    for column in 0..bar.w as u32 {
        let x = (column as f64 + 0.5) / bar.w as f64;
        let [r, g, b] = settings.legend_color(x).map(|c| (c * 255.0).round() as u8);
        fill_rect(
            image,
            Rect {
                x: bar.x + column as f32,
                y: bar.y,
                w: 1.0,
                h: bar.h,
            },
            [r, g, b, 255],
        );
    }
    let frame = (px / 14.0).max(1.0);
    for (a, b) in [
        ([bar.x, bar.y], [bar.x + bar.w, bar.y]),
        ([bar.x, bar.y + bar.h], [bar.x + bar.w, bar.y + bar.h]),
        ([bar.x, bar.y], [bar.x, bar.y + bar.h]),
        ([bar.x + bar.w, bar.y], [bar.x + bar.w, bar.y + bar.h]),
    ] {
        line_segment(image, a, b, frame, INK);
    }
    for (at, caption) in settings.legend_marks() {
        let x = bar.x + at as f32 * bar.w;
        line_segment(
            image,
            [x, bar.y + bar.h * 0.4],
            [x, bar.y + bar.h + px * 0.2],
            (px / 9.0).max(1.2),
            INK,
        );
        let tw = painter.width(Face::Sans, small, &caption);
        let tx = (x - tw / 2.0).clamp(left + pad * 0.5, left + box_w - pad * 0.5 - tw);
        painter.draw(
            image,
            Face::Sans,
            small,
            tx,
            bar.y + bar.h + px * 0.25,
            &caption,
            INK,
        );
    }
    bar
}
