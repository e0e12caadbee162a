//! `cutaway turntable SESSION.json --out DIR --frames N [--width W] [--height H] [--gif]
//! [--delay-ms MS]`: an orbit around the cut scene, written as one output set: `frame-0001.png` …
//! (the camera turned by 360°/N each frame about the camera's up axis through its target, frame
//! 1 the session's own view) and, with `--gif`, `turntable.gif` looping forever. The cuts are
//! made once and drawn from every angle.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context as _;
use glam::{DMat3, DVec3};

use crate::cutaway_geometry::preview_geometry;
use crate::io::OutputSet;
use crate::render::{RenderPngOptions, ViewMode, render_mode};

/// Most frames of one turntable.
pub const MAX_FRAMES: u32 = 720;

#[derive(Debug, clap::Args)]
pub struct TurntableArgs {
    /// A session file (`cutaway-session/2` or `/1`).
    pub session: PathBuf,
    /// The folder to write the frames (and the GIF) into.
    #[arg(long)]
    pub out: PathBuf,
    /// Frames in one full turn (1..=720).
    #[arg(long, default_value_t = 36)]
    pub frames: u32,
    /// Frame width in pixels (up to 4096).
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Frame height in pixels (up to 4096).
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Also write `turntable.gif`, an animated GIF of the frames.
    #[arg(long)]
    pub gif: bool,
    /// Time each GIF frame is shown, in milliseconds.
    #[arg(long, default_value_t = 80)]
    pub delay_ms: u32,
}

/// File name of frame `k` (0-based `k`, 1-based name).
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

pub fn run(args: &TurntableArgs) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if !(1..=4096).contains(&v) {
            anyhow::bail!("{}: --{what} {v} is outside 1..4096", args.out.display());
        }
    }
    if !(1..=MAX_FRAMES).contains(&args.frames) {
        anyhow::bail!(
            "{}: --frames {} is outside 1..{MAX_FRAMES}",
            args.out.display(),
            args.frames
        );
    }
    if !(10..=10_000).contains(&args.delay_ms) {
        anyhow::bail!(
            "{}: --delay-ms {} is outside 10..10000",
            args.out.display(),
            args.delay_ms
        );
    }
    let mut scene = crate::session::load(&args.session)?;
    let in_session = |e: anyhow::Error| e.context(args.session.display().to_string());
    let options = RenderPngOptions::new(args.width, args.height);
    let preview = (render_mode(&scene, &options) == ViewMode::Preview)
        .then(|| Arc::new(preview_geometry(&scene)));
    if let Some(note) = preview.as_ref().and_then(|p| p.notes.first()) {
        anyhow::bail!("{}: {note}", args.session.display());
    }
    let mut renderer = crate::render::HeadlessRenderer::new().map_err(in_session)?;
    let start = scene.camera;
    let mut set = OutputSet::begin(&args.out)?;
    set.replace_folder(Path::new("frames"))?;
    let mut gif_frames = Vec::new();
    for k in 0..args.frames {
        scene.camera = orbit(&start, k, args.frames);
        let image =
            crate::render::render_with_preview(&mut renderer, &scene, &options, preview.clone())
                .map_err(in_session)?;
        let name = frame_name(k);
        let mut bytes = Vec::new();
        image
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .with_context(|| format!("{}: could not encode {name}", args.out.display()))?;
        set.write_bytes(Path::new(&name), &bytes)?;
        if args.gif {
            gif_frames.push(image);
        }
        eprint!("\rframe {}/{}", k + 1, args.frames);
    }
    eprintln!();
    if args.gif {
        let gif = encode_gif(gif_frames, args.delay_ms)
            .with_context(|| format!("{}: could not encode turntable.gif", args.out.display()))?;
        set.write_bytes(Path::new("turntable.gif"), &gif)?;
    }
    set.commit()
}

/// `frames` as an animated GIF that loops forever, each shown `delay_ms`.
pub fn encode_gif(frames: Vec<image::RgbaImage>, delay_ms: u32) -> anyhow::Result<Vec<u8>> {
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
mod tests {
    use super::*;

    #[test]
    fn the_orbit_turns_about_the_up_axis_keeping_distance_and_height() {
        let camera = cutter::Camera {
            eye: DVec3::new(0.0, -100.0, 30.0),
            target: DVec3::new(0.0, 0.0, 10.0),
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        assert!((orbit(&camera, 0, 8).eye - camera.eye).length() < 1e-12);
        let quarter = orbit(&camera, 2, 8);
        assert!(
            (quarter.eye - DVec3::new(100.0, 0.0, 30.0)).length() < 1e-9,
            "{:?}",
            quarter.eye
        );
        for k in 0..8 {
            let c = orbit(&camera, k, 8);
            assert!((c.distance() - camera.distance()).abs() < 1e-9);
            assert!((c.eye.z - 30.0).abs() < 1e-9);
            assert_eq!(c.target, camera.target);
        }
    }

    #[test]
    fn the_gif_holds_every_frame_and_loops() {
        let frames: Vec<image::RgbaImage> = (0..3u8)
            .map(|k| image::RgbaImage::from_pixel(8, 6, image::Rgba([k * 100, 0, 0, 255])))
            .collect();
        let bytes = encode_gif(frames, 50).unwrap();
        assert_eq!(&bytes[..6], b"GIF89a");
        use image::AnimationDecoder as _;
        let decoded = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(&bytes))
            .unwrap()
            .into_frames()
            .collect_frames()
            .unwrap();
        assert_eq!(decoded.len(), 3);
        assert_eq!(decoded[2].buffer().get_pixel(3, 3)[0], 200);
        assert_eq!(decoded[1].delay().numer_denom_ms(), (50, 1));
        // NETSCAPE2.0 application extension: the animation loops.
        assert!(bytes.windows(11).any(|w| w == b"NETSCAPE2.0"));
    }
}
