//! The cut scene as one self-contained web page: `cutaway export SESSION.json --out scene.html`
//! and the window's File → Export Web Page… share [`export_webpage`].
//!
//! Why a page: a `.glb` opened in a common glTF viewer loses what matters (walls shaded as walls,
//! the removed piece as adjustable context, names, the views, the measures). The page carries the
//! same glTF document as `cutaway export … .glb` ([`super::gltf`]), one per cut variant, and a
//! small viewer built on three.js that draws it as `cutaway render` does. It opens from disk
//! (`file://`) with no server and no network: everything is inside the one file.
//!
//! What goes in ([`page`] writes it):
//! - the pinned copy of three.js from `assets/three/` ([`three`]), its MIT licence with it;
//! - per variant, the `.glb` bytes of that variant's cut scene (gzip, then base64);
//! - the page's data ([`manifest`]): title, camera, the six standard views, the patient's axes,
//!   structures, variants with what each glTF material draws, the metrics table, the data's
//!   attribution;
//! - the viewer's own script, style and markup (`viewer/`).
//!
//! Failure is all or nothing: a cut the exact boolean refuses, an unknown metrics name or a
//! cancel stops the export before anything is written; the file is written atomically.

pub mod manifest;
pub mod page;
pub mod three;

use std::path::Path;

use anyhow::Context as _;

use crate::cutting::cut_scene::preview_geometry;
use crate::metrics::variants::VariantMetrics;
use crate::metrics::{MetricsOptions, measure};
use crate::scene::Scene;

/// What the page shows besides the scene.
#[derive(Clone, Debug, Default)]
pub struct WebPageOptions {
    /// The page's title and heading (default: "Cutaway scene").
    pub title: Option<String>,
    /// What the metrics table measures besides the removal of every cut (`--focus`,
    /// `--critical`, `--samples`, as `cutaway metrics` takes them).
    pub metrics: MetricsOptions,
}

/// The title of a page whose options name none.
pub const DEFAULT_TITLE: &str = "Cutaway scene";

/// Longest title, in characters.
pub const MAX_TITLE_CHARS: usize = 200;

/// The outcome of an export (`--json`).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct WebPageExport {
    /// Size of the written page.
    pub bytes: usize,
    /// Structures the page lists (the visible models).
    pub structures: usize,
    /// Cut variants the page switches between.
    pub variants: usize,
    /// Wall time from the loaded scene to the written file.
    pub export_ms: f64,
}

/// Progress of an export and its cancel (the window's job; the CLI reports nothing).
pub trait WebPageProgress {
    /// `done` of `total` steps are finished; `what` says what comes next.
    fn step(&self, done: u32, total: u32, what: &str);
    /// True when the export should stop; checked between steps and before writing.
    fn cancelled(&self) -> bool;
}

/// Reports nothing and never cancels.
pub struct Quiet;

impl WebPageProgress for Quiet {
    fn step(&self, _: u32, _: u32, _: &str) {}
    fn cancelled(&self) -> bool {
        false
    }
}

/// A background job's progress bar counts the steps; its Cancel stops the export.
impl WebPageProgress for crate::platform::jobs::Progress {
    fn step(&self, done: u32, total: u32, what: &str) {
        self.set(done as u64, total as u64);
        self.set_message(what.to_string());
    }
    fn cancelled(&self) -> bool {
        self.is_cancelled()
    }
}

/// One variant of the scene, cut and written as glTF.
#[derive(Debug)]
pub struct VariantPage {
    pub name: String,
    /// The `.glb` bytes, exactly what `cutaway export` writes for this variant.
    pub glb: Vec<u8>,
    pub document: super::gltf::ExportStats,
    pub materials: Vec<super::gltf::MaterialRole>,
    /// The opacity of the removed piece of the first cutter that shows one.
    pub removed_opacity: Option<f32>,
}

/// The page's bytes for `scene`, with what went into them.
pub fn webpage_bytes(
    scene: &Scene,
    options: &WebPageOptions,
    progress: &dyn WebPageProgress,
) -> anyhow::Result<(Vec<u8>, WebPageExport)> {
    let clock = std::time::Instant::now();
    let title = checked_title(options.title.as_deref())?;
    let names = crate::scene::variants::names(scene);
    // Per variant: the cut and its glTF, then its measures; then the page.
    let total = 2 * names.len() as u32 + 1;
    let mut done = 0;
    let mut step = |what: String| -> anyhow::Result<()> {
        if progress.cancelled() {
            anyhow::bail!(crate::platform::jobs::Cancelled);
        }
        progress.step(done, total, &what);
        done += 1;
        Ok(())
    };
    let mut variants = Vec::with_capacity(names.len());
    let mut measured = Vec::with_capacity(names.len());
    for (k, name) in names.iter().enumerate() {
        step(format!("cutting variant '{name}'"))?;
        let shown = crate::scene::variants::variant_scene(scene, k).expect("k < variant count");
        variants.push(variant_page(&shown, name)?);
        step(format!("measuring variant '{name}'"))?;
        let metrics = measure(&shown, &options.metrics)
            .map_err(|e| anyhow::anyhow!("variant '{name}': {e}"))?;
        measured.push(VariantMetrics {
            name: name.clone(),
            metrics,
        });
    }
    step("writing the page".to_string())?;
    let data = manifest::Manifest::new(scene, &title, &variants, &measured, &options.metrics);
    let bytes = page::page_bytes(&data, &variants)?;
    if progress.cancelled() {
        anyhow::bail!(crate::platform::jobs::Cancelled);
    }
    progress.step(total, total, "done");
    let summary = WebPageExport {
        bytes: bytes.len(),
        structures: data.structures.len(),
        variants: variants.len(),
        export_ms: clock.elapsed().as_secs_f64() * 1e3,
    };
    Ok((bytes, summary))
}

/// Exports `scene` as a page to `out`, atomically (a temporary file renamed over `out`, so a
/// failure or a cancel leaves the old file or none). Errors name `out`.
pub fn export_webpage(
    scene: &Scene,
    out: &Path,
    options: &WebPageOptions,
    progress: &dyn WebPageProgress,
) -> anyhow::Result<WebPageExport> {
    let clock = std::time::Instant::now();
    let (bytes, mut summary) = webpage_bytes(scene, options, progress).map_err(|e| {
        if crate::platform::jobs::is_cancelled(&e) {
            e
        } else {
            e.context(out.display().to_string())
        }
    })?;
    crate::io::write_file(out, &bytes)?;
    summary.export_ms = clock.elapsed().as_secs_f64() * 1e3;
    Ok(summary)
}

/// The cut and the glTF of one variant's scene; a cut the exact boolean refuses is an error
/// naming the variant (the page would not show what the session holds).
fn variant_page(shown: &Scene, name: &str) -> anyhow::Result<VariantPage> {
    let geometry = preview_geometry(shown);
    if let Some(note) = geometry.notes.first() {
        anyhow::bail!("variant '{name}': {note}");
    }
    let risk = crate::cutting::wall_risk::wall_risk(
        shown,
        &geometry,
        &mut crate::cutting::wall_risk::CriticalIndexes::default(),
    );
    let document = super::gltf::scene_document(shown, &geometry, risk.as_ref());
    let json = serde_json::to_vec(&document.root).context("could not encode the glTF JSON")?;
    let glb = super::glb::glb_bytes(&json, &document.bin)?;
    let removed_opacity = shown.cutters.iter().find_map(|c| c.views.transparency);
    Ok(VariantPage {
        name: name.to_string(),
        glb,
        document: document.stats,
        materials: document.materials,
        removed_opacity,
    })
}

/// The title to show: the option's, trimmed, or [`DEFAULT_TITLE`]; one line of at most
/// [`MAX_TITLE_CHARS`] characters.
pub fn checked_title(title: Option<&str>) -> anyhow::Result<String> {
    let Some(title) = title.map(str::trim) else {
        return Ok(DEFAULT_TITLE.to_string());
    };
    if title.is_empty() {
        anyhow::bail!("the title is empty");
    }
    if title.chars().count() > MAX_TITLE_CHARS {
        anyhow::bail!("the title is longer than {MAX_TITLE_CHARS} characters");
    }
    if title.chars().any(char::is_control) {
        anyhow::bail!("the title holds a control character");
    }
    Ok(title.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::gltf::MaterialPart;
    use crate::scene::CutterViews;

    /// A cube cut at its corner showing the removed piece at 25 %, and a hidden second cube.
    fn scene() -> Scene {
        let mut scene = crate::test_support::scene_with_cube_cut(CutterViews {
            transparency: Some(0.25),
            ..CutterViews::default()
        });
        let mut hidden = scene.models[0].clone();
        hidden.model.name = "hidden".into();
        hidden.visible = false;
        scene.models.push(hidden);
        scene.camera = scene.framing_camera();
        scene
    }

    #[test]
    fn the_data_lists_visible_structures_and_what_each_material_draws() {
        let scene = scene();
        let (bytes, summary) = webpage_bytes(&scene, &WebPageOptions::default(), &Quiet).unwrap();
        assert_eq!(summary.bytes, bytes.len());
        assert_eq!((summary.structures, summary.variants), (1, 1));
        let variant = variant_page(&scene, "current").unwrap();
        assert_eq!(variant.removed_opacity, Some(0.25));
        let parts: Vec<MaterialPart> = variant.materials.iter().map(|r| r.part).collect();
        for part in [
            MaterialPart::Surface,
            MaterialPart::Wall,
            MaterialPart::Removed,
            MaterialPart::Contour,
        ] {
            assert!(parts.contains(&part), "{parts:?}");
        }
        let measured = vec![VariantMetrics {
            name: "current".into(),
            metrics: measure(&scene, &MetricsOptions::default()).unwrap(),
        }];
        let data = manifest::Manifest::new(
            &scene,
            "t",
            &[variant],
            &measured,
            &MetricsOptions::default(),
        );
        assert_eq!(data.structures.len(), 1);
        assert_eq!(data.structures[0].name, "cube");
        // Every material of the skin carries structure 0; the hidden box has none.
        for m in &data.variants[0].materials {
            match m.part {
                MaterialPart::Contour | MaterialPart::Image | MaterialPart::Risk => {
                    assert_eq!(m.structure, None)
                }
                _ => assert_eq!(m.structure, Some(0)),
            }
        }
        assert!(
            data.metrics
                .rows
                .iter()
                .any(|r| r.label == "removed volume")
        );
        assert_eq!(data.views.len(), 6);
        assert!(data.attribution.is_none(), "no atlas in this scene");
    }

    #[test]
    fn titles_are_one_trimmed_line() {
        assert_eq!(checked_title(None).unwrap(), DEFAULT_TITLE);
        assert_eq!(checked_title(Some("  Knee  ")).unwrap(), "Knee");
        assert!(checked_title(Some("   ")).is_err());
        assert!(checked_title(Some("a\nb")).is_err());
        assert!(checked_title(Some(&"x".repeat(MAX_TITLE_CHARS + 1))).is_err());
    }

    /// A cancel before the first step stops the export, and nothing is written.
    #[test]
    fn a_cancelled_export_writes_nothing() {
        struct Cancelled;
        impl WebPageProgress for Cancelled {
            fn step(&self, _: u32, _: u32, _: &str) {}
            fn cancelled(&self) -> bool {
                true
            }
        }
        let dir = std::env::temp_dir().join(format!("cutaway-webpage-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("page.html");
        let err =
            export_webpage(&scene(), &out, &WebPageOptions::default(), &Cancelled).unwrap_err();
        assert!(crate::platform::jobs::is_cancelled(&err), "{err:#}");
        assert!(!out.exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}
