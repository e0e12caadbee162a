//! `Session`: a scene as a session file describes it (loaded from one, or made from meshes in
//! memory through the same session reader), with what the CLI does to a session: `metrics`,
//! `render`, `export`, `expose`, `save`.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use cutaway::annotate::picture::render_session_picture;
use cutaway::cli::risk_args::{RiskArgs, apply as apply_risk};
use cutaway::export::scene_file::export_scene_file;
use cutaway::export::webpage::WebPageOptions;
use cutaway::expose::ExposeSettings;
use cutaway::expose::scene_expose::expose_named;
use cutaway::metrics::{MetricsOptions, measure};
use cutaway::render::HeadlessRenderer;
use cutaway::scene::{MeshOrigin, ModelUnit, Scene, ViewPreset};
use cutaway::view::RenderPngOptions;
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;

use crate::{arrays, detached};

/// A scene: models, cutters, camera, render settings (a `cutaway-session/2` in memory).
#[pyclass(module = "cutaway._cutaway", frozen)]
pub struct Session {
    scene: Mutex<Scene>,
    /// The session file it was loaded from: errors about the session name it, as the CLI's do.
    source: Option<PathBuf>,
}

impl Session {
    fn new(scene: Scene, source: Option<PathBuf>) -> Session {
        Session {
            scene: Mutex::new(scene),
            source,
        }
    }

    /// `error` named by the session file, as the CLI names it (in-memory sessions: as is).
    fn named(&self) -> impl Fn(anyhow::Error) -> anyhow::Error + Send + use<> {
        let source = self.source.clone();
        move |e| match &source {
            Some(path) => e.context(path.display().to_string()),
            None => e,
        }
    }

    fn scene(&self) -> Scene {
        self.scene.lock().unwrap_or_else(|p| p.into_inner()).clone()
    }

    fn set_scene(&self, scene: Scene) {
        *self.scene.lock().unwrap_or_else(|p| p.into_inner()) = scene;
    }
}

/// An in-memory model handed over by Python: name, vertices, triangles, group.
type ModelArg<'py> = (
    String,
    PyReadonlyArray2<'py, f64>,
    PyReadonlyArray2<'py, u32>,
    String,
);

/// The preset named `name` (case-insensitive: anterior, posterior, left, right, superior,
/// inferior).
fn preset(name: &str) -> anyhow::Result<ViewPreset> {
    ViewPreset::ALL
        .into_iter()
        .find(|p| p.label().eq_ignore_ascii_case(name))
        .ok_or_else(|| {
            anyhow::anyhow!(
                "unknown view '{name}' (anterior, posterior, left, right, superior or inferior)"
            )
        })
}

fn risk_args(critical: Vec<String>) -> RiskArgs {
    RiskArgs {
        critical,
        risk_mm: None,
        no_risk: false,
    }
}

#[pymethods]
impl Session {
    /// Loads a `cutaway-session/2` (or `/1`) file, as every CLI command that takes a session does.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Session> {
        let scene = detached(py, || cutaway::session::load(&path))?;
        Ok(Session::new(scene, Some(path)))
    }

    /// A session from in-memory models and the session JSON that places them (`models[i].path`
    /// is `memory/<i>`; `cutters`, `camera` and the rest as a session file has them), read by the
    /// session reader. `view` frames the scene from a preset instead of the JSON's camera.
    #[staticmethod]
    #[pyo3(signature = (models, session_json, view=None))]
    fn from_parts(
        py: Python<'_>,
        models: Vec<ModelArg<'_>>,
        session_json: String,
        view: Option<String>,
    ) -> PyResult<Session> {
        let mut meshes = Vec::with_capacity(models.len());
        for (i, (name, v, t, group)) in models.into_iter().enumerate() {
            meshes.push((
                name,
                arrays::read_vertices(&v)?,
                arrays::read_triangles(&t)?,
                group,
                i,
            ));
        }
        let scene = detached(py, move || {
            let file = cutaway::session::parse(&session_json)?;
            let mut built = Vec::new();
            for (name, v, t, group, i) in meshes {
                let mesh = cutaway::io::mesh_from_arrays(&format!("model {i} ('{name}')"), v, t)?;
                built.push(Some(cutaway::io::Model {
                    name,
                    source: PathBuf::from(format!("memory/{i}")),
                    index: 0,
                    color: None,
                    group,
                    mesh: std::sync::Arc::new(mesh),
                }));
            }
            let mut load =
                |path: &Path, _unit: ModelUnit| -> anyhow::Result<Vec<cutaway::io::Model>> {
                    let i = path
                        .strip_prefix("memory")
                        .ok()
                        .and_then(|p| p.to_str())
                        .and_then(|p| p.parse::<usize>().ok())
                        .filter(|&i| i < built.len())
                        .ok_or_else(|| anyhow::anyhow!("{}: no such model", path.display()))?;
                    built[i]
                        .clone()
                        .map(|m| vec![m])
                        .ok_or_else(|| anyhow::anyhow!("{}: no such model", path.display()))
                };
            let mut scene = cutaway::session::scene_from_file(&file, Path::new(""), &mut load)?;
            // No file holds these meshes: a save writes them beside the session.
            for model in &mut scene.models {
                model.origin = MeshOrigin::Edited;
            }
            if let Some(view) = view {
                scene.camera = scene.preset_camera(preset(&view)?);
            }
            Ok(scene)
        })?;
        Ok(Session::new(scene, None))
    }

    /// The models' names, in order.
    #[getter]
    fn models(&self) -> Vec<String> {
        self.scene
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .models
            .iter()
            .map(|m| m.model.name.clone())
            .collect()
    }

    /// The number of cutters (of the active variant).
    #[getter]
    fn cutter_count(&self) -> usize {
        self.scene
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .cutters
            .len()
    }

    /// Frames the scene from a view preset (anterior, posterior, left, right, superior,
    /// inferior), as the window's view keys do.
    fn set_view(&self, py: Python<'_>, view: String) -> PyResult<()> {
        let mut scene = self.scene();
        let scene = detached(py, move || {
            scene.camera = scene.preset_camera(preset(&view)?);
            Ok(scene)
        })?;
        self.set_scene(scene);
        Ok(())
    }

    /// The measures of `cutaway metrics --json` (as its JSON text).
    #[pyo3(signature = (focus=None, critical=Vec::new(), samples=None))]
    fn metrics(
        &self,
        py: Python<'_>,
        focus: Option<String>,
        critical: Vec<String>,
        samples: Option<usize>,
    ) -> PyResult<String> {
        let scene = self.scene();
        let named = self.named();
        detached(py, move || {
            let mut options = MetricsOptions {
                focus,
                critical,
                ..MetricsOptions::default()
            };
            if let Some(samples) = samples {
                options.samples = samples;
            }
            Ok(serde_json::to_string(
                &measure(&scene, &options).map_err(named)?,
            )?)
        })
    }

    /// The picture of `cutaway render` as a `uint8 (h,w,4)` RGBA array, and the cutters' report
    /// (JSON text of `cutaway render --json`). A refused cut raises, as the command fails.
    #[pyo3(signature = (width=1280, height=800, labels=None, transparent=false, critical=Vec::new()))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: u32,
        height: u32,
        labels: Option<Vec<String>>,
        transparent: bool,
        critical: Vec<String>,
    ) -> PyResult<(Bound<'py, PyAny>, String)> {
        let mut scene = self.scene();
        let named = self.named();
        let (image, report) = detached(py, move || {
            for (what, v) in [("width", width), ("height", height)] {
                if !(1..=16384).contains(&v) {
                    anyhow::bail!("--{what} {v} is outside 1..16384");
                }
            }
            apply_risk(&mut scene, &risk_args(critical)).map_err(&named)?;
            let labelled = match &labels {
                Some(names) => {
                    Some(cutaway::annotate::labelled::chosen(&scene, names).map_err(&named)?)
                }
                None => None,
            };
            let mut options = RenderPngOptions::new(width, height);
            options.transparent_background = transparent;
            let mut renderer = HeadlessRenderer::new().map_err(&named)?;
            let picture =
                render_session_picture(&mut renderer, &scene, &options, labelled.as_deref())
                    .map_err(&named)?;
            if let Some(note) = &picture.refused {
                return Err(named(anyhow::anyhow!("{note}")));
            }
            let cutters: Vec<serde_json::Value> = picture
                .reports
                .iter()
                .map(|r| serde_json::json!({"exact": r.exact, "cut_ms": r.cut_ms}))
                .collect();
            let report = serde_json::json!({"cutters": cutters, "render_ms": picture.render_ms});
            Ok((picture.image, report.to_string()))
        })?;
        Ok((arrays::image(py, image)?, report))
    }

    /// Writes the cut scene as `cutaway export` does (`.glb` or `.html` by the extension);
    /// returns the JSON text of `cutaway export --json`.
    #[pyo3(signature = (path, title=None, focus=None, critical=Vec::new(), samples=None))]
    fn export(
        &self,
        py: Python<'_>,
        path: PathBuf,
        title: Option<String>,
        focus: Option<String>,
        critical: Vec<String>,
        samples: Option<usize>,
    ) -> PyResult<String> {
        let mut scene = self.scene();
        let named = self.named();
        detached(py, move || {
            let format = cutaway::export::scene_file::ExportFormat::of(&path)?;
            if format == cutaway::export::scene_file::ExportFormat::Glb
                && (title.is_some() || focus.is_some() || samples.is_some())
            {
                anyhow::bail!(
                    "{}: title, focus and samples apply to a web page (.html), not to .glb",
                    path.display()
                );
            }
            apply_risk(&mut scene, &risk_args(critical.clone())).map_err(named)?;
            let mut metrics = MetricsOptions {
                focus,
                critical,
                ..MetricsOptions::default()
            };
            if let Some(samples) = samples {
                metrics.samples = samples;
            }
            let page = WebPageOptions { title, metrics };
            Ok(serde_json::to_string(&export_scene_file(
                &scene, &path, &page,
            )?)?)
        })
    }

    /// Saves the session (`cutaway-session/2`, atomically; in-memory meshes are written beside
    /// it in `<stem>.meshes/`).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let scene = self.scene();
        detached(py, move || {
            let is_json = path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("json"));
            if !is_json {
                anyhow::bail!(
                    "{}: a session is written as .json, not as this extension",
                    path.display()
                );
            }
            cutaway::session::save(&path, &scene)
        })
    }

    /// Adds the cutters that open the camera's view onto `focus` (`cutaway expose`); returns
    /// the JSON text of `cutaway expose --json`.
    #[pyo3(signature = (focus, margin=None, samples=None))]
    fn expose(
        &self,
        py: Python<'_>,
        focus: String,
        margin: Option<f64>,
        samples: Option<usize>,
    ) -> PyResult<String> {
        let scene = self.scene();
        let named = self.named();
        let (after, report) = detached(py, move || {
            let mut settings = ExposeSettings::default();
            if let Some(margin) = margin {
                settings.margin_mm = margin;
            }
            let samples = samples.unwrap_or(cutaway::metrics::exposure::DEFAULT_SAMPLES);
            cutaway::expose::scene_expose::check(&settings, samples)?;
            let exposure = expose_named(&scene, &focus, &settings, samples).map_err(named)?;
            Ok((exposure.scene, serde_json::to_string(&exposure.report)?))
        })?;
        self.set_scene(after);
        Ok(report)
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Session>()?;
    Ok(())
}
