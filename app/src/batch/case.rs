//! One case of a batch: a case folder's volume (and image) opened as a session naming them would
//! open it, the structures picked, the view set, the cutaway made (`cutaway expose`), then the
//! outputs rendered, exported and measured by the code of `cutaway render`, `export`, `turntable`
//! and `metrics`, and written into `OUT/<case>/` as one output set whose last file is
//! `case.json` (the case's row and what it wrote). A case whose `case.json` says it was done with
//! the same recipe is skipped; a failed case writes nothing and reports its error line.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use serde::{Deserialize, Serialize};

use super::recipe::{Recipe, matches};
use crate::annotate::picture::render_session_picture;
use crate::expose::ExposeSettings;
use crate::expose::scene_expose::expose_named;
use crate::metrics::{MetricsOptions, exposure::DEFAULT_SAMPLES, measure};
use crate::render::HeadlessRenderer;
use crate::scene::{Scene, ViewPreset};
use crate::view::RenderPngOptions;

/// The file that marks a complete case.
pub const CASE_FILE: &str = "case.json";

/// Every file a case may write (an earlier run's that this run does not write are removed).
const OUTPUT_FILES: [&str; 7] = [
    "picture.png",
    "turntable.gif",
    "scene.glb",
    "scene.html",
    "session.json",
    "metrics.json",
    CASE_FILE,
];

/// What happened to a case: its row of `metrics.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    /// The case folder's name (its outputs are in `OUT/<case>/`).
    pub case: String,
    /// `ok`, `skipped` (complete from an earlier run) or `failed`.
    pub status: String,
    /// The error line of a failed case.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The recipe's digest the outputs were made with.
    #[serde(default)]
    pub recipe: String,
    /// Wall time of the case.
    pub seconds: f64,
    /// The peak resident memory of the process while it ran the case, in MiB (`None` where the
    /// system does not say).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub memory_mb: Option<f64>,
    pub structures: usize,
    pub cutters: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure_before: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure_after: Option<f64>,
    /// mm³ removed by all cuts (closed structures).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub removed_volume: Option<f64>,
    /// mm from the cut walls to the nearest critical structure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_distance: Option<f64>,
    /// The files written into the case's folder.
    #[serde(default)]
    pub outputs: Vec<String>,
}

impl CaseResult {
    /// The result of a case that failed with `error` after `seconds`.
    pub fn failed(case: &str, recipe: &Recipe, seconds: f64, error: &anyhow::Error) -> CaseResult {
        let line = crate::platform::errors::error_line(error);
        CaseResult {
            case: case.to_owned(),
            status: "failed".to_owned(),
            error: Some(line.strip_prefix("error: ").unwrap_or(&line).to_owned()),
            recipe: recipe.digest(),
            seconds,
            memory_mb: super::memory::peak_mb(),
            structures: 0,
            cutters: 0,
            focus: None,
            exposure_before: None,
            exposure_after: None,
            removed_volume: None,
            min_distance: None,
            outputs: Vec::new(),
        }
    }
}

/// The name of a case folder (its last component).
pub fn case_name(case_dir: &Path) -> String {
    case_dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| case_dir.display().to_string())
}

/// The result recorded in `OUT/<case>/case.json` when that case is complete with this recipe.
pub fn completed(out: &Path, case: &str, recipe: &Recipe) -> Option<CaseResult> {
    let folder = out.join(case);
    // An interrupted set is finished or rolled back first, so a committed case counts.
    crate::io::atomic::recover(&folder).ok()?;
    let text = std::fs::read_to_string(folder.join(CASE_FILE)).ok()?;
    let done: CaseResult = serde_json::from_str(&text).ok()?;
    (done.status == "ok" && done.recipe == recipe.digest()).then_some(done)
}

/// Runs one case (or finds it complete) and says what happened; never panics on bad input.
pub fn run_case(recipe: &Recipe, case_dir: &Path, out: &Path) -> CaseResult {
    let case = case_name(case_dir);
    if let Some(mut done) = completed(out, &case, recipe) {
        done.status = "skipped".to_owned();
        return done;
    }
    super::memory::reset_peak();
    let clock = Instant::now();
    match make_case(recipe, case_dir, &out.join(&case), &case, &clock) {
        Ok(result) => result,
        Err(e) => {
            let e = e.context(case_dir.display().to_string());
            CaseResult::failed(&case, recipe, clock.elapsed().as_secs_f64(), &e)
        }
    }
}

/// The one entry of `dir` whose name matches `pattern` (the first in name order).
fn find(dir: &Path, pattern: &str, what: &str) -> anyhow::Result<PathBuf> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot list the case folder ({what})"))?
        .flatten()
        .filter_map(|e| e.file_name().to_str().map(str::to_owned))
        .filter(|n| !n.starts_with('.') && matches(pattern, n))
        .collect();
    names.sort();
    match names.first() {
        Some(name) => Ok(dir.join(name)),
        None => anyhow::bail!("no {what} named like '{pattern}'"),
    }
}

/// The case's scene: what a session naming its volume (and image) opens, then the recipe's
/// structures and view.
pub fn case_scene(recipe: &Recipe, case_dir: &Path) -> anyhow::Result<Scene> {
    let volume = find(case_dir, &recipe.volume, "volume")?;
    let image = match &recipe.image {
        Some(pattern) => Some(find(case_dir, pattern, "image")?),
        None => None,
    };
    let mut session = serde_json::json!({
        "format": crate::session::FORMAT,
        "models": [{"path": volume}],
    });
    if let Some(image) = image {
        session["image"] = serde_json::json!({"path": image});
    }
    let file = crate::session::parse(&session.to_string())?;
    let mut load =
        |path: &Path, unit| crate::anatomy::assets::load_or_embedded_picking(path, unit, None);
    let mut scene = crate::session::scene_from_file(&file, case_dir, &mut load)?;
    if !recipe.structures.is_empty() {
        let mut keep = Vec::new();
        for name in &recipe.structures {
            keep.push(crate::scene::names::model_named(
                &scene,
                name,
                "structures: ",
            )?);
        }
        let mut i = 0;
        scene.models.retain(|_| {
            i += 1;
            keep.contains(&(i - 1))
        });
    }
    let preset = ViewPreset::ALL
        .into_iter()
        .find(|p| p.label().eq_ignore_ascii_case(&recipe.view))
        .unwrap_or(ViewPreset::Anterior);
    scene.camera = scene.preset_camera(preset);
    Ok(scene)
}

fn make_case(
    recipe: &Recipe,
    case_dir: &Path,
    folder: &Path,
    case: &str,
    clock: &Instant,
) -> anyhow::Result<CaseResult> {
    let mut scene = case_scene(recipe, case_dir)?;
    let focus = recipe.expose.as_ref().map(|e| e.focus.clone());
    if let Some(step) = &recipe.expose {
        let mut settings = ExposeSettings::default();
        if let Some(margin) = step.margin {
            settings.margin_mm = margin;
        }
        scene = expose_named(&scene, &step.focus, &settings, DEFAULT_SAMPLES)?.scene;
    }
    let options = MetricsOptions {
        focus: focus.clone(),
        critical: recipe.outputs.metrics.critical.clone(),
        samples: DEFAULT_SAMPLES,
    };
    let metrics = measure(&scene, &options)?;

    let mut set = crate::io::OutputSet::begin(folder)?;
    let mut outputs = Vec::new();
    let mut add = |set: &mut crate::io::OutputSet, name: &str, bytes: &[u8]| {
        outputs.push(name.to_owned());
        set.write_bytes(Path::new(name), bytes)
    };
    let png = recipe.png();
    let mut picture_options = RenderPngOptions::new(png.width, png.height);
    picture_options.transparent_background = false;
    let labelled = if png.labels {
        Some(crate::annotate::labelled::chosen(&scene, &[])?)
    } else {
        None
    };
    let mut renderer = HeadlessRenderer::new()?;
    let picture =
        render_session_picture(&mut renderer, &scene, &picture_options, labelled.as_deref())?;
    if let Some(note) = &picture.refused {
        anyhow::bail!("{note}");
    }
    drop(renderer);
    add(&mut set, "picture.png", &png_bytes(&picture.image)?)?;
    if let Some(turn) = &recipe.outputs.turntable {
        let gif = turntable_gif(&scene, turn, folder)?;
        add(&mut set, "turntable.gif", &gif)?;
    }
    if recipe.outputs.glb {
        let (bytes, _) = crate::export::glb_of_scene(&scene)?;
        add(&mut set, "scene.glb", &bytes)?;
    }
    if recipe.outputs.html {
        let page = crate::export::webpage::WebPageOptions {
            title: Some(case.to_owned()),
            metrics: options.clone(),
        };
        let (bytes, _) =
            crate::export::webpage::webpage_bytes(&scene, &page, &crate::export::webpage::Quiet)?;
        add(&mut set, "scene.html", &bytes)?;
    }
    let session = crate::session::file_from_scene(&scene, folder);
    add(
        &mut set,
        "session.json",
        format!("{}\n", serde_json::to_string_pretty(&session)?).as_bytes(),
    )?;
    add(
        &mut set,
        "metrics.json",
        format!("{}\n", serde_json::to_string(&metrics)?).as_bytes(),
    )?;
    let removed: Vec<f64> = metrics
        .cutters
        .iter()
        .filter_map(|c| c.removed_volume)
        .collect();
    let result = CaseResult {
        case: case.to_owned(),
        status: "ok".to_owned(),
        error: None,
        recipe: recipe.digest(),
        seconds: clock.elapsed().as_secs_f64(),
        memory_mb: super::memory::peak_mb(),
        structures: scene.models.len(),
        cutters: scene.cutters.len(),
        focus: metrics.focus.as_ref().map(|f| f.name.clone()),
        exposure_before: metrics.focus.as_ref().map(|f| f.exposure_before),
        exposure_after: metrics.focus.as_ref().map(|f| f.exposure_after),
        removed_volume: (!removed.is_empty()).then(|| removed.iter().sum()),
        min_distance: metrics
            .structures
            .iter()
            .filter_map(|s| s.min_distance)
            .min_by(f64::total_cmp),
        outputs: outputs
            .iter()
            .cloned()
            .chain([CASE_FILE.to_owned()])
            .collect(),
    };
    set.write_bytes(
        Path::new(CASE_FILE),
        format!("{}\n", serde_json::to_string_pretty(&result)?).as_bytes(),
    )?;
    for name in OUTPUT_FILES {
        set.replace_file(Path::new(name))?;
    }
    set.commit()?;
    Ok(result)
}

fn png_bytes(image: &image::RgbaImage) -> anyhow::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .context("could not encode the PNG")?;
    Ok(bytes)
}

/// The orbit as an animated GIF, made by `cutaway turntable`'s code in a scratch folder beside
/// the case's outputs (removed afterwards).
fn turntable_gif(
    scene: &Scene,
    turn: &super::recipe::TurntableOutput,
    folder: &Path,
) -> anyhow::Result<Vec<u8>> {
    use crate::export::turntable::{GIF_NAME, Quiet, TurntableOptions, export_turntable};
    let scratch = folder.join(format!(".turntable-{}", std::process::id()));
    let options = TurntableOptions {
        frames: turn.frames,
        gif: true,
        delay_ms: turn.delay_ms,
    };
    let picture = RenderPngOptions::new(turn.width, turn.height);
    let made = export_turntable(scene, &picture, &options, &scratch, &Quiet, None).and_then(|_| {
        std::fs::read(scratch.join(GIF_NAME))
            .with_context(|| scratch.join(GIF_NAME).display().to_string())
    });
    std::fs::remove_dir_all(&scratch).ok();
    made
}
