//! # Batches: the same cutaway for every case of a cohort
//!
//! A recipe ([`recipe`], `cutaway-batch/1`) says what to do with each case folder; [`case`] does
//! it for one case with the code of the single commands (session loading, expose, the headless
//! render, the exports, the metrics) and writes `OUT/<case>/` as one output set; [`summary`]
//! writes `OUT/metrics.csv` and the static gallery `OUT/index.html`. Cases are independent and
//! idempotent: a case already complete in OUT with the same recipe is skipped, a failed case is
//! reported with its error line and stops nothing.
//!
//! Who runs a case is the caller's choice: `cutaway batch` runs each in a child process of its
//! own (`--jobs N` at a time; a crash or an out-of-memory kill costs one case and its peak memory
//! is its own), the Python package on any `concurrent.futures` executor (Dask's
//! `client.get_executor()`, a process pool). Both end in [`run_case`] and [`write_summary`].

pub mod case;
pub mod memory;
pub mod recipe;
pub mod summary;

use std::collections::HashSet;
use std::path::{Path, PathBuf};

pub use case::{CaseResult, completed, run_case};
pub use recipe::Recipe;
pub use summary::write_summary;

/// Checks the case folders before any work: each exists and is a folder, and no two share a
/// name (their outputs would collide in OUT).
pub fn check_cases(cases: &[PathBuf]) -> anyhow::Result<()> {
    if cases.is_empty() {
        anyhow::bail!("no case folders given");
    }
    let mut names = HashSet::new();
    for dir in cases {
        if !dir.is_dir() {
            anyhow::bail!("{}: not a folder", dir.display());
        }
        let name = case::case_name(dir);
        if name.starts_with('.') || name == "metrics.csv" || name == "index.html" {
            anyhow::bail!("{}: a case folder may not be named '{name}'", dir.display());
        }
        if !names.insert(name.clone()) {
            anyhow::bail!(
                "{}: a second case named '{name}' (outputs go to OUT/<case name>)",
                dir.display()
            );
        }
    }
    Ok(())
}

/// Runs `cases` with `run_one`, `jobs` at a time, in the order given; `report` hears each case
/// as it ends (its position among the ended ones, the count, the result). Returns the results in
/// case order.
pub fn run_cases(
    cases: &[PathBuf],
    jobs: usize,
    run_one: &(dyn Fn(&Path) -> CaseResult + Sync),
    report: &(dyn Fn(usize, usize, &CaseResult) + Sync),
) -> Vec<CaseResult> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let ended = std::sync::atomic::AtomicUsize::new(0);
    let results = std::sync::Mutex::new(vec![None; cases.len()]);
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, cases.len().max(1)) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                    let Some(dir) = cases.get(i) else { break };
                    let result = run_one(dir);
                    let done = ended.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                    report(done, cases.len(), &result);
                    results.lock().unwrap_or_else(|p| p.into_inner())[i] = Some(result);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .into_iter()
        .flatten()
        .collect()
}

/// One line per ended case, as the CLI prints it and the Python progress shows it.
pub fn status_line(done: usize, total: usize, r: &CaseResult) -> String {
    let memory = r
        .memory_mb
        .map(|m| format!(", {m:.0} MiB"))
        .unwrap_or_default();
    match &r.error {
        Some(e) => format!("[{done}/{total}] {}: failed: {e}", r.case),
        None => format!(
            "[{done}/{total}] {}: {} ({:.1} s{memory})",
            r.case, r.status, r.seconds
        ),
    }
}
