//! The window's background work: what each job starts with, and how its result lands in the
//! scene once it finishes.
//!
//! Loads, index builds, cuts and exports run on worker threads ([`crate::gui::jobs`]) so a frame never
//! waits for them; every job ends as one [`JobOutput`] that [`CutawayApp::poll_jobs`] hands to
//! `finish_job` on the UI thread, the only place a finished job changes the window's state.

use std::path::{Path, PathBuf};

use crate::scene::open::{file_label, load_paths};

use crate::gui::app::{CutawayApp, is_session_path, new_scene, triangle_count};
use crate::gui::job_output::JobOutput;
use crate::gui::jobs::{self, Job, Progress};

impl CutawayApp {
    pub(super) fn spawn(
        &mut self,
        ctx: &egui::Context,
        label: impl Into<String>,
        work: impl FnOnce(&Progress) -> anyhow::Result<JobOutput> + Send + 'static,
    ) {
        let ctx = ctx.clone();
        self.state
            .jobs
            .push(Job::spawn(label, move || ctx.request_repaint(), work));
    }

    /// The skin at once (milliseconds), the atlas's labels from a background job.
    pub(super) fn load_default_scene(&mut self, ctx: &egui::Context) {
        match crate::anatomy::default_scene::load_skin() {
            Ok(skin) => self.add_models(skin, true, &[]),
            Err(e) => return self.state.complain(&e),
        }
        self.state.atlas.start(ctx);
    }

    pub(super) fn load_example(&mut self, ctx: &egui::Context, name: String) {
        if name == crate::anatomy::default_scene::NAME {
            return self.load_default_scene(ctx);
        }
        self.spawn(
            ctx,
            format!("Loading the {name} example"),
            move |progress| {
                let models = crate::anatomy::examples::example_models(&name, progress)?;
                Ok(JobOutput::Models {
                    models,
                    replace: true,
                    sources: Vec::new(),
                    image: None,
                })
            },
        );
    }

    pub(super) fn remove_all_cut_geometry(&mut self, ctx: &egui::Context) {
        if self.state.scene.cutters.is_empty() {
            self.state.say("There are no cutters to apply");
            return;
        }
        let scene = self.state.scene.clone();
        let key = crate::cutting::scene_cuts::PreviewKey::of(&scene);
        self.spawn(ctx, "Removing all cut geometry", move |progress| {
            let meshes = crate::cutting::scene_cuts::apply_all_cuts(&scene, progress)?;
            Ok(JobOutput::CutsApplied { meshes, key })
        });
    }

    /// Starts building the spatial index of model `target` in the background (big targets).
    pub fn start_index_job(&mut self, ctx: &egui::Context, target: usize) {
        let Some(model) = self.state.scene.models.get(target) else {
            return;
        };
        if self
            .state
            .jobs
            .iter()
            .any(|j| j.label.starts_with("Indexing"))
        {
            return;
        }
        let mesh = model.model.mesh.clone();
        let name = model.model.name.clone();
        // A held drag's own message says more (that the drag is kept).
        if self.state.viewport.held.is_none() {
            self.state.say(format!("Indexing {name} for editing…"));
        }
        self.spawn(ctx, format!("Indexing {name}"), move |progress| {
            progress.set_message(format!(
                "{} triangles",
                crate::gui::panels::status_bar::grouped(mesh.triangle_count())
            ));
            let (weak, index) = crate::cutting::editing::build_index(&mesh, progress)?;
            Ok(JobOutput::Index {
                model: target,
                mesh: weak,
                index,
            })
        });
    }

    /// Opens files: a session replaces everything; meshes and directories load in the background.
    pub(super) fn open_paths(&mut self, ctx: &egui::Context, paths: Vec<PathBuf>, replace: bool) {
        if paths.is_empty() {
            return;
        }
        if paths.len() == 1 && is_session_path(&paths[0]) {
            let path = paths[0].clone();
            self.load_session(ctx, &path);
            return;
        }
        for p in &paths {
            self.state.recent.add(p);
        }
        if crate::scene::open::is_one_mask_folder(&paths) {
            let folder = paths[0].clone();
            if replace {
                crate::gui::folder_arrival::start(&mut self.state, ctx, folder);
            } else {
                crate::gui::folder_arrival::start_adding(&mut self.state, ctx, folder);
            }
            return;
        }
        let label = match paths.as_slice() {
            [one] => format!("Loading {}", file_label(one)),
            many => format!("Loading {} items", many.len()),
        };
        let sources = paths.clone();
        self.spawn(ctx, label, move |progress| {
            let (models, image) = load_paths(&paths, progress)?;
            Ok(JobOutput::Models {
                models,
                replace,
                sources,
                image,
            })
        });
    }

    pub(super) fn finish_job(&mut self, ctx: &egui::Context, output: JobOutput) {
        match output {
            JobOutput::Picked {
                purpose,
                paths,
                took,
            } => {
                // A dialog that "closes" within a blink never opened: no portal and no zenity.
                if paths.is_empty() && took < std::time::Duration::from_millis(150) {
                    self.state.browser = Some(crate::gui::panels::file_browser::FileBrowser::new(
                        purpose,
                        self.last_file(),
                    ));
                    self.state
                        .say("No native file dialog opened; choose in the window's browser");
                } else {
                    self.picked(ctx, purpose, paths);
                }
            }
            JobOutput::Models {
                models,
                replace,
                sources,
                image,
            } => {
                let image = image
                    .or_else(|| crate::gui::panels::image_panel::image_kept(&self.state, replace));
                self.add_models(models, replace, &sources);
                if let Some(layer) = image {
                    crate::gui::panels::image_panel::image_loaded(&mut self.state, layer);
                }
            }
            JobOutput::Session { path, scene } => {
                self.state.atlas.cancel();
                self.state.folder.cancel();
                self.state.scene = *scene;
                // A restored autosave has no file of its own: Save asks where to put it.
                let restored = path == self.state.recovery.session_path();
                self.state.session_path = (!restored).then(|| path.clone());
                self.state.selected_model = None;
                self.state.selected_cutter = 0;
                self.state.history.clear();
                self.state.viewport.reset_editor();
                self.state.last_committed = self.state.scene.clone();
                self.state.recovery.mark_dirty();
                // A restored autosave holds work nobody saved: replacing it asks first.
                if !restored {
                    self.state.recovery.mark_saved();
                    self.state.recent.add(&path);
                }
                self.state.say(format!(
                    "Opened {}: {} models, {} cutters",
                    path.display(),
                    self.state.scene.models.len(),
                    self.state.scene.cutters.len()
                ));
            }
            JobOutput::Image(layer) => {
                crate::gui::panels::image_panel::image_loaded(&mut self.state, layer)
            }
            JobOutput::Index { model, mesh, index } => {
                self.state.viewport.editor.store_index(mesh, index);
                // A drag held while it was built is replayed at the next frame.
                self.state.say(format!(
                    "{} is ready for cutting",
                    self.state
                        .scene
                        .models
                        .get(model)
                        .map(|m| m.model.name.as_str())
                        .unwrap_or("the target")
                ));
            }
            JobOutput::Preview { geometry, key, ms } => {
                if key == crate::cutting::scene_cuts::PreviewKey::of(&self.state.scene) {
                    self.state.status.last_cut_ms = Some(ms);
                    self.state.status.cut_triangles = geometry.triangle_count();
                    self.state.viewport.preview = Some(geometry);
                    self.state.viewport.preview_key = Some(key);
                }
            }
            JobOutput::CutsApplied { meshes, key } => {
                if key != crate::cutting::scene_cuts::PreviewKey::of(&self.state.scene) {
                    self.state.say("The cutters changed while cutting; Remove All Cut Geometry was not applied");
                    return;
                }
                let before = self.state.scene.clone();
                let count = meshes.len();
                for (i, mesh) in meshes {
                    if let Some(m) = self.state.scene.models.get_mut(i) {
                        m.replace_mesh(mesh);
                    }
                }
                self.state.scene.cutters.clear();
                self.state.viewport.editor.finish();
                self.state.viewport.preview = None;
                self.state.viewport.preview_key = None;
                self.state.record("remove all cut geometry", before);
                self.state.say(format!(
                    "Applied the cuts to {count} models; new cuts reach the structures behind"
                ));
            }
            JobOutput::Exposed {
                key,
                exposed,
                removed_mm3,
            } => self.finish_expose(key, &exposed, removed_mm3),
            JobOutput::Done(message) => self.state.say(message),
        }
    }

    pub(super) fn add_models(
        &mut self,
        models: Vec<crate::io::Model>,
        replace: bool,
        sources: &[PathBuf],
    ) {
        let before = self.state.scene.clone();
        if replace {
            self.state.atlas.cancel();
            self.state.folder.cancel();
            let render = self.state.scene.render;
            self.state.scene = new_scene();
            self.state.scene.render = render;
            self.state.session_path = None;
            self.state.selected_model = None;
            self.state.history.clear();
            self.state.viewport.reset_editor();
        }
        let first_new = self.state.scene.models.len();
        let count = models.len();
        let default_scene = crate::anatomy::default_scene::is_default_scene(&models);
        let from_volume = sources.iter().any(|p| crate::io::volume::is_volume(p));
        let added = crate::scene::open::structures(models, first_new);
        self.state.scene.models.extend(added);
        if replace {
            crate::gui::viewport::view_menu::orient_new_scene(
                &mut self.state,
                default_scene,
                from_volume,
            );
            self.state.last_committed = self.state.scene.clone();
            self.state.recovery.mark_dirty();
            self.state.recovery.mark_saved();
        } else {
            self.state.record(&format!("add {count} models"), before);
        }
        let what = match sources {
            [] => "the example scene".to_string(),
            [one] => file_label(one),
            many => format!("{} items", many.len()),
        };
        self.state.say(format!(
            "Loaded {what}: {count} models, {} triangles",
            crate::gui::panels::status_bar::grouped(triangle_count(&self.state.scene))
        ));
    }

    pub(super) fn save_session(&mut self, path: &Path) -> anyhow::Result<()> {
        crate::gui::bridge::save_session(&self.state, path)
    }

    pub(super) fn load_session(&mut self, ctx: &egui::Context, path: &Path) {
        let path = path.to_path_buf();
        self.spawn(
            ctx,
            format!("Opening {}", file_label(&path)),
            move |progress| {
                let scene = crate::session::load::load_with_progress(&path, progress)?;
                Ok(JobOutput::Session {
                    path,
                    scene: Box::new(scene),
                })
            },
        );
    }

    pub(super) fn export_image_to(&mut self, ctx: &egui::Context, path: PathBuf) {
        let scene = self.state.scene.clone();
        // Camera and Scalpel modes show the cut too: the picture shows it as well.
        let preview = crate::gui::viewport::cut_view::shows_cut(self.state.mode)
            && !self.state.scene.cutters.is_empty();
        let settings = self.state.export_image.clone();
        self.spawn(
            ctx,
            format!("Exporting {}×{} image", settings.width, settings.height),
            move |progress| {
                progress.set_message(file_label(&path));
                Ok(JobOutput::Done(crate::gui::bridge::export_image(
                    &scene, preview, &settings, &path,
                )?))
            },
        );
    }

    pub(super) fn export_meshes_to(&mut self, ctx: &egui::Context, dir: PathBuf) {
        let scene = self.state.scene.clone();
        let settings = self.state.export_meshes.clone();
        self.spawn(ctx, "Exporting cut meshes", move |progress| {
            let parts = crate::export::meshes::CutMeshParts {
                kept: settings.kept,
                walls: settings.walls,
                removed: settings.removed,
            };
            let extension = settings.format.extension();
            let files =
                crate::export::meshes::write_cut_meshes(&scene, parts, extension, &dir, progress)?;
            Ok(JobOutput::Done(format!(
                "Exported {} meshes to {}",
                files.len(),
                dir.display()
            )))
        });
    }

    pub(super) fn export_turntable_to(&mut self, ctx: &egui::Context, dir: PathBuf) {
        let scene = self.state.scene.clone();
        let preview = crate::gui::viewport::cut_view::shows_cut(self.state.mode)
            && !self.state.scene.cutters.is_empty();
        let settings = self.state.export_turntable.clone();
        let label = format!(
            "Exporting a turntable of {} frames",
            settings.options.frames
        );
        self.spawn(ctx, label, move |progress| {
            let message = crate::gui::panels::turntable_export::export(
                &scene, preview, &settings, &dir, progress,
            )?;
            Ok(JobOutput::Done(message))
        });
    }

    pub(super) fn export_webpage_to(&mut self, ctx: &egui::Context, path: PathBuf) {
        let scene = self.state.scene.clone();
        let settings = self.state.export_webpage.clone();
        let metrics = self.state.metrics.options();
        self.spawn(ctx, "Exporting a web page", move |progress| {
            let message = crate::gui::panels::webpage_export::export(
                &scene, &settings, metrics, &path, progress,
            )?;
            Ok(JobOutput::Done(message))
        });
    }

    /// In Preview, recompute the cut parts whenever the cutters or their targets changed.
    /// Elsewhere (Edit mode) a preview the cutters no longer match is dropped: nothing draws
    /// it, and it holds every cut model's kept part and walls.
    pub(super) fn update_preview(&mut self, ctx: &egui::Context) {
        let key = crate::cutting::scene_cuts::PreviewKey::of(&self.state.scene);
        if !crate::gui::viewport::cut_view::shows_cut(self.state.mode)
            || self.state.scene.cutters.is_empty()
        {
            if self.state.viewport.preview_key.as_ref() != Some(&key) {
                self.state.viewport.preview = None;
                self.state.viewport.preview_key = None;
            }
            return;
        }
        if self.state.viewport.preview_key.as_ref() == Some(&key)
            || self.state.jobs.iter().any(|j| j.label == PREVIEW_JOB)
        {
            return;
        }
        let scene = self.state.scene.clone();
        self.spawn(ctx, PREVIEW_JOB, move |_| {
            let (geometry, ms) = crate::cutting::scene_cuts::compute_preview(&scene);
            Ok(JobOutput::Preview { geometry, key, ms })
        });
    }

    pub(super) fn poll_jobs(&mut self, ctx: &egui::Context) {
        let mut finished = Vec::new();
        for job in &mut self.state.jobs {
            if let Some(result) = job.poll() {
                finished.push((job.label.clone(), result));
            }
        }
        self.state.jobs.retain(Job::is_running);
        for (label, result) in finished {
            match result {
                Ok(output) => self.finish_job(ctx, output),
                Err(e) if jobs::is_cancelled(&e) => self.state.say(format!("{label}: cancelled")),
                Err(e) => self.state.complain(&e),
            }
        }
    }
}

const PREVIEW_JOB: &str = "Cutting (Preview)";
