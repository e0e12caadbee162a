//! A turntable: an orbit around the cut scene written as a PNG sequence (`frames/frame-0001.png`
//! …) and optionally a looping animated GIF (`turntable.gif`), as one output set. The camera turns
//! by 360°/N each frame about its up axis through its target, frame 1 being the scene's own view;
//! the cuts are made once and drawn from every angle.
//!
//! Egui-free so that `cutaway render --turntable`, `cutaway turntable` and the window's
//! File → Export Turntable… share it. Progress and cancel go through [`TurntableProgress`]: the
//! function reports every finished frame and checks for a cancel before each one; a cancelled
//! or failed export never commits its output set, so the folder keeps what it held before.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;
use glam::{DMat3, DVec3};
use image::RgbaImage;

use crate::cutting::cut_scene::{PreviewGeometry, preview_geometry};
use crate::io::OutputSet;
use crate::render::ViewMode;
use crate::scene::Scene;
use crate::view::{RenderPngOptions, render_mode};

/// Most frames of one turntable.
pub const MAX_FRAMES: u32 = 720;

/// Name of the animated GIF inside the output folder.
pub const GIF_NAME: &str = "turntable.gif";

/// What to write besides the picture options.
#[derive(Clone, Debug, PartialEq)]
pub struct TurntableOptions {
    /// Frames in one full turn, 1..=[`MAX_FRAMES`].
    pub frames: u32,
    /// Also write [`GIF_NAME`].
    pub gif: bool,
    /// Time each GIF frame is shown, 10..=10000 ms.
    pub delay_ms: u32,
}

impl Default for TurntableOptions {
    fn default() -> Self {
        TurntableOptions {
            frames: 36,
            gif: true,
            delay_ms: 80,
        }
    }
}

impl TurntableOptions {
    /// One line naming `out` and the bad value, or `Ok`.
    pub fn validate(&self, out: &Path) -> anyhow::Result<()> {
        if !(1..=MAX_FRAMES).contains(&self.frames) {
            anyhow::bail!(
                "{}: {} frames is outside 1..{MAX_FRAMES}",
                out.display(),
                self.frames
            );
        }
        if !(10..=10_000).contains(&self.delay_ms) {
            anyhow::bail!(
                "{}: a frame delay of {} ms is outside 10..10000",
                out.display(),
                self.delay_ms
            );
        }
        Ok(())
    }
}

/// Where a turntable export reports to and learns it should stop.
pub trait TurntableProgress {
    /// `done` of `total` frames are drawn and staged (called after every frame).
    fn frame_done(&self, done: u32, total: u32);
    /// True when the export should stop; checked before every frame and before committing.
    fn cancelled(&self) -> bool;
}

/// Reports nothing and never cancels.
pub struct Quiet;

impl TurntableProgress for Quiet {
    fn frame_done(&self, _: u32, _: u32) {}
    fn cancelled(&self) -> bool {
        false
    }
}

/// The error a cancelled export ends with (nothing was written).
#[derive(Debug, thiserror::Error)]
#[error("turntable export cancelled; nothing was written")]
pub struct TurntableCancelled;

/// What an export wrote.
#[derive(Clone, Debug, serde::Serialize)]
pub struct TurntableSummary {
    pub frames: u32,
    pub gif: bool,
    /// Wall time of the cuts and of drawing every frame (encoding and writing excluded).
    pub render_ms: f64,
}

/// A drawing added to every frame after rendering (rulers, labels), given the frame's scene
/// (its camera turned) and the cut geometry.
pub type Decorate<'a> = &'a dyn Fn(&mut RgbaImage, &Scene, Option<&PreviewGeometry>);

/// File name of frame `k` (0-based `k`, 1-based name), relative to the output folder.
pub fn frame_name(k: u32) -> String {
    format!("frames/frame-{:04}.png", k + 1)
}

/// The camera of frame `k` of `frames`: `camera` turned by k·360°/frames about its up axis
/// through its target.
pub fn orbit(camera: &cutter::Camera, k: u32, frames: u32) -> cutter::Camera {
    let (_, up, _) = camera.basis();
    let axis = camera.up.try_normalize().unwrap_or(up);
    let angle = std::f64::consts::TAU * k as f64 / frames.max(1) as f64;
    let turn = DMat3::from_axis_angle(axis, angle);
    let offset: DVec3 = camera.eye - camera.target;
    cutter::Camera {
        eye: camera.target + turn * offset,
        ..*camera
    }
}

/// Renders the turntable of `scene` into `out` (see the module docs). Fails, writing nothing,
/// when a cut is refused by the exact boolean, on a cancel ([`TurntableCancelled`]) or on a
/// render or write error; errors name `out` or the scene's problem in one line. A folder `out`
/// that did not exist before is removed again on failure.
pub fn export_turntable(
    scene: &Scene,
    picture: &RenderPngOptions,
    options: &TurntableOptions,
    out: &Path,
    progress: &dyn TurntableProgress,
    decorate: Option<Decorate<'_>>,
) -> anyhow::Result<TurntableSummary> {
    options.validate(out)?;
    let existed = out.exists();
    let result = write_turntable(scene, picture, options, out, progress, decorate);
    if result.is_err() && !existed {
        // Only an empty folder is removed: the set's staging folder is gone once dropped.
        std::fs::remove_dir(out).ok();
    }
    result
}

fn write_turntable(
    scene: &Scene,
    picture: &RenderPngOptions,
    options: &TurntableOptions,
    out: &Path,
    progress: &dyn TurntableProgress,
    decorate: Option<Decorate<'_>>,
) -> anyhow::Result<TurntableSummary> {
    let started = std::time::Instant::now();
    let preview = (render_mode(scene, picture) == ViewMode::Preview)
        .then(|| Arc::new(preview_geometry(scene)));
    if let Some(note) = preview.as_ref().and_then(|p| p.notes.first()) {
        anyhow::bail!("{}: {note}", out.display());
    }
    if progress.cancelled() {
        return Err(TurntableCancelled.into());
    }
    let mut renderer =
        crate::render::HeadlessRenderer::new().with_context(|| format!("{}", out.display()))?;
    let mut render_ms = started.elapsed().as_secs_f64() * 1e3;
    let mut frame_scene = scene.clone();
    let mut set = OutputSet::begin(out)?;
    set.replace_folder(Path::new("frames"))?;
    if !options.gif {
        // A GIF of an earlier export would no longer match the frames.
        set.replace_file(Path::new(GIF_NAME))?;
    }
    let mut gif_frames = Vec::new();
    for k in 0..options.frames {
        if progress.cancelled() {
            return Err(TurntableCancelled.into());
        }
        let clock = std::time::Instant::now();
        frame_scene.camera = orbit(&scene.camera, k, options.frames);
        let mut image = crate::annotate::risk_legend::render_with_legend(
            &mut renderer,
            &frame_scene,
            picture,
            preview.clone(),
        )
        .with_context(|| format!("{}", out.display()))?;
        if let Some(decorate) = decorate {
            decorate(&mut image, &frame_scene, preview.as_deref());
        }
        render_ms += clock.elapsed().as_secs_f64() * 1e3;
        let name = frame_name(k);
        let mut bytes = Vec::new();
        image
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .with_context(|| format!("{}: could not encode {name}", out.display()))?;
        set.write_bytes(Path::new(&name), &bytes)?;
        if options.gif {
            gif_frames.push(image);
        }
        progress.frame_done(k + 1, options.frames);
    }
    if options.gif {
        let gif = encode_gif(gif_frames, options.delay_ms)
            .with_context(|| format!("{}: could not encode {GIF_NAME}", out.display()))?;
        set.write_bytes(Path::new(GIF_NAME), &gif)?;
    }
    if progress.cancelled() {
        return Err(TurntableCancelled.into());
    }
    set.commit()?;
    Ok(TurntableSummary {
        frames: options.frames,
        gif: options.gif,
        render_ms,
    })
}

/// `frames` as an animated GIF that loops forever, each shown `delay_ms`.
pub fn encode_gif(frames: Vec<RgbaImage>, delay_ms: u32) -> anyhow::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    {
        let mut encoder = image::codecs::gif::GifEncoder::new_with_speed(&mut bytes, 10);
        encoder.set_repeat(image::codecs::gif::Repeat::Infinite)?;
        let delay = image::Delay::from_numer_denom_ms(delay_ms, 1);
        encoder.encode_frames(
            frames
                .into_iter()
                .map(|f| image::Frame::from_parts(f, 0, 0, delay)),
        )?;
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests;
