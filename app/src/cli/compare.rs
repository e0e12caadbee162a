//! `cutaway compare SESSION.json --out DIR [--width W] [--height H] [--focus NAME]
//! [--critical NAME…] [--samples N] [--json]`: every cut variant of the session measured and
//! drawn from the session camera, written as one output set into DIR:
//!
//! - `variants/variant-1.png`, `variants/variant-2.png`, …: each variant's picture, in variant
//!   order (the folder is replaced as a whole, so no picture of an earlier run with more
//!   variants stays);
//! - `compare.png`: the pictures side by side under their names, the metrics table under them;
//! - `metrics.json`: `{"variants":[{"name","image","metrics"}…],"combined":"compare.png"}`
//!   (`metrics` as `cutaway metrics --json` prints it), also printed with `--json`;
//! - `metrics.csv`: one row per variant and structure ([`crate::metrics::table::CSV_HEADER`]).
//!
//! A session without variants is one variant, `current`.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use crate::compare::{render_variants, sheet};
use crate::io::OutputSet;
use crate::metrics::table;
use crate::metrics::variants::measure_variants;
use crate::metrics::{MetricsOptions, exposure::DEFAULT_SAMPLES};

#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// A session file (`cutaway-session/2` or `/1`), with or without variants.
    pub session: PathBuf,
    /// The folder to write the pictures, the sheet and the metrics into.
    #[arg(long)]
    pub out: PathBuf,
    /// Width of each variant's picture in pixels (up to 4096).
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Height of each variant's picture in pixels (up to 4096).
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Structure (model name) whose exposure to the camera is measured.
    #[arg(long)]
    pub focus: Option<String>,
    /// Structures (model names) whose distance to the cut walls is measured.
    #[arg(long, num_args = 1..)]
    pub critical: Vec<String>,
    /// Surface samples (one ray each) of the exposure estimate.
    #[arg(long, default_value_t = DEFAULT_SAMPLES)]
    pub samples: usize,
    /// Print the metrics document on standard output as one line of JSON.
    #[arg(long)]
    pub json: bool,
}

/// Name of the combined sheet in the output folder.
pub const SHEET: &str = "compare.png";

/// File name of variant `k`'s picture (0-based `k`, 1-based name).
pub fn picture_name(k: usize) -> String {
    format!("variants/variant-{}.png", k + 1)
}

pub fn run(args: &CompareArgs) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if !(1..=4096).contains(&v) {
            anyhow::bail!("{}: --{what} {v} is outside 1..4096", args.out.display());
        }
    }
    let scene = crate::session::load(&args.session)?;
    let in_session = |e: anyhow::Error| e.context(args.session.display().to_string());
    let options = MetricsOptions {
        focus: args.focus.clone(),
        critical: args.critical.clone(),
        samples: args.samples,
    };
    let variants = measure_variants(&scene, &options).map_err(in_session)?;
    let rows = table::rows(&variants);
    let names: Vec<String> = variants.iter().map(|v| v.name.clone()).collect();
    let layout = sheet::Layout::new(
        [args.width, args.height],
        names.len() as u32,
        rows.len() as u32,
        rows.iter()
            .map(|r| r.label.chars().count())
            .max()
            .unwrap_or(0),
    );
    let [w, h] = layout.size();
    if w > sheet::MAX_SIDE as u64 || h > sheet::MAX_SIDE as u64 {
        anyhow::bail!(
            "{}: {} variants of {}×{} make a sheet of {w}×{h} pixels, more than {} on a side; use a smaller --width or --height",
            args.session.display(),
            names.len(),
            args.width,
            args.height,
            sheet::MAX_SIDE
        );
    }
    let mut renderer = crate::render::HeadlessRenderer::new().map_err(in_session)?;
    let pictures =
        render_variants(&mut renderer, &scene, args.width, args.height).map_err(in_session)?;
    let combined = sheet::draw(&names, &pictures, &rows).map_err(in_session)?;

    let picture_names: Vec<String> = (0..pictures.len()).map(picture_name).collect();
    let document = table::json(&variants, &picture_names, SHEET);
    let mut set = OutputSet::begin(&args.out)?;
    set.replace_folder(Path::new("variants"))?;
    for (name, picture) in picture_names.iter().zip(&pictures) {
        set.write_bytes(Path::new(name), &png(picture, &args.out.join(name))?)?;
    }
    set.write_bytes(Path::new(SHEET), &png(&combined, &args.out.join(SHEET))?)?;
    let mut text = serde_json::to_string_pretty(&document)?;
    text.push('\n');
    set.write_bytes(Path::new("metrics.json"), text.as_bytes())?;
    set.write_bytes(Path::new("metrics.csv"), table::csv(&variants).as_bytes())?;
    set.commit()?;
    if args.json {
        println!("{}", serde_json::to_string(&document)?);
    }
    Ok(())
}

/// `image` encoded as PNG; the error names `path`.
fn png(image: &image::RgbaImage, path: &Path) -> anyhow::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .with_context(|| format!("{}: could not encode the PNG", path.display()))?;
    Ok(bytes)
}
