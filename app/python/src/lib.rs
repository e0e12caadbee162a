//! `cutaway._cutaway`: the native half of the `cutaway` Python package (PyO3, abi3).
//!
//! Every function here is a thin shell over the egui-free functions the `cutaway` CLI commands
//! call (`io`, `session`, `cutting`, `metrics`, `annotate`/`view` headless rendering, `export`,
//! `expose`, `batch`), so Python and the CLI compute the same things. Errors become
//! `cutaway.CutawayError` carrying the CLI's one-line message (without its `error: ` prefix);
//! the GIL is released while Rust works. Arrays cross as numpy arrays: vertices `float64 (n,3)`,
//! triangles `uint32 (m,3)`, images `uint8 (h,w,4)`; a result array takes over the Rust buffer
//! (no copy), an input array is read in place.
//!
//! The pure-Python half (`app/python/python/cutaway/`) gives these the shape users know from
//! trimesh and nibabel.

mod arrays;
mod batch;
mod mesh;
mod session;
mod volume;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    _cutaway,
    CutawayError,
    PyException,
    "An error of Cutaway: the one line the `cutaway` command would print, naming the file and the problem."
);

/// A Rust error as the Python exception carrying the CLI's one line.
pub(crate) fn to_py(error: anyhow::Error) -> PyErr {
    let line = cutaway::platform::errors::error_line(&error);
    let text = line.strip_prefix("error: ").unwrap_or(&line).to_owned();
    CutawayError::new_err(text)
}

/// Runs `work` with the GIL released and turns its error into a [`CutawayError`].
pub(crate) fn detached<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> anyhow::Result<T> + Send,
) -> PyResult<T> {
    py.detach(work).map_err(to_py)
}

#[pymodule]
fn _cutaway(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("CutawayError", m.py().get_type::<CutawayError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    volume::register(m)?;
    mesh::register(m)?;
    session::register(m)?;
    batch::register(m)?;
    Ok(())
}
