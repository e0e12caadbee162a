//! Meshes in and the exact boolean: `cutaway subtract`'s cut ([`cutaway::cutting::mesh_cut`]) on
//! meshes given as numpy arrays or as files.

use std::path::PathBuf;

use cutaway::cutting::mesh_cut::{MeshCut, MeshCutError, cut_mesh};
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{arrays, detached};

/// A mesh argument: a file path, or vertices and triangles.
#[derive(FromPyObject)]
pub enum MeshArg<'py> {
    Path(PathBuf),
    Arrays(PyReadonlyArray2<'py, f64>, PyReadonlyArray2<'py, u32>),
}

/// What a [`MeshArg`] holds before the GIL is released.
pub enum MeshSource {
    File(PathBuf),
    Memory(String, Vec<csg::DVec3>, Vec<[u32; 3]>),
}

impl MeshSource {
    pub fn of(arg: MeshArg<'_>, what: &str) -> PyResult<MeshSource> {
        Ok(match arg {
            MeshArg::Path(p) => MeshSource::File(p),
            MeshArg::Arrays(v, t) => MeshSource::Memory(
                what.to_owned(),
                arrays::read_vertices(&v)?,
                arrays::read_triangles(&t)?,
            ),
        })
    }

    /// The name errors give it.
    pub fn name(&self) -> String {
        match self {
            MeshSource::File(p) => p.display().to_string(),
            MeshSource::Memory(what, ..) => what.clone(),
        }
    }

    /// Read (a file, through `cutaway::io::read_mesh`) or checked and welded as a file's part is.
    pub fn mesh(self) -> anyhow::Result<csg::Mesh> {
        match self {
            MeshSource::File(p) => cutaway::io::read_mesh(&p),
            MeshSource::Memory(what, v, t) => cutaway::io::mesh_from_arrays(&what, v, t),
        }
    }
}

/// `(vertices, triangles)` of a mesh.
fn pair<'py>(py: Python<'py>, mesh: &csg::Mesh) -> PyResult<Bound<'py, PyAny>> {
    let v = arrays::vertices(py, &mesh.positions)?;
    let t = arrays::triangles(py, &mesh.triangles)?;
    Ok((v, t).into_pyobject(py)?.into_any())
}

/// A mesh as Cutaway reads it: checked, welded by exact position and compacted, as a file's part.
#[pyfunction]
fn load_mesh<'py>(py: Python<'py>, mesh: MeshArg<'py>) -> PyResult<Bound<'py, PyAny>> {
    let source = MeshSource::of(mesh, "mesh")?;
    let mesh = detached(py, move || source.mesh())?;
    pair(py, &mesh)
}

/// Cuts `cutter` out of every region of `target` as `cutaway subtract` does; returns a dict with
/// `kept`, `walls`, `removed` (each `(vertices, triangles)`), `contour` (polylines), `regions`
/// and the numbers of `cutaway subtract --json`.
#[pyfunction]
fn subtract<'py>(
    py: Python<'py>,
    target: MeshArg<'py>,
    cutter: MeshArg<'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let target = MeshSource::of(target, "target")?;
    let cutter = MeshSource::of(cutter, "cutter")?;
    let cut: MeshCut = detached(py, move || {
        let (target_name, cutter_name) = (target.name(), cutter.name());
        let target = target.mesh()?;
        let cutter = cutter.mesh()?;
        cut_mesh(target, &cutter).map_err(|e| match e {
            MeshCutError::Target(e) => e.context(target_name),
            MeshCutError::Cutter(e) => e.context(cutter_name),
        })
    })?;
    let out = PyDict::new(py);
    out.set_item("kept", pair(py, &cut.kept)?)?;
    out.set_item("walls", pair(py, &cut.walls)?)?;
    out.set_item("removed", pair(py, &cut.removed)?)?;
    let contour = cut
        .contour
        .iter()
        .map(|line| arrays::vertices(py, line))
        .collect::<PyResult<Vec<_>>>()?;
    out.set_item("contour", contour)?;
    let regions = cut
        .regions
        .iter()
        .zip(&cut.region_reports)
        .map(|(parts, report)| {
            let r = PyDict::new(py);
            r.set_item("index", report.index)?;
            r.set_item("kept", pair(py, &parts.kept)?)?;
            r.set_item("walls", pair(py, &parts.walls)?)?;
            r.set_item("removed", pair(py, &parts.removed)?)?;
            r.set_item("removed_volume", report.removed_volume)?;
            r.set_item("closed", report.closed)?;
            Ok(r)
        })
        .collect::<PyResult<Vec<_>>>()?;
    out.set_item("regions", regions)?;
    out.set_item("target_triangles", cut.target_triangles)?;
    out.set_item("cutter_triangles", cut.cutter_triangles)?;
    out.set_item("cut_ms", cut.cut_ms)?;
    out.set_item("materialize_ms", cut.materialize_ms)?;
    Ok(out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(subtract, m)?)?;
    Ok(())
}
