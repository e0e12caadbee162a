//! Sessions that hold meshes no file on disk has: scalpel strokes, detached loop pieces and
//! Remove All Cut Geometry replace a model's mesh, so naming the file it was loaded from would
//! reload the uncut geometry (and a detached piece as a copy of its parent's region).
//!
//! ## What a save writes
//! Every model whose [`MeshOrigin`] is not `Region` (edited since loaded, or itself read from
//! such a file) is written as binary PLY (`double` coordinates: an exact `f64` round trip) into
//! `<session stem>.meshes/` next to the session, and its session entry names that file with
//! `"exact": true` and `"region": 0` (plus the model's `"name"`). Loading an exact entry reads the
//! file verbatim ([`crate::io::read_mesh_verbatim`]: no welding, no region split), so the model
//! comes back bit for bit, as one model, whatever its topology. The scalpel's incision walls
//! are marked in the file (the PLY face property `cutaway_wall`, see `crate::io::ply`) and come
//! back with it. Other tools that ignore `exact` (and the property) still find an ordinary mesh
//! file.
//!
//! ## Why file names carry a content hash
//! A mesh file is named `<model name>-<64-bit hash of the mesh>.ply` and never overwritten with
//! other content. Saving writes the new mesh files first (each atomically), then renames the new
//! session JSON over the old one, and only then deletes the mesh files of that folder the new
//! JSON no longer names. At every moment the session on disk names complete files that hold
//! exactly what it was saved with: a crash or an error at any point leaves the previous session
//! intact (at worst with unreferenced new files, removed by the next save). A mesh that did not
//! change keeps its name, so re-saving does not write it again. So the session and its meshes
//! folder are replaced as a set without a staging folder; the temporary files of single writes
//! that a kill leaves are removed by the next write into the same folder
//! ([`crate::io::atomic`]).
//!
//! The hash is computed at save time from the mesh (a cheap pass over its words); it only names
//! files, it never decides whether a model changed ([`MeshOrigin::Edited`] does).

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use csg::Mesh;

use crate::scene::{MeshOrigin, Scene};

/// The folder holding a session's own meshes: `<session stem>.meshes` next to the session file.
pub fn mesh_dir(session: &Path) -> PathBuf {
    let stem = session
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "session".to_owned());
    session.with_file_name(format!("{stem}.meshes"))
}

/// Writes the meshes of `scene` that need a file of their own into [`mesh_dir`] of `session`
/// (files that already exist under their content name are kept as they are). Returns, per model,
/// the file that holds its mesh (`None`: the model is a region of its source file).
pub fn write_meshes(session: &Path, scene: &Scene) -> anyhow::Result<Vec<Option<PathBuf>>> {
    let dir = mesh_dir(session);
    let mut written = Vec::with_capacity(scene.models.len());
    for (i, model) in scene.models.iter().enumerate() {
        if model.origin == MeshOrigin::Region {
            written.push(None);
            continue;
        }
        let walls = model.wall_faces();
        let path = dir.join(mesh_file_name(&model.model.name, &model.model.mesh, walls));
        if !path.is_file() {
            std::fs::create_dir_all(&dir).with_context(|| {
                format!(
                    "{}: could not create the folder for the cut meshes",
                    dir.display()
                )
            })?;
            crate::io::write_mesh_walls(&path, &model.model.mesh, walls)
                .with_context(|| format!("model {i} ({})", model.model.name))?;
        }
        written.push(Some(path));
    }
    Ok(written)
}

/// Deletes the mesh files in [`mesh_dir`] of `session` that `written` does not name (left from
/// an earlier save of the same session), and the folder when it is left empty. Call it only
/// after the new session file is in place. Only files named as [`mesh_file_name`] names them are
/// touched; failures are ignored (a stale file wastes space, it breaks nothing).
pub fn remove_stale(session: &Path, written: &[Option<PathBuf>]) {
    let dir = mesh_dir(session);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return;
    };
    let keep: HashSet<&std::ffi::OsStr> = written
        .iter()
        .flatten()
        .filter_map(|p| p.file_name())
        .collect();
    for entry in entries.flatten() {
        let name = entry.file_name();
        if is_mesh_file_name(&name.to_string_lossy()) && !keep.contains(name.as_os_str()) {
            std::fs::remove_file(entry.path()).ok();
        }
    }
    // Succeeds only when nothing is left in it.
    std::fs::remove_dir(&dir).ok();
}

/// `<model name, file-safe>-<16 hex digits of the mesh's hash>.ply`; the hash covers the
/// incision walls `walls` too (a mesh without walls keeps the name it always had).
pub fn mesh_file_name(model_name: &str, mesh: &Mesh, walls: &[u32]) -> String {
    let mut safe: String = model_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .take(64)
        .collect();
    // No hidden files (the atomic writer's temporaries start with a dot).
    while safe.starts_with('.') {
        safe.remove(0);
    }
    if safe.is_empty() {
        safe.push_str("mesh");
    }
    format!("{safe}-{:016x}.ply", mesh_hash(mesh, walls))
}

fn is_mesh_file_name(name: &str) -> bool {
    let Some(stem) = name.strip_suffix(".ply") else {
        return false;
    };
    match stem.rsplit_once('-') {
        Some((_, hash)) => hash.len() == 16 && hash.bytes().all(|b| b.is_ascii_hexdigit()),
        None => false,
    }
}

/// A 64-bit hash of the positions' bits, the triangles (counts included) and the wall faces
/// when there are any, stable across runs and platforms.
fn mesh_hash(mesh: &Mesh, walls: &[u32]) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut h: u64 = 0x243f_6a88_85a3_08d3;
    let mut mix = |w: u64| {
        h = (h ^ w).wrapping_mul(K).rotate_left(29);
    };
    mix(mesh.positions.len() as u64);
    mix(mesh.triangles.len() as u64);
    for p in &mesh.positions {
        mix(p.x.to_bits());
        mix(p.y.to_bits());
        mix(p.z.to_bits());
    }
    for t in &mesh.triangles {
        mix(u64::from(t[0]) | u64::from(t[1]) << 32);
        mix(u64::from(t[2]));
    }
    if !walls.is_empty() {
        mix(walls.len() as u64);
        for &f in walls {
            mix(u64::from(f));
        }
    }
    // Final avalanche so that nearby inputs give unrelated names.
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    h
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DVec3;

    use super::*;
    use crate::scene::SceneModel;

    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "cutaway-session-meshes-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A mesh whose welding or region split would change it: two disjoint triangles, a
    /// duplicated position, an unused vertex, coordinates that are not short decimals.
    fn awkward_mesh() -> Mesh {
        Mesh {
            positions: vec![
                DVec3::new(0.1, 0.2, 1.0 / 3.0),
                DVec3::new(1.0, f64::EPSILON, 0.0),
                DVec3::new(0.0, 1.0, -1e-300),
                DVec3::new(0.1, 0.2, 1.0 / 3.0),
                DVec3::new(7.0, 7.0, 7.0),
                DVec3::new(5.0, 5.0, 5.0),
                DVec3::new(6.0, 5.0, 5.0),
                DVec3::new(5.0, 6.0, 5.0),
            ],
            triangles: vec![[0, 1, 2], [5, 6, 7], [3, 2, 1]],
        }
    }

    fn model_file(dir: &Path) -> PathBuf {
        let path = dir.join("plain.ply");
        crate::io::write_mesh(&path, &csg::testkit::icosphere(1, 2.0)).unwrap();
        path
    }

    #[test]
    fn an_edited_mesh_comes_back_bit_for_bit_as_one_model() {
        let dir = temp_dir("exact");
        let source = model_file(&dir);
        let mut scene = Scene::default();
        let plain = crate::io::load_models(&source).unwrap().remove(0);
        scene.models.push(SceneModel::new(
            plain.name,
            &source,
            plain.mesh,
            [0.5, 0.5, 0.5],
        ));
        let mut edited =
            SceneModel::new("bone 1/cut", &source, Arc::new(Mesh::default()), [1.0; 3]);
        edited.replace_mesh(Arc::new(awkward_mesh()));
        edited.opacity = 0.5;
        scene.models.push(edited);
        let session = dir.join("s.json");
        crate::session::save(&session, &scene).unwrap();

        let text = std::fs::read_to_string(&session).unwrap();
        let file = crate::session::parse(&text).unwrap();
        assert!(!file.models[0].exact);
        assert_eq!(file.models[0].path, PathBuf::from("plain.ply"));
        assert!(file.models[1].exact);
        assert!(file.models[1].path.starts_with("s.meshes"), "{text}");

        let back = crate::session::load(&session).unwrap();
        assert_eq!(back.models.len(), 2);
        assert_eq!(back.models[0].origin, MeshOrigin::Region);
        assert_eq!(back.models[1].origin, MeshOrigin::Exact);
        assert_eq!(back.models[1].model.name, "bone 1/cut");
        assert_eq!(back.models[1].opacity, 0.5);
        let (a, b) = (&*scene.models[1].model.mesh, &*back.models[1].model.mesh);
        assert_eq!(a.triangles, b.triangles);
        let bits = |m: &Mesh| -> Vec<[u64; 3]> {
            m.positions
                .iter()
                .map(|p| p.to_array().map(f64::to_bits))
                .collect()
        };
        assert_eq!(bits(a), bits(b));

        // Saving the reopened session again keeps the same file and nothing else.
        crate::session::save(&session, &back).unwrap();
        let files: Vec<_> = std::fs::read_dir(mesh_dir(&session))
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        assert_eq!(files.len(), 1, "{files:?}");
        assert_eq!(files[0], dir.join(&file.models[1].path));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failed_resave_leaves_the_previous_session_and_its_meshes_intact() {
        let dir = temp_dir("resave");
        let session = dir.join("s.json");
        let mut scene = Scene::default();
        let mut model = SceneModel::new("m", "m.ply", Arc::new(Mesh::default()), [1.0; 3]);
        model.replace_mesh(Arc::new(awkward_mesh()));
        scene.models.push(model);
        crate::session::save(&session, &scene).unwrap();
        let first_json = std::fs::read(&session).unwrap();
        let first_mesh =
            mesh_dir(&session).join(mesh_file_name("m", &scene.models[0].model.mesh, &[]));
        let first_bytes = std::fs::read(&first_mesh).unwrap();

        // A second version whose JSON cannot be written (an injected failure at its rename), so
        // the save fails after its mesh files were written.
        let mut second = scene.clone();
        let mut changed = awkward_mesh();
        changed.positions[4].x = 8.0;
        second.models[0].replace_mesh(Arc::new(changed));
        crate::io::atomic::fail_writes_to(Some(session.clone()));
        assert!(crate::session::save(&session, &second).is_err());
        crate::io::atomic::fail_writes_to(None);
        assert_eq!(std::fs::read(&session).unwrap(), first_json);
        assert_eq!(std::fs::read(&first_mesh).unwrap(), first_bytes);
        let back = crate::session::load(&session).unwrap();
        assert_eq!(
            back.models[0].model.mesh.positions,
            scene.models[0].model.mesh.positions
        );

        // Once the save goes through, the old mesh file is gone and the new one is named.
        crate::session::save(&session, &second).unwrap();
        assert!(!first_mesh.exists());
        let back = crate::session::load(&session).unwrap();
        assert_eq!(back.models[0].model.mesh.positions[4].x, 8.0);
        assert_eq!(std::fs::read_dir(mesh_dir(&session)).unwrap().count(), 1);
        // Nothing else: no temporary file of the failed save is left.
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, ["s.json", "s.meshes"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_edited_model_left_empty_still_saves_and_reopens() {
        let dir = temp_dir("empty");
        let session = dir.join("s.json");
        let mut scene = Scene::default();
        let mut model = SceneModel::new("gone", "gone.ply", Arc::new(awkward_mesh()), [1.0; 3]);
        model.replace_mesh(Arc::new(Mesh::default()));
        scene.models.push(model);
        crate::session::save(&session, &scene).unwrap();
        let back = crate::session::load(&session).unwrap();
        assert_eq!(back.models.len(), 1);
        assert_eq!(back.models[0].model.mesh.triangle_count(), 0);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn names_are_safe_and_only_ours_are_removed() {
        let mesh = awkward_mesh();
        let name = mesh_file_name("../knee skin 1", &mesh, &[]);
        assert!(!name.contains('/') && !name.starts_with('.'), "{name}");
        assert!(is_mesh_file_name(&name));
        assert!(!is_mesh_file_name("notes.ply"));
        assert!(!is_mesh_file_name("bone-1.ply"));
        let mut other = mesh.clone();
        other.triangles.swap(0, 1);
        assert_ne!(
            mesh_file_name("a", &mesh, &[]),
            mesh_file_name("a", &other, &[])
        );
        assert_ne!(
            mesh_file_name("a", &mesh, &[]),
            mesh_file_name("a", &mesh, &[0])
        );

        let dir = temp_dir("stale");
        let session = dir.join("s.json");
        std::fs::create_dir_all(mesh_dir(&session)).unwrap();
        let theirs = mesh_dir(&session).join("notes.ply");
        std::fs::write(&theirs, "x").unwrap();
        let stale = mesh_dir(&session).join(&name);
        std::fs::write(&stale, "x").unwrap();
        remove_stale(&session, &[None]);
        assert!(theirs.exists());
        assert!(!stale.exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
