//! `cutaway render SESSION.json --out IMG.png [--width W] [--height H]`: the session's picture,
//! headless (no window, no display), with the same renderer as the GUI.

use std::path::PathBuf;

use anyhow::Context as _;

use crate::render::{RenderPngOptions, render_png};

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
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if !(1..=16384).contains(&v) {
            anyhow::bail!("{}: --{what} {v} is outside 1..16384", args.out.display());
        }
    }
    let scene = crate::session::load(&args.session)?;
    let mut options = RenderPngOptions::new(args.width, args.height);
    options.transparent_background = args.transparent;
    let image =
        render_png(&scene, &options).with_context(|| format!("{}", args.session.display()))?;
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .with_context(|| format!("{}: could not encode the PNG", args.out.display()))?;
    crate::io::write_file(&args.out, &bytes)
}
