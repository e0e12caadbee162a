//! numpy in and out. Results move their Rust buffer into numpy (`from_vec`, then a reshape that
//! makes a view), so a mesh or an image crosses with no copy beyond the one that lays `DVec3`s
//! out flat; inputs are read in place when C-contiguous.

use csg::DVec3;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// `positions` as a `float64 (n,3)` array.
pub fn vertices<'py>(py: Python<'py>, positions: &[DVec3]) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = positions.iter().flat_map(|p| p.to_array()).collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([positions.len(), 3])?
        .into_any())
}

/// `triangles` as a `uint32 (m,3)` array.
pub fn triangles<'py>(py: Python<'py>, triangles: &[[u32; 3]]) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([triangles.len(), 3])?
        .into_any())
}

/// An RGBA image's bytes as a `uint8 (h,w,4)` array (the buffer moves, no copy).
pub fn image<'py>(py: Python<'py>, image: image::RgbaImage) -> PyResult<Bound<'py, PyAny>> {
    let (w, h) = (image.width() as usize, image.height() as usize);
    Ok(PyArray1::from_vec(py, image.into_raw())
        .reshape([h, w, 4])?
        .into_any())
}

/// Points of a `float64 (n,3)` array.
pub fn read_vertices(array: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    check_columns(array.shape(), "vertices")?;
    let view = array.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// Triangles of a `uint32 (m,3)` array.
pub fn read_triangles(array: &PyReadonlyArray2<'_, u32>) -> PyResult<Vec<[u32; 3]>> {
    check_columns(array.shape(), "triangles")?;
    let view = array.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

fn check_columns(shape: &[usize], what: &str) -> PyResult<()> {
    if shape.len() != 2 || shape[1] != 3 {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "{what} must have shape (n, 3), not {shape:?}"
        )));
    }
    Ok(())
}
