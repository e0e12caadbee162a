//! Batches (`cutaway batch`'s code): a recipe checked, one case run in this process, a case
//! found complete, and the summary (`metrics.csv`, `index.html`) written.

use std::path::{Path, PathBuf};

use cutaway::batch::{
    CaseResult, Recipe, check_cases, completed, run_case, status_line, write_summary,
};
use pyo3::prelude::*;

use crate::detached;

/// A recipe given as a file path or as JSON text (starting with `{`).
fn recipe_of(text: &str) -> anyhow::Result<Recipe> {
    if text.trim_start().starts_with('{') {
        Recipe::parse(text)
    } else {
        Recipe::read(Path::new(text))
    }
}

fn parse_result(json: &str) -> anyhow::Result<CaseResult> {
    Ok(serde_json::from_str(json)?)
}

/// Checks the recipe and the case folders, creates `out`; returns the recipe as JSON text.
#[pyfunction]
fn batch_prepare(
    py: Python<'_>,
    recipe: String,
    cases: Vec<PathBuf>,
    out: PathBuf,
) -> PyResult<String> {
    detached(py, move || {
        let recipe = recipe_of(&recipe)?;
        check_cases(&cases)?;
        std::fs::create_dir_all(&out)
            .map_err(|e| anyhow::anyhow!("{}: cannot create the folder: {e}", out.display()))?;
        Ok(serde_json::to_string(&recipe)?)
    })
}

/// The result of a case already complete in `out` with this recipe (status `skipped`), or None.
#[pyfunction]
fn batch_completed(
    py: Python<'_>,
    recipe: String,
    case_dir: PathBuf,
    out: PathBuf,
) -> PyResult<Option<String>> {
    detached(py, move || {
        let recipe = Recipe::parse(&recipe)?;
        let case = cutaway::batch::case::case_name(&case_dir);
        Ok(match completed(&out, &case, &recipe) {
            Some(mut done) => {
                done.status = "skipped".to_owned();
                Some(serde_json::to_string(&done)?)
            }
            None => None,
        })
    })
}

/// Runs one case in this process (GIL released); returns its result as JSON text.
#[pyfunction]
fn batch_case(py: Python<'_>, recipe: String, case_dir: PathBuf, out: PathBuf) -> PyResult<String> {
    detached(py, move || {
        let recipe = Recipe::parse(&recipe)?;
        Ok(serde_json::to_string(&run_case(&recipe, &case_dir, &out))?)
    })
}

/// The result of a case whose worker failed before it could report (`why`).
#[pyfunction]
fn batch_failed(recipe: String, case_dir: PathBuf, why: String) -> PyResult<String> {
    let recipe = Recipe::parse(&recipe).map_err(crate::to_py)?;
    let error = anyhow::anyhow!(why).context(case_dir.display().to_string());
    let result = CaseResult::failed(
        &cutaway::batch::case::case_name(&case_dir),
        &recipe,
        0.0,
        &error,
    );
    serde_json::to_string(&result).map_err(|e| crate::to_py(e.into()))
}

/// Writes `metrics.csv` and `index.html` into `out` from the cases' results.
#[pyfunction]
fn batch_summary(
    py: Python<'_>,
    out: PathBuf,
    title: String,
    results: Vec<String>,
) -> PyResult<()> {
    detached(py, move || {
        let results = results
            .iter()
            .map(|r| parse_result(r))
            .collect::<anyhow::Result<Vec<_>>>()?;
        write_summary(&out, &title, &results)
    })
}

/// The status line `cutaway batch` prints for an ended case.
#[pyfunction]
fn batch_status_line(done: usize, total: usize, result: String) -> PyResult<String> {
    let result = parse_result(&result).map_err(crate::to_py)?;
    Ok(status_line(done, total, &result))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(batch_prepare, m)?)?;
    m.add_function(wrap_pyfunction!(batch_completed, m)?)?;
    m.add_function(wrap_pyfunction!(batch_case, m)?)?;
    m.add_function(wrap_pyfunction!(batch_failed, m)?)?;
    m.add_function(wrap_pyfunction!(batch_summary, m)?)?;
    m.add_function(wrap_pyfunction!(batch_status_line, m)?)?;
    Ok(())
}
