//! Label volumes: read from a file (`cutaway surfaces VOLUME`'s reader) or made from a numpy
//! label map, and surfaced (`cutaway surfaces`' surfacing, without the files).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cutaway::io::volume::{LabelData, LabelInfo, LabelVolume, array, read_volume, surfaces_with};
use glam::{DAffine3, DMat3, DVec3};
use numpy::npyffi::NPY_ORDER;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::{arrays, detached};

/// One structure: `(layer, value, name, (r, g, b), voxels)`.
type StructureTuple = (usize, u32, String, (u8, u8, u8), u64);

/// A label's name handed over from Python: `(value, name, (r, g, b) or None)`.
type NameTuple = (u32, String, Option<(u8, u8, u8)>);

/// A label volume as Cutaway reads it: label maps, voxel-to-world matrix (RAS mm), and one
/// structure per label value present (layer, value, name, colour, voxels).
#[pyclass(module = "cutaway._cutaway", frozen)]
pub struct Volume {
    pub inner: Arc<LabelVolume>,
}

#[pymethods]
impl Volume {
    /// The file (or the name given to an array) the volume came from.
    #[getter]
    fn source(&self) -> String {
        self.inner.source.display().to_string()
    }

    /// Grid size (i, j, k).
    #[getter]
    fn shape(&self) -> (usize, usize, usize) {
        let [i, j, k] = self.inner.dims;
        (i, j, k)
    }

    /// Number of label maps (more than one for overlapping Slicer segmentations).
    #[getter]
    fn layer_count(&self) -> usize {
        self.inner.layers.len()
    }

    /// The voxel-to-world matrix, a 4×4 `float64` array (RAS millimetres).
    #[getter]
    fn affine<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let a = self.inner.world_from_voxel;
        let m = a.matrix3;
        let t = a.translation;
        let rows = [
            [m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x],
            [m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y],
            [m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        Ok(PyArray1::from_vec(py, flat).reshape([4, 4])?.into_any())
    }

    /// The structures: `(layer, value, name, (r, g, b), voxels)` in ascending value, then layer.
    #[getter]
    fn structures(&self) -> Vec<StructureTuple> {
        self.inner
            .structures
            .iter()
            .map(|s| {
                let [r, g, b] = s.color;
                (s.layer, s.value, s.name.clone(), (r, g, b), s.voxels)
            })
            .collect()
    }

    /// Label map `layer` as an (i, j, k) array in Fortran order (i fastest, as stored; one copy
    /// out of the volume, which keeps its own for surfacing).
    fn labels<'py>(&self, py: Python<'py>, layer: usize) -> PyResult<Bound<'py, PyAny>> {
        let Some(data) = self.inner.layers.get(layer) else {
            return Err(pyo3::exceptions::PyIndexError::new_err(format!(
                "layer {layer} of {}",
                self.inner.layers.len()
            )));
        };
        let dims = self.inner.dims;
        let array = match data {
            LabelData::U8(v) => PyArray1::from_slice(py, v)
                .reshape_with_order(dims, NPY_ORDER::NPY_FORTRANORDER)?
                .into_any(),
            LabelData::U16(v) => PyArray1::from_slice(py, v)
                .reshape_with_order(dims, NPY_ORDER::NPY_FORTRANORDER)?
                .into_any(),
            LabelData::U32(v) => PyArray1::from_slice(py, v)
                .reshape_with_order(dims, NPY_ORDER::NPY_FORTRANORDER)?
                .into_any(),
        };
        Ok(array)
    }
}

/// Reads a label volume (.nrrd, .seg.nrrd, .nhdr, .nii, .nii.gz, or a folder of masks), named
/// by `labels` (a colour table) when given: `cutaway surfaces`' reader.
#[pyfunction]
#[pyo3(signature = (path, labels=None))]
fn read_volume_file(py: Python<'_>, path: PathBuf, labels: Option<PathBuf>) -> PyResult<Volume> {
    let volume = detached(py, || read_volume(&path, labels.as_deref()))?;
    Ok(Volume {
        inner: Arc::new(volume),
    })
}

/// A volume from a flat label map (i fastest, `dims` long; `uint8`, `uint16` or `uint32`), a
/// 4×4 voxel-to-world matrix, and names `(value, name, colour or None)`, or a colour table file
/// (`table`).
#[pyfunction]
#[pyo3(signature = (source, dims, affine, data, names, table=None))]
fn volume_from_array(
    py: Python<'_>,
    source: String,
    dims: (usize, usize, usize),
    affine: PyReadonlyArray2<'_, f64>,
    data: &Bound<'_, PyAny>,
    names: Vec<NameTuple>,
    table: Option<PathBuf>,
) -> PyResult<Volume> {
    if affine.shape() != [4, 4] {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "{source}: the affine must be a 4×4 matrix, not {:?}",
            affine.shape()
        )));
    }
    let a = affine.as_array();
    let column = |c: usize| DVec3::new(a[[0, c]], a[[1, c]], a[[2, c]]);
    let world_from_voxel = DAffine3::from_mat3_translation(
        DMat3::from_cols(column(0), column(1), column(2)),
        column(3),
    );
    let data = if let Ok(a) = data.extract::<PyReadonlyArray1<'_, u8>>() {
        LabelData::U8(a.as_slice()?.to_vec())
    } else if let Ok(a) = data.extract::<PyReadonlyArray1<'_, u16>>() {
        LabelData::U16(a.as_slice()?.to_vec())
    } else {
        let a = data.extract::<PyReadonlyArray1<'_, u32>>()?;
        LabelData::U32(a.as_slice()?.to_vec())
    };
    let mut infos: Vec<LabelInfo> = names
        .into_iter()
        .map(|(value, name, color)| LabelInfo {
            layer: None,
            value,
            name,
            color: color.map(|(r, g, b)| [r, g, b]),
        })
        .collect();
    let volume = detached(py, || {
        if let Some(table) = &table {
            infos.extend(cutaway::io::volume::color_table::read(table)?);
        }
        array::volume_from_labels(
            Path::new(&source),
            [dims.0, dims.1, dims.2],
            world_from_voxel,
            data,
            &infos,
        )
    })?;
    Ok(Volume {
        inner: Arc::new(volume),
    })
}

/// One surface: `(layer, value, name, (r, g, b), voxels, vertices, triangles)`.
type SurfaceTuple<'py> = (
    usize,
    u32,
    String,
    (u8, u8, u8),
    u64,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
);

/// One closed surface per structure of `volume` (only the label values in `only` when given),
/// with `cutaway surfaces`' options and checks.
#[pyfunction]
#[pyo3(signature = (volume, smoothing=None, decimate=None, only=None))]
fn surfaces<'py>(
    py: Python<'py>,
    volume: &Volume,
    smoothing: Option<f64>,
    decimate: Option<f64>,
    only: Option<Vec<u32>>,
) -> PyResult<Vec<SurfaceTuple<'py>>> {
    let volume = volume.inner.clone();
    let found = detached(py, move || {
        let options = array::surface_options(smoothing, decimate)?;
        let picked;
        let volume: &LabelVolume = match &only {
            Some(values) => {
                let mut v = (*volume).clone();
                v.structures.retain(|s| values.contains(&s.value));
                if v.structures.is_empty() {
                    anyhow::bail!(
                        "{}: none of the labels {values:?} is present",
                        v.source.display()
                    );
                }
                picked = v;
                &picked
            }
            None => &volume,
        };
        use anyhow::Context as _;
        surfaces_with(volume, options, &|_| true)
            .with_context(|| volume.source.display().to_string())
    })?;
    found
        .into_iter()
        .map(|s| {
            let [r, g, b] = s.structure.color;
            Ok((
                s.structure.layer,
                s.structure.value,
                s.structure.name,
                (r, g, b),
                s.structure.voxels,
                arrays::vertices(py, &s.mesh.positions)?,
                arrays::triangles(py, &s.mesh.triangles)?,
            ))
        })
        .collect()
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Volume>()?;
    m.add_function(wrap_pyfunction!(read_volume_file, m)?)?;
    m.add_function(wrap_pyfunction!(volume_from_array, m)?)?;
    m.add_function(wrap_pyfunction!(surfaces, m)?)?;
    Ok(())
}
