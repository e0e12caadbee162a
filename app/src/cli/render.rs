//! `cutaway render SESSION.json --out IMG.png [--width W] [--height H] [--labels [NAME…]]
//! [--json] [--image CT.nrrd] [--window lung|LEVEL,WIDTH] [--display image|blend|color]`: the
//! session's picture, headless (no window, no display), with the same renderer as the GUI.
//! `--labels` draws structure names with leader lines (every opaque visible structure, or the ones
//! named), a scale bar in mm and the orientation marker ([`crate::annotate`]); the image options
//! replace or adjust the session's `"image"`. The session's rulers are drawn over the picture
//! ([`crate::annotate::rulers`]). `--critical NAME…` colours the cut walls by their distance to
//! those structures (`--risk-mm NEAR,FAR`, `--no-risk`: [`crate::cli::risk_args`]), with the
//! legend drawn at the bottom ([`crate::annotate::risk_legend`]); a session's `"risk"` does the
//! same without flags.
//!
//! `--turntable N` writes an orbit instead of one picture: `--out` is then a folder that gets
//! `frames/frame-0001.png` … `frame-000N.png` (and `turntable.gif` with `--gif`) as one output
//! set, by [`crate::export::turntable`] (the same code as `cutaway turntable` and the window's
//! File → Export Turntable…), with rulers and `--labels` drawn on every frame; sides up to 4096.
//! Progress goes to stderr only when stderr is a terminal; `--json` then prints
//! `{"frames":N,"gif":bool,"render_ms":f}`.
//!
//! Every cut is made by the exact boolean; there is no approximate stand-in. A cutter the boolean
//! refuses makes the command fail (no image is written) with the reason, after `--json` has
//! printed the report: `{"cutters":[{"exact":bool,"cut_ms":f,"levels":n,"triangles":n}],
//! "render_ms":f}`, one entry per cutter of the session in order (`exact` false for a refused
//! cut; a cutter with no view shown is not cut: `exact` true, `cut_ms` 0; `levels` the
//! subdivision levels its surface has, 0 for boxes, and `triangles` that surface's size). `render_ms` is the wall time from the loaded scene to
//! the finished image (cuts and drawing; reading the files and writing the PNG excluded).

use std::path::PathBuf;

use anyhow::Context as _;

use crate::render::HeadlessRenderer;
use crate::view::RenderPngOptions;

#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A session file (`cutaway-session/2` or `/1`).
    pub session: PathBuf,
    /// The PNG to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Image width in pixels (up to 16384; large images are rendered in tiles).
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Image height in pixels (up to 16384).
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Transparent background instead of the session's background colour.
    #[arg(long)]
    pub transparent: bool,
    /// Print whether each cut was exact and the times as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Show this intensity image (NRRD or NIfTI) on the walls instead of the session's.
    #[arg(long)]
    pub image: Option<PathBuf>,
    /// Window of the image: soft-tissue, lung, bone, brain, auto, or LEVEL,WIDTH.
    #[arg(long, allow_hyphen_values = true)]
    pub window: Option<String>,
    /// What walls show: image, blend or color.
    #[arg(long)]
    pub display: Option<String>,
    /// Label structures (all opaque visible ones, or the NAMEs given) with leader lines, and
    /// draw a scale bar in mm and the orientation marker (R/L, A/P, S/I).
    #[arg(long, num_args = 0.., value_name = "NAME")]
    pub labels: Option<Vec<String>>,
    /// Write an orbit of N frames into the folder `--out` instead of one PNG (1..=720).
    #[arg(long, value_name = "N")]
    pub turntable: Option<u32>,
    /// With `--turntable`: also write `turntable.gif`, an animated GIF of the frames.
    #[arg(long, requires = "turntable")]
    pub gif: bool,
    /// With `--turntable`: time each GIF frame is shown, in milliseconds.
    #[arg(long, default_value_t = 80, requires = "turntable")]
    pub delay_ms: u32,
    #[command(flatten)]
    pub risk: crate::cli::risk_args::RiskArgs,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if !(1..=16384).contains(&v) {
            anyhow::bail!("{}: --{what} {v} is outside 1..16384", args.out.display());
        }
    }
    let mut scene = crate::session::load(&args.session)?;
    crate::cli::image_args::apply(
        &mut scene,
        args.image.as_deref(),
        args.window.as_deref(),
        args.display.as_deref(),
    )?;
    crate::cli::risk_args::apply(&mut scene, &args.risk)
        .with_context(|| format!("{}", args.session.display()))?;
    let labelled = match &args.labels {
        Some(names) => Some(
            crate::annotate::labelled::chosen(&scene, names)
                .with_context(|| format!("{}", args.session.display()))?,
        ),
        None => None,
    };
    let mut options = RenderPngOptions::new(args.width, args.height);
    options.transparent_background = args.transparent;
    if let Some(frames) = args.turntable {
        return turntable(args, frames, &scene, &options, labelled.as_deref());
    }
    let mut renderer =
        HeadlessRenderer::new().with_context(|| format!("{}", args.session.display()))?;
    if let Some(layer) = &scene.image {
        let limit = renderer.max_texture_dimension_3d() as usize;
        if let Some(notice) = crate::io::intensity::fit::notice(&layer.image, limit) {
            eprintln!("{}: {notice}", layer.image.source.display());
        }
    }
    let picture = crate::annotate::picture::render_session_picture(
        &mut renderer,
        &scene,
        &options,
        labelled.as_deref(),
    )
    .with_context(|| format!("{}", args.session.display()))?;
    let reports = &picture.reports;
    let render_ms = picture.render_ms;
    if args.json {
        let cutters: Vec<serde_json::Value> = reports
            .iter()
            .zip(&scene.cutters)
            .map(|(r, c)| {
                // The surface this cutter cuts with: its subdivision levels and size.
                let (levels, triangles) = if c.cutter.planes.len() < 2 {
                    (0, 0)
                } else {
                    let s = c.cutter.smoothing(c.cutter.levels);
                    (s.levels, s.mesh.triangulate().triangle_count())
                };
                serde_json::json!({
                    "exact": r.exact,
                    "cut_ms": r.cut_ms,
                    "levels": levels,
                    "triangles": triangles,
                })
            })
            .collect();
        println!(
            "{}",
            serde_json::json!({"cutters": cutters, "render_ms": render_ms})
        );
    }
    if let Some(note) = &picture.refused {
        anyhow::bail!("{}: {note}", args.session.display());
    }
    let mut bytes = Vec::new();
    picture
        .image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .with_context(|| format!("{}: could not encode the PNG", args.out.display()))?;
    crate::io::write_file(&args.out, &bytes)
}

/// `--turntable N`: the orbit written into the folder `--out`, rulers and labels on every frame.
fn turntable(
    args: &RenderArgs,
    frames: u32,
    scene: &crate::scene::Scene,
    options: &RenderPngOptions,
    labelled: Option<&[usize]>,
) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if v > 4096 {
            anyhow::bail!(
                "{}: --{what} {v} is over 4096 (the largest turntable frame)",
                args.out.display()
            );
        }
    }
    let turn = crate::cli::turntable::checked_options(
        &args.out,
        "--turntable",
        frames,
        args.gif,
        args.delay_ms,
    )?;
    let decorate =
        |image: &mut image::RgbaImage,
         frame: &crate::scene::Scene,
         preview: Option<&crate::cutting::cut_scene::PreviewGeometry>| {
            crate::annotate::rulers::draw_rulers(image, frame);
            if let Some(models) = labelled {
                crate::annotate::labelled::annotate(image, frame, preview, models);
            }
        };
    let progress = crate::cli::turntable::TerminalProgress::new();
    let result = crate::export::turntable::export_turntable(
        scene,
        options,
        &turn,
        &args.out,
        &progress,
        Some(&decorate),
    );
    progress.finish();
    let summary = result?;
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}
