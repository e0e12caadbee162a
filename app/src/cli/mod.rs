//! Command line: one subcommand per file, each a thin shell over library code the GUI also uses.
//!
//! Errors are reported exactly once, by `main`, as one line `error: <file>: <what is wrong>`
//! (see `../shared/CONTRACT.md`).

use std::ffi::OsString;
use std::path::PathBuf;

use clap::{Parser, Subcommand};

pub use crate::platform::errors::error_line;

pub mod batch;
pub mod compare;
pub mod export;
pub mod expose;
pub mod extrude;
pub mod extrude_session;
pub mod image_args;
pub mod info;
pub mod metrics;
pub mod open;
pub mod phantom;
pub mod render;
pub mod risk_args;
pub mod scalpel;
pub mod subtract;
pub mod surfaces;
pub mod turntable;

/// Context-preserving cutaways of segmented anatomy.
#[derive(Debug, Parser)]
#[command(name = "cutaway", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the GUI with meshes, label volumes, folders of masks or of meshes, or a session file.
    Open(open::OpenArgs),
    /// Print mesh facts (of a label volume: its surfaces, grid and labels).
    Info(info::InfoArgs),
    /// Cut CUTTER out of every region of TARGET; write kept, walls, removed and contour to DIR.
    Subtract(subtract::SubtractArgs),
    /// Replay a recorded mouse gesture through the cutter editor; write the cutter (on a
    /// session: the session with the new cutter).
    Extrude(extrude::ExtrudeArgs),
    /// Render a session headless to a PNG image.
    Render(render::RenderArgs),
    /// Progressive scalpel cut along a path on the surface.
    Scalpel(scalpel::ScalpelArgs),
    /// One closed surface per label of a segmentation volume, one mesh file each.
    Surfaces(surfaces::SurfacesArgs),
    /// Write the cut scene of a session as glTF 2.0 binary (.glb) or as one web page (.html).
    Export(export::ExportArgs),
    /// Measure the cuts of a session: removed volume and area, exposure, distances.
    Metrics(metrics::MetricsArgs),
    /// Build the cutters that open the session's view onto a structure; write the session with
    /// them.
    Expose(expose::ExposeArgs),
    /// Render and measure every cut variant of a session: pictures, a side-by-side sheet with
    /// the metrics table, metrics as JSON and CSV.
    Compare(compare::CompareArgs),
    /// Render an orbit around the cut scene: a PNG sequence and optionally an animated GIF.
    Turntable(turntable::TurntableArgs),
    /// The same cutaway for every case folder of a cohort: pictures, exports, metrics.csv and
    /// a gallery (index.html).
    Batch(batch::BatchArgs),
    /// Regenerate the embedded synthetic anatomy phantoms into a folder (maintainers only).
    #[command(hide = true)]
    Phantom(phantom::PhantomArgs),
}

/// Parses `args` (program name first) and runs the command. No subcommand opens the GUI on the
/// embedded default scene.
pub fn run<I, T>(args: I) -> anyhow::Result<()>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version go to stdout with success; usage errors print clap's own message.
            if e.use_stderr() {
                e.print().ok();
                std::process::exit(2);
            }
            e.print().ok();
            return Ok(());
        }
    };
    match cli.command {
        None => open::run(&open::OpenArgs {
            paths: Vec::<PathBuf>::new(),
            image: None,
        }),
        Some(Command::Open(a)) => open::run(&a),
        Some(Command::Info(a)) => info::run(&a),
        Some(Command::Subtract(a)) => subtract::run(&a),
        Some(Command::Extrude(a)) => extrude::run(&a),
        Some(Command::Render(a)) => render::run(&a),
        Some(Command::Scalpel(a)) => scalpel::run(&a),
        Some(Command::Surfaces(a)) => surfaces::run(&a),
        Some(Command::Export(a)) => export::run(&a),
        Some(Command::Metrics(a)) => metrics::run(&a),
        Some(Command::Expose(a)) => expose::run(&a),
        Some(Command::Compare(a)) => compare::run(&a),
        Some(Command::Turntable(a)) => turntable::run(&a),
        Some(Command::Batch(a)) => batch::run(&a),
        Some(Command::Phantom(a)) => phantom::run(&a),
    }
}
