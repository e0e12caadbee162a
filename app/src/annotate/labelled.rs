//! A labelled image: structure names with leader lines ([`super::layout`]) ending on a pixel
//! where the structure is seen ([`super::visible`]), a scale bar in mm ([`super::scale_bar`])
//! in the bottom-right corner and the orientation marker ([`super::orientation`]) in the
//! bottom-left, drawn over a rendered picture of the scene.

use image::{Rgba, RgbaImage};

use super::layout::{LabelRequest, PlacedLabel, Rect, place};
use super::orientation::screen_axes;
use super::scale_bar::{ScaleBar, caption, scale_bar};
use super::text::{Face, TextPainter, blend};
use super::visible::{VisibleGrid, anchor, is_opaque, visible_grid};
use crate::cutting::cut_scene::PreviewGeometry;
use crate::scene::Scene;

const INK: [u8; 4] = [20, 22, 26, 255];
const BOX: [u8; 4] = [255, 255, 255, 215];
const LEADER: [u8; 4] = [20, 22, 26, 230];

/// What was drawn, for callers that report it and for tests.
#[derive(Clone, Debug, PartialEq)]
pub struct Annotations {
    /// The labels placed: structure (model index), its name, the box and the leader.
    pub labels: Vec<(usize, PlacedLabel)>,
    /// Named structures not labelled: not seen from the camera, or no room left.
    pub unlabelled: Vec<String>,
    pub scale_bar: Option<ScaleBar>,
    /// Where the scale bar was drawn: its left end and y (pixels).
    pub scale_bar_at: Option<[f32; 2]>,
    /// The orientation marker's centre and arm length (pixels).
    pub marker: ([f32; 2], f32),
}

/// Which structures to label: every opaque visible model, or the models named (an unknown name
/// is an error listing the structures).
pub fn chosen(scene: &Scene, names: &[String]) -> anyhow::Result<Vec<usize>> {
    if names.is_empty() {
        return Ok((0..scene.models.len())
            .filter(|&m| is_opaque(scene, m))
            .collect());
    }
    names
        .iter()
        .map(|name| crate::scene::names::model_named(scene, name, "--labels: "))
        .collect()
}

/// Text size for an image `height` pixels tall.
fn text_px(image: &RgbaImage) -> f32 {
    (image.height().min(image.width()) as f32 / 45.0).clamp(11.0, 28.0)
}

/// Which of the scale bar and the orientation marker to draw besides the labels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Extras {
    pub scale_bar: bool,
    pub marker: bool,
}

impl Default for Extras {
    fn default() -> Extras {
        Extras {
            scale_bar: true,
            marker: true,
        }
    }
}

/// Draws labels for `models`, the scale bar and the orientation marker over `image`, a picture
/// of `scene` drawn with `preview` (the cut parts, or `None` for whole models).
pub fn annotate(
    image: &mut RgbaImage,
    scene: &Scene,
    preview: Option<&PreviewGeometry>,
    models: &[usize],
) -> Annotations {
    annotate_with(image, scene, preview, models, Extras::default())
}

/// [`annotate`] drawing the scale bar and the marker only where `extras` asks (the window's
/// export dialog offers each).
pub fn annotate_with(
    image: &mut RgbaImage,
    scene: &Scene,
    preview: Option<&PreviewGeometry>,
    models: &[usize],
    extras: Extras,
) -> Annotations {
    let size = [image.width(), image.height()];
    let px = text_px(image);
    let painter = TextPainter::new();
    let margin = px * 0.8;
    let step = (size[0].max(size[1]) / 240).max(2);
    let grid: VisibleGrid = visible_grid(scene, preview, size, step);
    let line = painter.line_height(Face::Sans, px);
    let pad = px * 0.3;
    let mut requests = Vec::new();
    let mut owners = Vec::new();
    let mut unlabelled = Vec::new();
    for &m in models {
        let name = &scene.models[m].model.name;
        match anchor(&grid, m as u32) {
            Some(point) => {
                requests.push(LabelRequest {
                    text: name.clone(),
                    size: [
                        painter.width(Face::Sans, px, name) + 2.0 * pad,
                        line + 2.0 * pad,
                    ],
                    anchor: point,
                });
                owners.push(m);
            }
            None => unlabelled.push(name.clone()),
        }
    }
    let marker_arm = px * 2.4;
    let bottom_band = marker_arm * 2.0 + px * 1.5;
    let placed = place(
        &requests,
        [size[0] as f32, size[1] as f32],
        margin,
        px * 0.25,
        bottom_band,
    );
    for (k, request) in requests.iter().enumerate() {
        if !placed.iter().any(|p| p.request == k) {
            unlabelled.push(request.text.clone());
        }
    }
    for p in &placed {
        let [a, b] = p.leader;
        line_segment(image, a, b, (px / 9.0).max(1.2), LEADER);
        disc(image, b, (px / 5.0).max(2.0), LEADER);
        disc(image, b, (px / 9.0).max(1.0), [255, 255, 255, 255]);
        fill_rect(image, p.rect, BOX);
        painter.draw(
            image,
            Face::Sans,
            px,
            p.rect.x + pad,
            p.rect.y + pad,
            &requests[p.request].text,
            INK,
        );
    }
    // Scale bar, bottom right: the bar over its caption.
    let bar = scale_bar(&scene.camera, size[1], size[0] as f64 * 0.25).filter(|_| extras.scale_bar);
    let mut scale_bar_at = None;
    if let Some(bar) = bar {
        let text = caption(&bar);
        let right = size[0] as f32 - margin;
        let left = right - bar.pixels as f32;
        let caption_top = size[1] as f32 - margin - line;
        let y = caption_top - px * 0.5;
        let thickness = (px / 4.0).max(2.0);
        fill_rect(
            image,
            Rect {
                x: left - pad,
                y: y - thickness - pad,
                w: bar.pixels as f32 + 2.0 * pad,
                h: size[1] as f32 - margin - (y - thickness - pad) + pad * 0.5,
            },
            BOX,
        );
        fill_rect(
            image,
            Rect {
                x: left,
                y: y - thickness,
                w: bar.pixels as f32,
                h: thickness,
            },
            INK,
        );
        let w = painter.width(Face::Sans, px, &text);
        painter.draw(
            image,
            Face::Sans,
            px,
            left + (bar.pixels as f32 - w) / 2.0,
            caption_top,
            &text,
            INK,
        );
        scale_bar_at = Some([left, y]);
    }
    // Orientation marker, bottom left: farthest axes first so the nearer ones draw over them.
    let centre = [
        margin + marker_arm + px * 0.6,
        size[1] as f32 - margin - marker_arm - px * 0.6,
    ];
    let mut axes = if extras.marker {
        screen_axes(&scene.camera, &scene.orientation).to_vec()
    } else {
        Vec::new()
    };
    axes.sort_by(|a, b| a.toward_viewer.total_cmp(&b.toward_viewer));
    let colour = |letter: char| match letter {
        'R' => [200, 40, 40, 255],
        'A' => [40, 150, 50, 255],
        _ => [40, 80, 210, 255],
    };
    for axis in &axes {
        let d = [axis.screen[0] as f32, axis.screen[1] as f32];
        let tip = [centre[0] + d[0] * marker_arm, centre[1] + d[1] * marker_arm];
        let tail = [
            centre[0] - d[0] * marker_arm * 0.6,
            centre[1] - d[1] * marker_arm * 0.6,
        ];
        let c = colour(axis.positive);
        let faint = [c[0], c[1], c[2], 110];
        line_segment(image, centre, tail, (px / 9.0).max(1.0), faint);
        line_segment(image, centre, tip, (px / 6.0).max(1.5), c);
        for (letter, at, ink) in [
            (axis.positive, 1.0 + 0.45, c),
            (axis.negative, -0.6 - 0.4, faint),
        ] {
            // Letters of axes pointing at the viewer would sit on the centre: skip them.
            if (d[0] * d[0] + d[1] * d[1]).sqrt() < 0.25 {
                continue;
            }
            let s = letter.to_string();
            let lx =
                centre[0] + d[0] * marker_arm * at - painter.width(Face::Sans, px * 0.8, &s) / 2.0;
            let ly = centre[1] + d[1] * marker_arm * at
                - painter.line_height(Face::Sans, px * 0.8) / 2.0;
            painter.draw(image, Face::Sans, px * 0.8, lx, ly, &s, ink);
        }
    }
    Annotations {
        labels: placed.into_iter().map(|p| (owners[p.request], p)).collect(),
        unlabelled,
        scale_bar: bar,
        scale_bar_at,
        marker: (centre, marker_arm),
    }
}

/// Blends `color` over the rectangle.
pub(super) fn fill_rect(image: &mut RgbaImage, rect: Rect, color: [u8; 4]) {
    let x0 = rect.x.max(0.0).round() as u32;
    let y0 = rect.y.max(0.0).round() as u32;
    let x1 = ((rect.x + rect.w).round().max(0.0) as u32).min(image.width());
    let y1 = ((rect.y + rect.h).round().max(0.0) as u32).min(image.height());
    for y in y0..y1 {
        for x in x0..x1 {
            blend(image.get_pixel_mut(x, y), color, 1.0);
        }
    }
}

/// Coverage of a pixel centre at distance `d` from a shape edge (one pixel of anti-aliasing).
fn coverage(d: f32) -> f32 {
    (0.5 - d).clamp(0.0, 1.0)
}

/// A segment `width` pixels wide from `a` to `b`, anti-aliased.
pub(super) fn line_segment(
    image: &mut RgbaImage,
    a: [f32; 2],
    b: [f32; 2],
    width: f32,
    color: [u8; 4],
) {
    let half = width * 0.5;
    let x0 = (a[0].min(b[0]) - half - 1.0).floor().max(0.0) as u32;
    let y0 = (a[1].min(b[1]) - half - 1.0).floor().max(0.0) as u32;
    let x1 = ((a[0].max(b[0]) + half + 1.0).ceil().max(0.0) as u32).min(image.width());
    let y1 = ((a[1].max(b[1]) + half + 1.0).ceil().max(0.0) as u32).min(image.height());
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = (dx * dx + dy * dy).max(1e-6);
    for y in y0..y1 {
        for x in x0..x1 {
            let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
            let t = (((px - a[0]) * dx + (py - a[1]) * dy) / length2).clamp(0.0, 1.0);
            let (cx, cy) = (a[0] + t * dx, a[1] + t * dy);
            let d = ((px - cx).powi(2) + (py - cy).powi(2)).sqrt() - half;
            let c = coverage(d);
            if c > 0.0 {
                blend(image.get_pixel_mut(x, y), color, c);
            }
        }
    }
}

/// A filled disc, anti-aliased.
pub(super) fn disc(image: &mut RgbaImage, centre: [f32; 2], radius: f32, color: [u8; 4]) {
    line_segment(image, centre, centre, radius * 2.0, color);
}

/// Pixel colour helper for tests and callers that check what is under a leader's end.
pub fn pixel(image: &RgbaImage, at: [f32; 2]) -> Option<Rgba<u8>> {
    let (x, y) = (at[0].floor() as i64, at[1].floor() as i64);
    (x >= 0 && y >= 0 && x < image.width() as i64 && y < image.height() as i64)
        .then(|| *image.get_pixel(x as u32, y as u32))
}
