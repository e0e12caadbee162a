//! The session file of `../shared/CONTRACT.md`, saved and loaded exactly, in two versions:
//!
//! - `cutaway-session/2` (what Cutaway writes when the scene holds structures): a model is a
//!   **structure** (one mesh file, or one label of a segmentation volume, with all its regions),
//!   and a cutter's `target` indexes the models list, so a cutter cuts every region of its
//!   structure. An entry names `"structure": k` (0-based among the file's structures: 0 for a mesh
//!   file, ascending label value for a volume), or `"region": k` for a single connected region
//!   (a model kept from a `/1` session), or neither for every structure of the file. It also
//!   stores the structure's `name` and the model list's `group`.
//! - `cutaway-session/1`: a model is a **region**, as described below; such files keep loading
//!   with that meaning, and a scene made only of regions is saved as `/1` again.
//!
//! Rules shared by both:
//! - Model paths are written relative to the session file's folder and resolved against it on
//!   load (absolute paths are accepted and kept when no relative path exists).
//! - Regions count as models, in file order: an entry without `region` stands for every region of
//!   its file (each region becomes one model with the entry's colour, opacity, style and
//!   visibility), which is what a hand-written session or another tool writes. Cutaway itself adds
//!   `"region": k` (0-based) to every entry, so per-region colours survive a round trip.
//! - A model edited since it was loaded (scalpel strokes, a detached piece, Remove All Cut
//!   Geometry) is saved as a mesh file of its own next to the session, named with `"exact": true`
//!   (read verbatim, one model); see [`crate::session::meshes`].
//! - Unknown fields are ignored, never an error; missing optional fields take their defaults
//!   (colour: distinct colours, opacity 1, solid, visible, no cutters, a framing camera, default
//!   render settings).
//! - Saving is atomic: the JSON goes to a temporary file next to the target, then is renamed over
//!   it ([`crate::io::write_file`]), so a crash never leaves a half-written session; with its
//!   meshes folder it is replaced as a set (see [`crate::session::meshes`] for why the order of
//!   the writes is enough).
//! - Counts and sizes are bounded when the file is parsed ([`crate::session::limits`]), before
//!   anything is loaded or built.
//! - Every error is one line naming the session file and the problem.

pub mod cutters;
pub mod format;
pub mod image;
pub mod limits;
pub mod load;
pub mod meshes;
pub mod paths;
pub mod picks;
pub mod recovery;
pub mod risk;
pub mod rulers;
pub mod undo;
pub mod variants;
#[cfg(test)]
mod view_tests;
pub mod volumes;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context as _;
use cutter::Camera;
use glam::DVec3;

use crate::scene::{MeshOrigin, ModelStyle, ModelUnit, RenderSettings, Scene, SceneModel, Stereo};

pub use crate::session::format::*;
pub use crate::session::paths::relative_path;

/// Parses a session's text (no file access). Errors say what is wrong and where (line, column).
pub fn parse(text: &str) -> anyhow::Result<SessionFile> {
    let file: SessionFile =
        serde_json::from_str(text).map_err(|e| anyhow::anyhow!("not a valid session: {e}"))?;
    if file.format != FORMAT && file.format != FORMAT_V1 {
        anyhow::bail!(
            "format is {:?}, expected {FORMAT:?} or {FORMAT_V1:?}",
            file.format
        );
    }
    crate::session::limits::check(&file)?;
    Ok(file)
}

/// Reads the session at `path` and loads its models with [`crate::io::load_models`] (regions)
/// or [`crate::io::load_structures`]; model paths of the built-in example scenes
/// (`…/assets/<scene>/<part>.ply`) that do not exist on disk are served from the embedded
/// phantoms, so sessions saved from the examples open anywhere.
pub fn load(path: &Path) -> anyhow::Result<Scene> {
    load_with(path, crate::anatomy::assets::load_or_embedded_picking)
}

/// Loads one model file or folder as a list of models of one [`ModelUnit`]: its regions in file
/// order, or its structures.
pub type LoadModels<'a> = dyn FnMut(&Path, ModelUnit) -> anyhow::Result<Vec<crate::io::Model>> + 'a;

/// Reads the session at `path`, loading each model file with `load_models`. Errors name the
/// session file (or the model file that failed).
/// `load_models` also gets the positions of the structures the session picks from the file
/// (`None`: all of them, or regions); it may return just those, each with its position as
/// `index` (see [`crate::session::picks`]).
pub fn load_with(
    path: &Path,
    mut load_models: impl FnMut(
        &Path,
        ModelUnit,
        Option<&[usize]>,
    ) -> anyhow::Result<Vec<crate::io::Model>>,
) -> anyhow::Result<Scene> {
    let text = crate::io::bounded::read_text(path, crate::io::bounded::JSON_MAX_BYTES)
        .with_context(|| format!("{}", path.display()))?;
    let file = parse(&text).with_context(|| format!("{}", path.display()))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let picks = crate::session::picks::structure_picks(&file, folder);
    let mut load_picked = |source: &Path, unit: ModelUnit| {
        let only = match unit {
            ModelUnit::Structure => crate::session::picks::picks_of(&picks, source),
            ModelUnit::Region => None,
        };
        load_models(source, unit, only)
    };
    let scene = scene_from_file(&file, folder, &mut load_picked)
        .with_context(|| format!("{}", path.display()))?;
    Ok(scene)
}

/// Builds the scene a parsed session describes; model paths are resolved against `folder`.
pub fn scene_from_file(
    file: &SessionFile,
    folder: &Path,
    load_models: &mut LoadModels,
) -> anyhow::Result<Scene> {
    let mut scene = Scene::default();
    let structures_format = file.format != FORMAT_V1;
    // Files loaded once per unit, however many entries name them.
    let mut loaded: Vec<(PathBuf, ModelUnit, Vec<crate::io::Model>)> = Vec::new();
    for (i, entry) in file.models.iter().enumerate() {
        let source = folder.join(&entry.path);
        let unit = if !structures_format || entry.region.is_some() {
            ModelUnit::Region
        } else {
            ModelUnit::Structure
        };
        if structures_format && !entry.exact && entry.region.is_some() && entry.structure.is_some()
        {
            anyhow::bail!("model {i}: names both a region and a structure; give one of them");
        }
        let exact_model: Vec<crate::io::Model>;
        // The incision walls an exact mesh file marks (a scalpel-cut model saved with them).
        let mut exact_walls = Vec::new();
        let regions = if entry.exact {
            let stem = entry.path.file_stem().unwrap_or_default().to_string_lossy();
            let (mesh, walls) = crate::io::read_mesh_verbatim_walls(&source)?;
            exact_walls = walls;
            exact_model = vec![crate::io::Model {
                source: source.clone(),
                group: entry.group.clone().unwrap_or_default(),
                ..crate::io::Model::part(
                    entry.name.clone().unwrap_or_else(|| stem.into_owned()),
                    None,
                    mesh,
                )
            }];
            &exact_model
        } else {
            let slot = match loaded
                .iter()
                .position(|(p, u, _)| *p == source && *u == unit)
            {
                Some(k) => k,
                None => {
                    let models = load_models(&source, unit)?;
                    loaded.push((source.clone(), unit, models));
                    loaded.len() - 1
                }
            };
            &loaded[slot].2
        };
        let style = match entry.style.as_str() {
            "solid" => ModelStyle::Solid,
            "wireframe" => ModelStyle::Wireframe,
            other => {
                anyhow::bail!("model {i}: style {other:?} is neither \"solid\" nor \"wireframe\"")
            }
        };
        let (picked_index, what) = match unit {
            ModelUnit::Region => (entry.region, "region"),
            ModelUnit::Structure => (entry.structure, "structure"),
        };
        let picked: Vec<(usize, &crate::io::Model)> = match picked_index {
            Some(r) => match crate::session::picks::at_position(regions, r) {
                Some(m) => vec![(r, m)],
                None => anyhow::bail!(
                    "model {i}: {what} {r} of {} does not exist (it has {} {what}s)",
                    entry.path.display(),
                    regions.len()
                ),
            },
            None => regions.iter().enumerate().collect(),
        };
        for (region, model) in picked {
            let index = scene.models.len();
            let color = entry.color.unwrap_or_else(|| match unit {
                ModelUnit::Region => crate::anatomy::colors::distinct_colors(index + 1)[index],
                ModelUnit::Structure => {
                    crate::anatomy::colors::structure_color(&model.name, model.color, index)
                }
            });
            // The entry's name wins (a region the session names keeps that name, unnumbered);
            // an entry standing for several regions numbers them after it.
            let name = match (&entry.name, entry.exact) {
                (Some(name), false) => entry_name(name, unit, picked_index, region, regions.len()),
                _ => model.name.clone(),
            };
            let group = match (&entry.group, structures_format) {
                (Some(group), true) => group.clone(),
                _ => model.group.clone(),
            };
            let mesh = Arc::clone(&model.mesh);
            let walls = crate::scene::wall_faces::WallFaces::new(&mesh, exact_walls.clone());
            scene.models.push(SceneModel {
                model: crate::io::Model {
                    name,
                    color: model.color,
                    mesh,
                    source: model.source.clone(),
                    index: region,
                    group,
                },
                unit: if entry.exact && structures_format {
                    ModelUnit::Structure
                } else {
                    unit
                },
                origin: if entry.exact {
                    MeshOrigin::Exact
                } else {
                    MeshOrigin::Region
                },
                color,
                opacity: entry.opacity,
                style,
                visible: entry.visible,
                walls,
            });
        }
    }
    for (i, c) in file.cutters.iter().enumerate() {
        scene.cutters.push(cutter_from_entry(i, c)?);
    }
    scene.unit = crate::scene::LengthUnit::guess(&scene.bbox(), false);
    scene.orientation = match file.orientation {
        Some(o) => crate::scene::Orientation::checked(
            DVec3::from_array(o.superior),
            DVec3::from_array(o.anterior),
        )
        .ok_or_else(|| {
            anyhow::anyhow!("orientation: superior and anterior must be orthogonal unit vectors")
        })?,
        None => crate::scene::Orientation::guess(&scene.bbox(), false),
    };
    scene.variants = crate::session::variants::from_entries(&file.variants, file.active_variant)?;
    scene.rulers = crate::session::rulers::from_entries(&file.rulers)?;
    scene.camera = match file.camera {
        Some(c) => Camera {
            eye: DVec3::from_array(c.eye),
            target: DVec3::from_array(c.target),
            up: DVec3::from_array(c.up),
            fov_y_deg: c.fov_y_deg,
        },
        None => scene.framing_camera(),
    };
    if let Some(r) = &file.render {
        scene.render = RenderSettings {
            background: r.background,
            antialias: r.antialias,
            stereo: Stereo::parse(&r.stereo).ok_or_else(|| {
                anyhow::anyhow!(
                    "render: stereo {:?} is neither \"none\" nor \"anaglyph\"",
                    r.stereo
                )
            })?,
        };
    }
    if let Some(entry) = &file.image {
        scene.image = Some(crate::session::image::load(entry, folder, &scene)?);
    }
    if let Some(entry) = &file.risk {
        scene.risk = crate::session::risk::load(entry, &scene).context("risk")?;
    }
    scene.sanity_check().map_err(anyhow::Error::msg)?;
    Ok(scene)
}

/// The name of the model an entry named `name` gives for its region `region` of a file with
/// `regions` regions: the name itself, numbered from 1 only when a region entry stands for
/// several regions (no `region` picked, several in the file). A structure entry's name is the
/// structure's, as it always was.
fn entry_name(
    name: &str,
    unit: ModelUnit,
    picked: Option<usize>,
    region: usize,
    regions: usize,
) -> String {
    if unit == ModelUnit::Region && picked.is_none() && regions > 1 {
        format!("{name} {}", region + 1)
    } else {
        name.to_string()
    }
}

/// The session file describing `scene`, model paths relative to `folder` (the session file's
/// folder) where possible: `cutaway-session/2` when any model is a structure, else
/// `cutaway-session/1` (a scene made only of regions, as loaded from a `/1` file, keeps its
/// format).
pub fn file_from_scene(scene: &Scene, folder: &Path) -> SessionFile {
    let structures_format = scene.models.iter().any(|m| m.unit == ModelUnit::Structure);
    let models = scene
        .models
        .iter()
        .map(|m| ModelEntry {
            path: relative_path(&m.model.source, folder),
            region: (m.unit == ModelUnit::Region).then_some(m.model.index),
            structure: (m.unit == ModelUnit::Structure).then_some(m.model.index),
            group: (structures_format && !m.model.group.is_empty()).then(|| m.model.group.clone()),
            color: Some(m.color),
            opacity: m.opacity,
            style: match m.style {
                ModelStyle::Solid => "solid",
                ModelStyle::Wireframe => "wireframe",
            }
            .to_string(),
            visible: m.visible,
            exact: false,
            name: Some(m.model.name.clone()),
        })
        .collect();
    let cutters = scene.cutters.iter().map(cutter_entry).collect();
    let (variants, active_variant) = crate::session::variants::entries(scene);
    let c = scene.camera;
    SessionFile {
        format: if structures_format { FORMAT } else { FORMAT_V1 }.to_string(),
        models,
        cutters,
        camera: Some(CameraEntry {
            eye: c.eye.to_array(),
            target: c.target.to_array(),
            up: c.up.to_array(),
            fov_y_deg: c.fov_y_deg,
        }),
        render: Some(RenderEntry {
            background: scene.render.background,
            antialias: scene.render.antialias,
            stereo: scene.render.stereo.as_str().to_string(),
        }),
        orientation: Some(OrientationEntry {
            superior: scene.orientation.superior.to_array(),
            anterior: scene.orientation.anterior.to_array(),
        }),
        image: scene
            .image
            .as_ref()
            .map(|layer| crate::session::image::entry(layer, folder)),
        variants,
        active_variant,
        rulers: crate::session::rulers::entries(&scene.rulers),
        risk: crate::session::risk::entry(&scene.risk),
    }
}

/// Saves `scene` to `path` atomically (temporary file in the same folder, then rename). Models
/// whose mesh no file holds (edited since loaded) are written next to the session first, and the
/// mesh files the new session no longer names are removed after it is in place
/// ([`crate::session::meshes`]).
pub fn save(path: &Path, scene: &Scene) -> anyhow::Result<()> {
    let folder = path.parent().unwrap_or(Path::new(""));
    let meshes = crate::session::meshes::write_meshes(path, scene)
        .with_context(|| format!("{}", path.display()))?;
    let mut file = file_from_scene(scene, folder);
    point_entries(&mut file, scene, &meshes, folder);
    let mut text =
        serde_json::to_string_pretty(&file).with_context(|| format!("{}", path.display()))?;
    text.push('\n');
    crate::io::write_file(path, text.as_bytes())?;
    crate::session::meshes::remove_stale(path, &meshes);
    Ok(())
}

/// Points the entries of models with a mesh file of their own (from [`crate::session::meshes::write_meshes`]) at that
/// file: path relative to `folder` (the session's folder), `exact`, region 0, the model's name.
fn point_entries(
    file: &mut SessionFile,
    scene: &Scene,
    written: &[Option<PathBuf>],
    folder: &Path,
) {
    for ((entry, model), path) in file.models.iter_mut().zip(&scene.models).zip(written) {
        if let Some(path) = path {
            entry.path = relative_path(path, folder);
            entry.region = Some(0);
            entry.structure = None;
            entry.exact = true;
            entry.name = Some(model.model.name.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths() {
        assert_eq!(
            relative_path(Path::new("/a/b/c.obj"), Path::new("/a/d")),
            PathBuf::from("../b/c.obj")
        );
        assert_eq!(
            relative_path(Path::new("/a/b/c.obj"), Path::new("/a/b")),
            PathBuf::from("c.obj")
        );
        assert_eq!(
            relative_path(Path::new("/a/./b/../c.obj"), Path::new("/a")),
            PathBuf::from("c.obj")
        );
    }

    #[test]
    fn contract_example_parses_with_defaults() {
        let text = r#"{
          "format": "cutaway-session/1",
          "models": [{"path": "knee.obj", "color": [0.9, 0.7, 0.6], "opacity": 1.0, "style": "solid", "visible": true}],
          "cutters": [{"target": 0, "kind": "curving", "smooth": false,
                       "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                       "views": {"cut": true, "transparency": 0.25, "ribbons": {"count": 5, "width": 2.0}, "slices": null}}],
          "camera": {"eye": [0, -300, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 30},
          "render": {"background": [1, 1, 1, 1], "antialias": true, "stereo": "none"},
          "some_future_field": {"x": 1}
        }"#;
        let file = parse(text).unwrap();
        assert_eq!(file.models[0].region, None);
        assert_eq!(
            file.cutters[0].views.ribbons,
            Some(SubCutterEntry {
                count: 5,
                width: 2.0,
                placement: "even".into(),
                relative: false,
            })
        );
        assert_eq!(file.cutters[0].views.transparency, Some(0.25));
        let err = parse(&text.replace("cutaway-session/1", "cutaway-session/9")).unwrap_err();
        assert!(format!("{err}").contains("cutaway-session/9"));
        let err = parse("{\"format\": \"cutaway-session/1\", \"models\": [").unwrap_err();
        assert!(format!("{err}").contains("line"), "{err}");
    }

    /// A loader that serves one file, `pair.obj`: two regions as models, or one structure
    /// holding both.
    fn pair_loader(path: &Path, unit: ModelUnit) -> anyhow::Result<Vec<crate::io::Model>> {
        anyhow::ensure!(
            path.ends_with("pair.obj"),
            "{}: no such file",
            path.display()
        );
        let sphere = |x: f64| {
            let mut m = csg::testkit::icosphere(1, 1.0);
            for p in &mut m.positions {
                p.x += x;
            }
            m
        };
        let model = |name: &str, index: usize, mesh: csg::Mesh| crate::io::Model {
            name: name.to_string(),
            source: path.to_path_buf(),
            index,
            color: None,
            group: String::new(),
            mesh: mesh.into(),
        };
        Ok(match unit {
            ModelUnit::Region => vec![
                model("pair 1", 0, sphere(0.0)),
                model("pair 2", 1, sphere(3.0)),
            ],
            ModelUnit::Structure => {
                let mut both = sphere(0.0);
                both.append(&sphere(3.0));
                vec![model("pair", 0, both)]
            }
        })
    }

    fn session(format: &str, models: &str, target: usize) -> SessionFile {
        parse(&format!(
            r#"{{"format": "{format}", "models": {models},
                "cutters": [{{"target": {target}, "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]]}}]}}"#
        ))
        .unwrap()
    }

    #[test]
    fn version_1_models_are_regions_and_version_2_models_are_structures() {
        let folder = Path::new("/s");
        let v1 = session(FORMAT_V1, r#"[{"path": "pair.obj"}]"#, 1);
        let scene = scene_from_file(&v1, folder, &mut pair_loader).unwrap();
        assert_eq!(scene.models.len(), 2, "v1: one model per region");
        assert!(scene.models.iter().all(|m| m.unit == ModelUnit::Region));
        assert_eq!(
            (scene.models[1].model.index, scene.cutters[0].target),
            (1, 1)
        );

        let v2 = session(FORMAT, r#"[{"path": "pair.obj"}]"#, 0);
        let scene = scene_from_file(&v2, folder, &mut pair_loader).unwrap();
        assert_eq!(scene.models.len(), 1, "v2: one model per structure");
        assert_eq!(scene.models[0].unit, ModelUnit::Structure);
        assert_eq!(scene.models[0].model.mesh.triangle_count(), 2 * 80);
        // The structure's colour comes from the palette (no anatomical name, no file colour).
        assert_eq!(
            scene.models[0].color,
            crate::anatomy::colors::distinct_colors(1)[0]
        );
        let err = scene_from_file(
            &session(FORMAT, r#"[{"path": "pair.obj"}]"#, 1),
            folder,
            &mut pair_loader,
        )
        .unwrap_err();
        assert!(format!("{err}").contains("target 1"), "{err}");

        // v2 may keep a single region (a model carried over from a v1 session).
        let mixed = session(
            FORMAT,
            r#"[{"path": "pair.obj", "structure": 0, "name": "both", "group": "g/h"}, {"path": "pair.obj", "region": 1}]"#,
            1,
        );
        let scene = scene_from_file(&mixed, folder, &mut pair_loader).unwrap();
        assert_eq!(
            scene
                .models
                .iter()
                .map(|m| (m.model.name.as_str(), m.model.group.as_str(), m.unit))
                .collect::<Vec<_>>(),
            [
                ("both", "g/h", ModelUnit::Structure),
                ("pair 2", "", ModelUnit::Region)
            ]
        );
        let both = session(
            FORMAT,
            r#"[{"path": "pair.obj", "structure": 0, "region": 0}]"#,
            0,
        );
        let err = scene_from_file(&both, folder, &mut pair_loader).unwrap_err();
        assert!(
            format!("{err}").contains("both a region and a structure"),
            "{err}"
        );
        let missing = session(FORMAT, r#"[{"path": "pair.obj", "structure": 3}]"#, 0);
        let err = scene_from_file(&missing, folder, &mut pair_loader).unwrap_err();
        assert!(format!("{err}").contains("structure 3"), "{err}");
    }

    #[test]
    fn saving_writes_version_2_for_structures_and_version_1_for_regions_only() {
        let folder = Path::new("/s");
        let mixed = session(
            FORMAT,
            r#"[{"path": "pair.obj", "structure": 0, "group": "g"}, {"path": "pair.obj", "region": 1}]"#,
            0,
        );
        let scene = scene_from_file(&mixed, folder, &mut pair_loader).unwrap();
        let file = file_from_scene(&scene, folder);
        assert_eq!(file.format, FORMAT);
        let entries: Vec<_> = file
            .models
            .iter()
            .map(|m| (m.structure, m.region, m.name.as_deref(), m.group.as_deref()))
            .collect();
        assert_eq!(
            entries,
            [
                (Some(0), None, Some("pair"), Some("g")),
                // A region is saved with its name, so a name a session gave it survives.
                (None, Some(1), Some("pair 2"), None)
            ]
        );
        let back = scene_from_file(&file, folder, &mut pair_loader).unwrap();
        assert_eq!(back.models.len(), 2);
        assert_eq!(back.models[0].model.group, "g");
        assert_eq!(back.cutters, scene.cutters);

        let v1 = session(FORMAT_V1, r#"[{"path": "pair.obj"}]"#, 1);
        let scene = scene_from_file(&v1, folder, &mut pair_loader).unwrap();
        let file = file_from_scene(&scene, folder);
        assert_eq!(
            file.format, FORMAT_V1,
            "a scene of regions keeps its format"
        );
        assert!(file.models.iter().all(|m| m.structure.is_none()));
        let names: Vec<_> = file.models.iter().map(|m| m.name.as_deref()).collect();
        assert_eq!(names, [Some("pair 1"), Some("pair 2")]);
    }

    #[test]
    fn a_session_names_its_region_models_and_numbers_only_several() {
        let folder = Path::new("/s");
        // `pair.obj` holds two regions, `one.obj` (the first of them alone) one.
        let mut loader = |path: &Path, unit: ModelUnit| {
            if !path.ends_with("one.obj") {
                return pair_loader(path, unit);
            }
            let mut models = pair_loader(&path.with_file_name("pair.obj"), unit)?;
            models.truncate(1);
            models[0].name = "one".into();
            Ok(models)
        };
        let v1 = session(
            FORMAT_V1,
            r#"[{"path": "one.obj", "name": "organ"}, {"path": "pair.obj", "name": "kidney"}, {"path": "pair.obj"}]"#,
            0,
        );
        let scene = scene_from_file(&v1, folder, &mut loader).unwrap();
        let names: Vec<&str> = scene.models.iter().map(|m| m.model.name.as_str()).collect();
        assert_eq!(names, ["organ", "kidney 1", "kidney 2", "pair 1", "pair 2"]);
        // Picked by `region`, the name is the region's as given.
        let v2 = session(
            FORMAT,
            r#"[{"path": "pair.obj", "region": 1, "name": "left kidney"}]"#,
            0,
        );
        let scene = scene_from_file(&v2, folder, &mut loader).unwrap();
        assert_eq!(scene.models[0].model.name, "left kidney");
        // Saved and read back, the names stay.
        let back = scene_from_file(&file_from_scene(&scene, folder), folder, &mut loader).unwrap();
        assert_eq!(back.models[0].model.name, "left kidney");
    }

    #[test]
    fn ribbon_placement_and_relative_width_round_trip() {
        let text = r#"{
          "format": "cutaway-session/1",
          "models": [],
          "cutters": [{"target": 0, "kind": "curving", "smooth": true,
                       "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]]],
                       "views": {"cut": true,
                                 "ribbons": {"count": 4, "width": 0.3, "placement": "horizontal", "relative": true},
                                 "slices": {"count": 2, "width": 1.5, "placement": "planes"}}}]
        }"#;
        let file = parse(text).unwrap();
        let views = &file.cutters[0].views;
        let ribbons = views.ribbons.as_ref().unwrap();
        assert_eq!(
            (ribbons.placement.as_str(), ribbons.relative),
            ("horizontal", true)
        );
        let slices = views.slices.as_ref().unwrap();
        assert_eq!(
            (slices.placement.as_str(), slices.relative),
            ("planes", false)
        );
        let back: SessionFile =
            serde_json::from_str(&serde_json::to_string(&file).unwrap()).unwrap();
        assert_eq!(back.cutters[0].views, file.cutters[0].views);
        let bad = text.replace("\"planes\"}", "\"diagonal\"}");
        let err = scene_from_file(&parse(&bad).unwrap(), Path::new("."), &mut |_, _| {
            Ok(Vec::new())
        })
        .map(|_| ())
        .unwrap_err();
        assert!(format!("{err:#}").contains("diagonal"), "{err:#}");
    }
}
