//! Command line: one subcommand per file, each a thin shell over library code the GUI also uses.
//!
//! Errors are reported exactly once, by `main`, as one line `error: <file>: <what is wrong>`
//! (see `../shared/CONTRACT.md`).

use std::ffi::OsString;
use std::path::PathBuf;

use clap::{Parser, Subcommand};

pub mod compare;
pub mod export;
pub mod extrude;
pub mod info;
pub mod metrics;
pub mod open;
pub mod phantom;
pub mod render;
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
    /// Open the GUI with meshes, directories of meshes, or a session file.
    Open(open::OpenArgs),
    /// Print mesh facts (of a label volume: its surfaces, grid and labels).
    Info(info::InfoArgs),
    /// Cut CUTTER out of every region of TARGET; write kept, walls, removed and contour to DIR.
    Subtract(subtract::SubtractArgs),
    /// Replay a recorded mouse gesture through the cutter editor; write the cutter.
    Extrude(extrude::ExtrudeArgs),
    /// Render a session headless to a PNG image.
    Render(render::RenderArgs),
    /// Progressive scalpel cut along a path on the surface.
    Scalpel(scalpel::ScalpelArgs),
    /// One closed surface per label of a segmentation volume, one mesh file each.
    Surfaces(surfaces::SurfacesArgs),
    /// Write the cut scene of a session as glTF 2.0 binary (.glb).
    Export(export::ExportArgs),
    /// Measure the cuts of a session: removed volume and area, exposure, distances.
    Metrics(metrics::MetricsArgs),
    /// Render and measure every cut variant of a session: pictures, a side-by-side sheet with
    /// the metrics table, metrics as JSON and CSV.
    Compare(compare::CompareArgs),
    /// Render an orbit around the cut scene: a PNG sequence and optionally an animated GIF.
    Turntable(turntable::TurntableArgs),
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
        Some(Command::Compare(a)) => compare::run(&a),
        Some(Command::Turntable(a)) => turntable::run(&a),
        Some(Command::Phantom(a)) => phantom::run(&a),
    }
}

/// The one line `main` prints for an error: `error: ` and the context chain joined by `: `, with
/// any whitespace run inside a message (newlines included) folded to a space so that the report
/// stays on one line, and every other control character (escape sequences, backspace, bidi
/// overrides) written as a `\u{..}` escape. Error messages quote names and tokens taken from
/// input files; this keeps such bytes from reaching the terminal raw.
pub fn error_line(error: &anyhow::Error) -> String {
    let text = format!("{error:#}");
    let mut line = String::from("error:");
    for word in text.split_whitespace() {
        line.push(' ');
        for c in word.chars() {
            if is_terminal_control(c) {
                line.extend(c.escape_unicode());
            } else {
                line.push(c);
            }
        }
    }
    line
}

/// Characters a terminal may act on rather than show: C0/C1 controls, DEL, and the Unicode
/// direction overrides and isolates (which reorder what follows them on the line).
fn is_terminal_control(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

#[cfg(test)]
mod tests {
    #[test]
    fn error_line_is_one_line_without_raw_control_bytes() {
        let error = anyhow::anyhow!("object 'evil\u{1b}[31mred\u{7}' is bad\nnext\u{202e}line")
            .context("knee\r\n.obj");
        let line = super::error_line(&error);
        assert_eq!(
            line,
            "error: knee .obj: object 'evil\\u{1b}[31mred\\u{7}' is bad next\\u{202e}line"
        );
        assert!(!line.chars().any(super::is_terminal_control));
    }
}
