//! Exports of the cut scene for other tools. Egui- and wgpu-free, so the CLI, the GUI and the
//! tests share them.
//!
//! - [`gltf`]: the scene as Preview draws it (kept parts, walls, removed pieces, ribbons, slices,
//!   contours; one named node per structure) as a glTF 2.0 document;
//! - [`glb`]: the binary container it is written in;
//! - [`image_colors`]: the intensity image baked into wall vertex colours;
//! - [`risk_colors`]: the risk map baked into wall vertex colours.
//! - [`scene_file`]: the export a path's extension asks for (`.glb` or `.html`).
//! - [`turntable`]: an orbit around the cut as a PNG sequence and a looping GIF, with progress
//!   and cancel.
//! - [`webpage`]: the cut scene as one self-contained web page (the `.glb` of every variant, a
//!   three.js viewer and the page's data), with progress and cancel.

pub mod glb;
pub mod gltf;
pub mod image_colors;
pub mod meshes;
pub mod risk_colors;
pub mod scene_file;
pub mod turntable;
pub mod webpage;

use std::path::Path;

use anyhow::Context as _;

use crate::cutting::cut_scene::preview_geometry;
use crate::scene::Scene;

/// The outcome of [`export_glb`].
#[derive(Clone, Debug, serde::Serialize)]
pub struct GlbExport {
    #[serde(flatten)]
    pub stats: gltf::ExportStats,
    /// Size of the written file.
    pub bytes: usize,
    /// True when every cut was made by the exact boolean.
    pub exact: bool,
    /// Why a cut is approximate (one line each; empty when `exact`).
    pub notes: Vec<String>,
    /// Wall time of the cuts and of building and writing the file.
    pub cut_ms: f64,
    pub write_ms: f64,
}

/// The `.glb` bytes of `scene` cut as Preview cuts it, with what went into them.
pub fn glb_of_scene(scene: &Scene) -> anyhow::Result<(Vec<u8>, GlbExport)> {
    let clock = std::time::Instant::now();
    let geometry = preview_geometry(scene);
    let risk = crate::cutting::wall_risk::wall_risk(
        scene,
        &geometry,
        &mut crate::cutting::wall_risk::CriticalIndexes::default(),
    );
    let cut_ms = clock.elapsed().as_secs_f64() * 1e3;
    let document = gltf::scene_document(scene, &geometry, risk.as_ref());
    let json = serde_json::to_vec(&document.root).context("could not encode the glTF JSON")?;
    let bytes = glb::glb_bytes(&json, &document.bin)?;
    let summary = GlbExport {
        stats: document.stats,
        bytes: bytes.len(),
        exact: geometry.notes.is_empty(),
        notes: geometry.notes,
        cut_ms,
        write_ms: 0.0,
    };
    Ok((bytes, summary))
}

/// Cuts `scene` and writes it to `out` as a `.glb`, atomically (a temporary file renamed over
/// `out`, so a failure leaves the old file or none). Errors name `out`.
pub fn export_glb(scene: &Scene, out: &Path) -> anyhow::Result<GlbExport> {
    let (bytes, mut summary) = glb_of_scene(scene).with_context(|| format!("{}", out.display()))?;
    let clock = std::time::Instant::now();
    crate::io::atomic::write(out, |w| w.write_all(&bytes))
        .with_context(|| format!("{}: could not write", out.display()))?;
    summary.write_ms = clock.elapsed().as_secs_f64() * 1e3;
    Ok(summary)
}
