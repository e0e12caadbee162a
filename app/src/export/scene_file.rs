//! The cut scene written to the file a user names, its format following the extension: `.glb`
//! ([`super::export_glb`]) or `.html`/`.htm` ([`super::webpage::export_webpage`]). What
//! `cutaway export`, `cutaway batch` and the Python `Session.export` share.

use std::path::Path;

use super::webpage::{Quiet, WebPageOptions, export_webpage};
use crate::scene::Scene;

/// What an export's path asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    Glb,
    WebPage,
}

impl ExportFormat {
    /// The format of `out` by its extension (case-insensitive), or a one-line error naming it.
    pub fn of(out: &Path) -> anyhow::Result<ExportFormat> {
        let extension = out
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            Some("glb") => Ok(ExportFormat::Glb),
            Some("html" | "htm") => Ok(ExportFormat::WebPage),
            Some(other) => anyhow::bail!(
                "{}: cannot write '.{other}' files (export writes .glb or .html)",
                out.display()
            ),
            None => anyhow::bail!(
                "{}: no extension (export writes .glb or .html)",
                out.display()
            ),
        }
    }
}

/// The summary of [`export_scene_file`], serialized as the object `cutaway export --json`
/// prints for that format.
#[derive(Clone, Debug, serde::Serialize)]
#[serde(untagged)]
pub enum ExportSummary {
    Glb(super::GlbExport),
    WebPage(super::webpage::WebPageExport),
}

/// Writes `scene` to `out` in the format of its extension (`page` applies to a web page only).
pub fn export_scene_file(
    scene: &Scene,
    out: &Path,
    page: &WebPageOptions,
) -> anyhow::Result<ExportSummary> {
    Ok(match ExportFormat::of(out)? {
        ExportFormat::Glb => ExportSummary::Glb(super::export_glb(scene, out)?),
        ExportFormat::WebPage => ExportSummary::WebPage(export_webpage(scene, out, page, &Quiet)?),
    })
}
