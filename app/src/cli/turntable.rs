//! `cutaway turntable SESSION.json --out DIR --frames N [--width W] [--height H] [--gif]
//! [--delay-ms MS]`: an orbit around the cut scene, written as one output set by
//! [`crate::export::turntable`] (the same code as `cutaway render --turntable N` and the window's
//! File → Export Turntable…). Progress goes to stderr only when stderr is a terminal. The risk
//! map's flags are `render`'s ([`crate::cli::risk_args`]).

use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};

use crate::export::turntable::{MAX_FRAMES, TurntableOptions, TurntableProgress, export_turntable};
use crate::view::RenderPngOptions;

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
    #[command(flatten)]
    pub risk: crate::cli::risk_args::RiskArgs,
}

/// Progress of a CLI turntable: `frame k/N` rewritten in place on stderr when stderr is a
/// terminal, nothing otherwise (logs and `--json` consumers see no progress noise).
pub struct TerminalProgress {
    shown: bool,
}

impl TerminalProgress {
    pub fn new() -> TerminalProgress {
        TerminalProgress {
            shown: std::io::stderr().is_terminal(),
        }
    }

    /// Ends the progress line (call once the export returned).
    pub fn finish(&self) {
        if self.shown {
            eprintln!();
        }
    }
}

impl Default for TerminalProgress {
    fn default() -> Self {
        TerminalProgress::new()
    }
}

impl TurntableProgress for TerminalProgress {
    fn frame_done(&self, done: u32, total: u32) {
        if self.shown {
            eprint!("\rframe {done}/{total}");
        }
    }
    fn cancelled(&self) -> bool {
        false
    }
}

/// The turntable options of the command line, refused in one line naming the flag.
/// `frames_flag` is the flag that gave `frames` (`--frames` or `--turntable`).
pub fn checked_options(
    out: &Path,
    frames_flag: &str,
    frames: u32,
    gif: bool,
    delay_ms: u32,
) -> anyhow::Result<TurntableOptions> {
    if !(1..=MAX_FRAMES).contains(&frames) {
        anyhow::bail!(
            "{}: {frames_flag} {frames} is outside 1..{MAX_FRAMES}",
            out.display()
        );
    }
    if !(10..=10_000).contains(&delay_ms) {
        anyhow::bail!(
            "{}: --delay-ms {delay_ms} is outside 10..10000",
            out.display()
        );
    }
    let options = TurntableOptions {
        frames,
        gif,
        delay_ms,
    };
    options.validate(out)?;
    Ok(options)
}

pub fn run(args: &TurntableArgs) -> anyhow::Result<()> {
    for (what, v) in [("width", args.width), ("height", args.height)] {
        if !(1..=4096).contains(&v) {
            anyhow::bail!("{}: --{what} {v} is outside 1..4096", args.out.display());
        }
    }
    let options = checked_options(&args.out, "--frames", args.frames, args.gif, args.delay_ms)?;
    let mut scene = crate::session::load(&args.session)?;
    crate::cli::risk_args::apply(&mut scene, &args.risk)
        .map_err(|e| e.context(args.session.display().to_string()))?;
    let progress = TerminalProgress::new();
    let result = export_turntable(
        &scene,
        &RenderPngOptions::new(args.width, args.height),
        &options,
        &args.out,
        &progress,
        None,
    );
    progress.finish();
    result.map(|_| ())
}
