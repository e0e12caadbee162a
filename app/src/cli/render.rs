//! `cutaway render SESSION.json --out IMG.png [--width W] [--height H]`. OWNER: renderer helper.

use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A `cutaway-session/1` file.
    pub session: PathBuf,
    /// The PNG to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Image width in pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    anyhow::bail!("{}: render is not implemented yet", args.session.display())
}
