//! File formats: reading meshes (OBJ, STL, PLY, legacy VTK, directories) and writing them.
//!
//! OWNER: IO helper (foundation issue). Signatures are fixed; bodies to be written.
//! Every error names the file and the problem in one line (anyhow context `"<path>"`).

use std::path::Path;

use csg::Mesh;

/// A named part of a file (an OBJ object/group, or the whole file for formats without parts).
#[derive(Clone, Debug)]
pub struct Part {
    pub name: String,
    /// Welded (bit-identical positions merged), validated mesh.
    pub mesh: Mesh,
}

/// A model of the scene: one connected region of one file.
#[derive(Clone, Debug)]
pub struct Model {
    /// File stem + region number, as in the thesis's Models list (e.g. `knee_skin 1`).
    pub name: String,
    /// The file it came from.
    pub source: std::path::PathBuf,
    /// Welded, validated, compacted mesh of this region only.
    pub mesh: Mesh,
}

/// Reads every part of a mesh file (format chosen by extension, checked against the content).
pub fn read_parts(path: &Path) -> anyhow::Result<Vec<Part>> {
    let _ = path;
    unimplemented!("IO helper")
}

/// Reads a mesh file as one welded mesh (all parts concatenated).
pub fn read_mesh(path: &Path) -> anyhow::Result<Mesh> {
    let _ = path;
    unimplemented!("IO helper")
}

/// Loads a file or every mesh file of a directory, split into regions, one [`Model`] per region,
/// in file order (files of a directory sorted by name).
pub fn load_models(path: &Path) -> anyhow::Result<Vec<Model>> {
    let _ = path;
    unimplemented!("IO helper")
}

/// Writes a triangle mesh; format by extension (`.obj`, `.stl` binary, `.ply` binary). Atomic
/// (temporary file, then rename).
pub fn write_mesh(path: &Path, mesh: &Mesh) -> anyhow::Result<()> {
    let _ = (path, mesh);
    unimplemented!("IO helper")
}

/// Writes an OBJ of general polygons (`f a b c d` for quads), exact f64 round trip. Atomic.
pub fn write_obj_polygons(path: &Path, positions: &[glam::DVec3], faces: &[Vec<u32>]) -> anyhow::Result<()> {
    let _ = (path, positions, faces);
    unimplemented!("IO helper")
}

/// Writes OBJ polylines (`v` records and `l` records), exact f64 round trip. Atomic.
pub fn write_obj_polylines(path: &Path, polylines: &[Vec<glam::DVec3>]) -> anyhow::Result<()> {
    let _ = (path, polylines);
    unimplemented!("IO helper")
}
