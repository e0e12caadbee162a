//! File formats: reading meshes (OBJ, STL, PLY, legacy VTK, directories) and writing them.
//!
//! The mesh core (`csg`) never sees a file format; this module turns files into welded, validated
//! [`Mesh`]es and back.
//!
//! # Reading
//! Every reader works on the whole file in memory (`&[u8]`) and produces raw parts (positions in
//! `f64`, triangles); [`parse_bytes`] then checks each part's structure
//! ([`Mesh::sanity_check`]: indices in range, finite coordinates), welds bit-identical positions
//! ([`csg::weld::weld_exact`]: STL stores no shared vertices, OBJ splits vertices by normal) and
//! drops vertices that no triangle uses. Values are never rounded: `f32` data converts to `f64`
//! exactly and text is parsed straight to `f64`.
//!
//! | format | reader | notes |
//! |---|---|---|
//! | `.obj` | `tobj` (`single_index`, `triangulate`) | every `o`/`g` name is its own part ([`Model`]); polygons fan-triangulated; points and lines ignored; a vertex weight `w` is ignored, not divided by |
//! | `.stl` | our own ([`stl`]) | binary when the size is exactly `84 + 50·count` (even if the header starts with `solid`), else ASCII; `stl_io` decides by the `solid ` prefix alone and so rejects such binary files |
//! | `.ply` | `ply-rs-bw` | ASCII and binary (both byte orders); faces from `vertex_indices` or `vertex_index` lists of any integer type, fan-triangulated |
//! | `.vtk` | own reader (`vtk.rs`, legacy) | `POLYDATA` with `POLYGONS` (fan-triangulated) and `TRIANGLE_STRIPS` (triangulated here with alternating winding) |
//!
//! The format is chosen by the extension (case-insensitive) and checked against the content: a
//! PLY file named `.stl` is an error that says so, never a silent guess.
//!
//! # Bad input
//! Every error is one line naming the file (`anyhow` context `"<path>"`), so `main` prints
//! `error: <file>: <what is wrong>`. Files are read through [`bounded`]: only regular files
//! (symbolic links followed; FIFOs, devices and sockets refused before they are opened) of at most
//! [`bounded::MESH_MAX_BYTES`] (2 GiB). No allocation is sized by a count read from a header
//! before the data it counts is seen to exist (our own parsers compare counts with the file size;
//! the third-party parsers were checked for this, see `../shared/DESIGN.md`). Coordinates must be
//! finite and within ±[`MAX_ABS_COORDINATE`] (10¹²); the error names the vertex. Third-party
//! parsers run inside [`std::panic::catch_unwind`] as a last resort, so that a parser bug on
//! malformed input becomes an error, not a crash.
//!
//! # Models
//! [`load_models`] splits every part into regions (edge-connected components,
//! [`csg::regions::split_regions`]) and names each region as the thesis's Models list does: the
//! file stem and the region number, counted from 1 through the whole file. A file that holds a
//! single region keeps the plain stem (`VHF_Left_Bone_Tibia_smooth`): a number there would name
//! a region the file does not divide into, and the name a user types (`--focus`) would not be
//! the file's. When a file has several named parts (OBJ objects/groups), the part name follows
//! the stem after `#`, as in `../shared/anatomy/SOURCES.md`: `lumbar_spine#vertebra_L1 1`,
//! `lumbar_spine#vertebra_L2 2`.
//!
//! # Writing
//! All writers are atomic ([`atomic`]: a temporary file in the same directory, then a rename), so
//! a crash never leaves a half-written file under the requested name; files that belong together
//! are written as an [`OutputSet`], which replaces the previous set as a whole. OBJ and PLY round-trip `f64`
//! exactly (OBJ: Rust's shortest round-trip decimal formatting; PLY: `double` properties). STL
//! stores `f32` by definition, so writing STL rounds coordinates to `f32`.

use std::cell::Cell;
use std::path::Path;
use std::sync::Once;

use anyhow::Context as _;
use csg::Mesh;

pub mod atomic;
pub mod bounded;
mod dir;
pub mod dropped;
pub mod gesture;
pub mod intensity;
mod model;
mod obj;
pub mod path_file;
mod ply;
mod stl;
mod structures;
pub mod volume;
mod vtk;

pub use atomic::{OutputSet, recover as recover_output_set, write_file};
pub use dir::mesh_files;
pub use model::{Model, ModelUnit};
pub use structures::{
    FileContent, content_of_file, content_of_file_with, group_of, load_structures, structure_name,
    structures_of_file, structures_of_parts,
};

/// The mesh file formats Cutaway reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    Obj,
    Stl,
    Ply,
    Vtk,
}

impl Format {
    /// All formats, in the order error messages list them.
    pub const ALL: [Format; 4] = [Format::Obj, Format::Stl, Format::Ply, Format::Vtk];

    /// The format a path's extension names (case-insensitive), if any.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Format::Obj),
            "stl" => Some(Format::Stl),
            "ply" => Some(Format::Ply),
            "vtk" => Some(Format::Vtk),
            _ => None,
        }
    }

    /// Upper-case name for messages (`STL`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::Stl => "STL",
            Format::Ply => "PLY",
            Format::Vtk => "VTK",
        }
    }

    /// Guesses the format from the first bytes and the size. Used only to explain errors (a file
    /// whose content does not match its extension); reading always follows the extension.
    pub fn sniff(bytes: &[u8]) -> Option<Format> {
        let start = trim_ascii_start(bytes);
        if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
            return Some(Format::Ply);
        }
        if bytes.starts_with(b"# vtk DataFile") {
            return Some(Format::Vtk);
        }
        if stl::is_binary_size(bytes) || start.starts_with(b"solid") {
            return Some(Format::Stl);
        }
        let head = &bytes[..bytes.len().min(4096)];
        let text = match std::str::from_utf8(head) {
            Ok(text) => text,
            // A multi-byte character cut at the 4096th byte is still text.
            Err(e) if e.valid_up_to() + 4 > head.len() => {
                std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or_default()
            }
            Err(_) => return None,
        };
        let obj_like = text.lines().any(|line| {
            let line = line.trim_start();
            line.starts_with("v ") || line.starts_with("f ") || line.starts_with("o ")
        });
        obj_like.then_some(Format::Obj)
    }
}

fn trim_ascii_start(bytes: &[u8]) -> &[u8] {
    let skip = bytes.iter().take_while(|b| b.is_ascii_whitespace()).count();
    &bytes[skip..]
}

/// A part as a reader produced it: not yet validated, welded or compacted.
#[derive(Debug, Default)]
pub(crate) struct RawPart {
    /// The part's own name (OBJ object/group, ASCII STL solid name); `None` means "the file".
    pub name: Option<String>,
    pub positions: Vec<csg::DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// Reads every part of a mesh file (format chosen by extension, checked against the content).
/// A label volume (file or mask directory, [`volume::is_volume`]) gives one part per structure,
/// named and coloured, in ascending label order.
pub fn read_parts(path: &Path) -> anyhow::Result<Vec<Model>> {
    let mut parts = if volume::is_volume(path) {
        volume::read_parts(path)?
    } else {
        read_parts_inner(path).with_context(|| path.display().to_string())?
    };
    for (index, part) in parts.iter_mut().enumerate() {
        part.source = path.to_path_buf();
        part.index = index;
    }
    Ok(parts)
}

fn read_parts_inner(path: &Path) -> anyhow::Result<Vec<Model>> {
    // A path that is not there is missing, whatever its name says about its format.
    std::fs::metadata(path)?;
    let format = Format::from_path(path).ok_or_else(|| {
        let ext = path
            .extension()
            .map(|e| format!("extension '.{}'", e.to_string_lossy()))
            .unwrap_or_else(|| "no extension".to_owned());
        anyhow::anyhow!("unknown mesh format ({ext}); expected .obj, .stl, .ply or .vtk")
    })?;
    let bytes = bounded::read_bytes(path, bounded::MESH_MAX_BYTES)?;
    let stem = file_stem(path);
    parse_bytes(format, &bytes, &stem)
}

/// Parses a whole file's bytes as `format`. `default_name` names parts that have no name of their
/// own (usually the file stem). Errors do not name the file (the caller adds it).
pub fn parse_bytes(format: Format, bytes: &[u8], default_name: &str) -> anyhow::Result<Vec<Model>> {
    if bytes.is_empty() {
        anyhow::bail!("the file is empty");
    }
    let parsed = match format {
        Format::Obj => guarded(format, || obj::parse(bytes)),
        Format::Stl => stl::parse(bytes),
        Format::Ply => guarded(format, || ply::parse(bytes)),
        Format::Vtk => guarded(format, || vtk::parse(bytes)),
    };
    let raw = match parsed {
        Ok(raw) => raw,
        Err(e) => return Err(explain_mismatch(format, bytes, e)),
    };
    let parts = finish_parts(raw, default_name)?;
    if parts.is_empty() {
        let e = anyhow::anyhow!("no triangles in this {} file", format.name());
        return Err(explain_mismatch(format, bytes, e));
    }
    Ok(parts)
}

/// A mesh handed over in memory (positions and triangles, as the Python package takes them),
/// checked, welded and compacted exactly as a file's part is ([`read_mesh`]). `what` names it in
/// errors.
pub fn mesh_from_arrays(
    what: &str,
    positions: Vec<csg::DVec3>,
    triangles: Vec<[u32; 3]>,
) -> anyhow::Result<Mesh> {
    let raw = vec![RawPart {
        name: None,
        positions,
        triangles,
    }];
    let parts = finish_parts(raw, what).with_context(|| what.to_owned())?;
    match parts.into_iter().next() {
        Some(part) => Ok(std::sync::Arc::unwrap_or_clone(part.mesh)),
        None => anyhow::bail!("{what}: no triangles"),
    }
}

/// When a file fails to parse and its content looks like another format, say so.
fn explain_mismatch(format: Format, bytes: &[u8], error: anyhow::Error) -> anyhow::Error {
    match Format::sniff(bytes) {
        Some(actual) if actual != format => error.context(format!(
            "the content looks like {}, not {} as the extension says",
            actual.name(),
            format.name()
        )),
        _ => error,
    }
}

/// Validates, welds and compacts raw parts; drops parts without triangles; merges parts that
/// share a name (tobj splits an object at each `usemtl`).
pub(crate) fn finish_parts(raw: Vec<RawPart>, default_name: &str) -> anyhow::Result<Vec<Model>> {
    let named = raw.iter().filter(|r| !r.triangles.is_empty()).count() > 1;
    let mut merged: Vec<(String, Mesh)> = Vec::new();
    for (index, part) in raw.into_iter().enumerate() {
        if part.triangles.is_empty() {
            continue;
        }
        let name = part.name.unwrap_or_else(|| default_name.to_owned());
        let mesh = Mesh {
            positions: part.positions,
            triangles: part.triangles,
        };
        check_coordinates(&mesh.positions)
            .and_then(|()| mesh.sanity_check().map_err(anyhow::Error::from))
            .with_context(|| {
                if named {
                    format!("part {} ('{name}')", index + 1)
                } else {
                    "bad mesh data".to_owned()
                }
            })?;
        match merged.iter_mut().find(|(n, _)| *n == name) {
            Some((_, existing)) => {
                existing.append(&mesh);
            }
            None => merged.push((name, mesh)),
        }
    }
    Ok(merged
        .into_iter()
        .map(|(name, mesh)| Model::part(name, None, csg::weld::weld_exact(&mesh).compacted()))
        .collect())
}

/// Largest coordinate magnitude a mesh file may hold. Anatomy in metres or millimetres is many
/// orders of magnitude below; a value beyond it is a corrupt or mis-scaled file, and exact
/// predicates on such values would overflow the products they form (|x|³ near `f64::MAX`).
pub const MAX_ABS_COORDINATE: f64 = 1e12;

/// Refuses non-finite coordinates and coordinates beyond ±[`MAX_ABS_COORDINATE`], naming the
/// first vertex (0-based index in the part) that has one.
pub(crate) fn check_coordinates(positions: &[csg::DVec3]) -> anyhow::Result<()> {
    let bad = positions
        .iter()
        .position(|p| !p.to_array().iter().all(|c| c.abs() <= MAX_ABS_COORDINATE));
    match bad {
        None => Ok(()),
        Some(v) => {
            let p = positions[v];
            if p.is_finite() {
                anyhow::bail!(
                    "vertex {v} (counted from 0) has coordinate ({:?}, {:?}, {:?}) beyond ±{MAX_ABS_COORDINATE:e} (a corrupt or mis-scaled file)",
                    p.x,
                    p.y,
                    p.z
                )
            }
            anyhow::bail!(
                "vertex {v} (counted from 0) has a non-finite coordinate ({:?}, {:?}, {:?})",
                p.x,
                p.y,
                p.z
            )
        }
    }
}

thread_local! {
    /// True while this thread runs a third-party parser under [`guarded`]: its panics are turned
    /// into errors, so the panic hook must not print them.
    static IN_GUARDED_PARSER: Cell<bool> = const { Cell::new(false) };
}

/// Runs a third-party parser, turning a panic into an error. The process's panic hook stays in
/// place for every other panic; only panics inside `parse` on this thread are kept quiet (the
/// error replaces them).
fn guarded<T>(format: Format, parse: impl FnOnce() -> anyhow::Result<T>) -> anyhow::Result<T> {
    static QUIET_HOOK: Once = Once::new();
    QUIET_HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !IN_GUARDED_PARSER.get() {
                previous(info);
            }
        }));
    });
    let was = IN_GUARDED_PARSER.replace(true);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(parse));
    IN_GUARDED_PARSER.set(was);
    result.unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".to_owned());
        Err(anyhow::anyhow!(
            "malformed {} file (the parser failed: {message})",
            format.name()
        ))
    })
}

/// The file stem of `path` as text (`"mesh"` when it has none).
pub fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".to_owned())
}

/// Reads a mesh file as one welded mesh (all parts concatenated). Parts are welded each on its
/// own and not across each other, so a file's regions are the same here as in [`load_models`].
pub fn read_mesh(path: &Path) -> anyhow::Result<Mesh> {
    let parts = read_parts(path)?;
    let mut mesh = Mesh::default();
    for part in &parts {
        mesh.append(&part.mesh);
    }
    Ok(mesh)
}

/// Reads a mesh file exactly as stored, all parts concatenated: no welding, no dropping of unused
/// vertices, no region split, so a mesh written by [`write_mesh`] as `.ply` reads back bit for
/// bit (positions and triangles in the same order; OBJ goes through `tobj`, which may reorder). Indices are checked and coordinates
/// must be finite; a file without triangles gives an empty mesh.
pub fn read_mesh_verbatim(path: &Path) -> anyhow::Result<Mesh> {
    read_mesh_verbatim_walls(path).map(|(mesh, _)| mesh)
}

/// [`read_mesh_verbatim`], and the triangles a PLY file marks as incision walls (ascending;
/// none for other formats): a scalpel-cut mesh as [`write_mesh_walls`] wrote it.
pub fn read_mesh_verbatim_walls(path: &Path) -> anyhow::Result<(Mesh, Vec<u32>)> {
    read_mesh_verbatim_inner(path).with_context(|| path.display().to_string())
}

fn read_mesh_verbatim_inner(path: &Path) -> anyhow::Result<(Mesh, Vec<u32>)> {
    let format = Format::from_path(path)
        .ok_or_else(|| anyhow::anyhow!("unknown mesh format; expected .obj, .stl, .ply or .vtk"))?;
    let bytes = bounded::read_bytes(path, bounded::MESH_MAX_BYTES)?;
    if bytes.is_empty() {
        anyhow::bail!("the file is empty");
    }
    let mut walls = Vec::new();
    let parsed = match format {
        Format::Obj => guarded(format, || obj::parse(&bytes)),
        Format::Stl => stl::parse(&bytes),
        Format::Ply => guarded(format, || ply::parse_marked(&bytes)).map(|(parts, marked)| {
            walls = marked;
            parts
        }),
        Format::Vtk => guarded(format, || vtk::parse(&bytes)),
    };
    let raw = parsed.map_err(|e| explain_mismatch(format, &bytes, e))?;
    let mut mesh = Mesh::default();
    for part in raw {
        let part = Mesh {
            positions: part.positions,
            triangles: part.triangles,
        };
        check_coordinates(&part.positions)
            .and_then(|()| part.sanity_check().map_err(anyhow::Error::from))
            .context("bad mesh data")?;
        if mesh.positions.is_empty() && mesh.triangles.is_empty() {
            mesh = part;
        } else {
            mesh.append(&part);
        }
    }
    Ok((mesh, walls))
}

/// Loads a file or every mesh file of a directory, split into regions, one [`Model`] per region,
/// in file order (files of a directory sorted by name).
///
/// A directory is searched recursively (sub-folders too, symbolic links to folders are not
/// followed), and only files with a mesh extension are read; a directory without any mesh file
/// is an error. Files are read in parallel; the order of the result does not depend on it.
pub fn load_models(path: &Path) -> anyhow::Result<Vec<Model>> {
    dir::load_models(path)
}

/// Splits one file's parts into models named as the module doc says.
pub fn models_of_parts(source: &Path, parts: &[Model]) -> Vec<Model> {
    let stem = file_stem(source);
    let several_parts = parts.len() > 1;
    let mut models = Vec::new();
    let mut prefixes = Vec::new();
    for part in parts {
        let prefix = if several_parts {
            format!("{stem}#{}", part.name)
        } else {
            stem.clone()
        };
        for region in csg::regions::split_regions(&part.mesh) {
            prefixes.push(prefix.clone());
            models.push(Model {
                source: source.to_path_buf(),
                index: models.len(),
                ..Model::part("", None, region)
            });
        }
    }
    // Numbered only when the file really holds several regions.
    let numbered = models.len() > 1;
    for (model, prefix) in models.iter_mut().zip(prefixes) {
        model.name = if numbered {
            format!("{prefix} {}", model.index + 1)
        } else {
            prefix
        };
    }
    models
}

/// Writes a triangle mesh; format by extension (`.obj`, `.stl` binary, `.ply` binary). Atomic
/// (temporary file, then rename).
pub fn write_mesh(path: &Path, mesh: &Mesh) -> anyhow::Result<()> {
    write_mesh_walls(path, mesh, &[])
}

/// [`write_mesh`] with the faces `walls` (ascending) marked as incision walls where the format
/// can say so (PLY's `cutaway_wall` face property; other formats write the mesh alone).
pub fn write_mesh_walls(path: &Path, mesh: &Mesh, walls: &[u32]) -> anyhow::Result<()> {
    mesh_writer(path, mesh, walls)
        .and_then(|fill| atomic::write(path, fill))
        .with_context(|| path.display().to_string())
}

/// A function writing `mesh` in the format `path`'s extension names, after checking the mesh.
fn mesh_writer<'a>(
    path: &Path,
    mesh: &'a Mesh,
    walls: &'a [u32],
) -> anyhow::Result<Box<MeshFill<'a>>> {
    mesh.sanity_check()
        .context("refusing to write an invalid mesh")?;
    Ok(match Format::from_path(path) {
        Some(Format::Obj) => Box::new(|w: &mut dyn std::io::Write| obj::write_mesh(w, mesh)),
        Some(Format::Stl) => {
            let count = u32::try_from(mesh.triangles.len())
                .map_err(|_| anyhow::anyhow!("binary STL holds at most {} triangles", u32::MAX))?;
            Box::new(move |w: &mut dyn std::io::Write| stl::write_binary(w, mesh, count))
        }
        Some(Format::Ply) => {
            Box::new(move |w: &mut dyn std::io::Write| ply::write_binary(w, mesh, walls))
        }
        Some(Format::Vtk) => anyhow::bail!("writing VTK is not supported; use .obj, .stl or .ply"),
        None => anyhow::bail!("unknown mesh extension; use .obj, .stl or .ply"),
    })
}

type MeshFill<'a> = dyn FnOnce(&mut dyn std::io::Write) -> std::io::Result<()> + 'a;

/// Writes an OBJ of general polygons (`f a b c d` for quads), exact f64 round trip. Atomic.
pub fn write_obj_polygons(
    path: &Path,
    positions: &[glam::DVec3],
    faces: &[Vec<u32>],
) -> anyhow::Result<()> {
    obj::check_polygons(positions, faces)
        .and_then(|()| atomic::write(path, |w| obj::write_polygons(w, positions, faces)))
        .with_context(|| path.display().to_string())
}

/// Writes OBJ polylines (`v` records and `l` records), exact f64 round trip. Atomic.
///
/// Every point is its own vertex, except that a polyline whose last point equals its first
/// (bit for bit) is written closed: its `l` record ends with the first vertex's index again.
pub fn write_obj_polylines(path: &Path, polylines: &[Vec<glam::DVec3>]) -> anyhow::Result<()> {
    obj::check_polylines(polylines)
        .and_then(|()| atomic::write(path, |w| obj::write_polylines(w, polylines)))
        .with_context(|| path.display().to_string())
}

impl OutputSet {
    /// Stages `mesh` as the file `relative` of the set, as [`write_mesh`] writes it.
    pub fn write_mesh(&self, relative: &Path, mesh: &Mesh) -> anyhow::Result<()> {
        let fill = mesh_writer(relative, mesh, &[])
            .with_context(|| self.final_path(relative).display().to_string())?;
        self.write(relative, fill)
    }

    /// Stages polylines as the OBJ file `relative` of the set, as [`write_obj_polylines`] writes
    /// them.
    pub fn write_obj_polylines(
        &mut self,
        relative: &Path,
        polylines: &[Vec<glam::DVec3>],
    ) -> anyhow::Result<()> {
        obj::check_polylines(polylines)
            .with_context(|| self.final_path(relative).display().to_string())?;
        self.write(relative, |w| obj::write_polylines(w, polylines))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_from_extension_is_case_insensitive() {
        assert_eq!(Format::from_path(Path::new("a/b.STL")), Some(Format::Stl));
        assert_eq!(Format::from_path(Path::new("b.Obj")), Some(Format::Obj));
        assert_eq!(Format::from_path(Path::new("b.vtk")), Some(Format::Vtk));
        assert_eq!(Format::from_path(Path::new("b.ply")), Some(Format::Ply));
        assert_eq!(Format::from_path(Path::new("b.txt")), None);
        assert_eq!(Format::from_path(Path::new("b")), None);
    }

    #[test]
    fn sniff_recognises_each_format() {
        assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n"), Some(Format::Ply));
        assert_eq!(
            Format::sniff(b"# vtk DataFile Version 3.0\n"),
            Some(Format::Vtk)
        );
        assert_eq!(Format::sniff(b"  solid x\nfacet"), Some(Format::Stl));
        assert_eq!(Format::sniff(b"# c\nv 1 2 3\nf 1 2 3\n"), Some(Format::Obj));
        assert_eq!(Format::sniff(&[0xff, 0xfe, 0, 1]), None);
    }

    #[test]
    fn guarded_turns_a_panic_into_an_error() {
        let result: anyhow::Result<()> = guarded(Format::Obj, || panic!("boom"));
        let message = format!("{:#}", result.unwrap_err());
        assert!(
            message.contains("boom") && message.contains("OBJ"),
            "{message}"
        );
        // The flag is reset, so later panics elsewhere are reported normally.
        assert!(!IN_GUARDED_PARSER.get());
    }
}
