//! `cutaway batch RECIPE.json CASE_DIR… --out OUT [--jobs N] [--json]`: the recipe's cutaway for
//! every case folder ([`crate::batch`]). Each case runs in a child process of its own (this
//! binary with `--one-case`), `--jobs` at a time: a case that crashes or runs out of memory
//! costs that case only, and its peak memory is measured alone. One status line per case goes
//! to stderr as it ends; OUT gets `<case>/…`, `metrics.csv` and `index.html`. A case complete in
//! OUT with the same recipe is skipped, so a killed batch run again finishes the rest. The
//! command fails (after writing the summary) when a case failed.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::Context as _;

use crate::batch::{CaseResult, Recipe, check_cases, completed, run_case, status_line};

#[derive(Debug, clap::Args)]
pub struct BatchArgs {
    /// The recipe (`cutaway-batch/1`): volume, structures, view, cutaway, outputs.
    pub recipe: PathBuf,
    /// Case folders, each holding one case's volume (and image).
    #[arg(required = true)]
    pub cases: Vec<PathBuf>,
    /// Output folder: `<case>/…`, `metrics.csv`, `index.html`.
    #[arg(long)]
    pub out: PathBuf,
    /// Cases run at once (default 1).
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Print the cases' results as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Run the one case given in this process and print its result (what each child does).
    #[arg(long, hide = true)]
    pub one_case: bool,
}

/// What `--json` prints (field order is the contract's).
#[derive(serde::Serialize)]
struct BatchReport<'a> {
    ok: usize,
    skipped: usize,
    failed: usize,
    cases: &'a [CaseResult],
}

pub fn run(args: &BatchArgs) -> anyhow::Result<()> {
    if !(1..=256).contains(&args.jobs) {
        anyhow::bail!("--jobs {} is outside 1..256", args.jobs);
    }
    let recipe = Recipe::read(&args.recipe)?;
    check_cases(&args.cases)?;
    if args.one_case {
        let result = run_case(&recipe, &args.cases[0], &args.out);
        println!("{}", serde_json::to_string(&result)?);
        return Ok(());
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create the folder", args.out.display()))?;
    let exe = std::env::current_exe().context("cannot find the cutaway binary")?;
    let run_one = |dir: &Path| -> CaseResult {
        let case = crate::batch::case::case_name(dir);
        if let Some(mut done) = completed(&args.out, &case, &recipe) {
            done.status = "skipped".to_owned();
            return done;
        }
        child_case(&exe, args, dir, &recipe)
    };
    let report = |done: usize, total: usize, r: &CaseResult| {
        eprintln!("{}", status_line(done, total, r));
    };
    let results = crate::batch::run_cases(&args.cases, args.jobs, &run_one, &report);
    let title = format!(
        "Cutaway batch: {}",
        args.recipe
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    );
    crate::batch::write_summary(&args.out, &title, &results)?;
    let count = |s: &str| results.iter().filter(|r| r.status == s).count();
    let (ok, skipped, failed) = (count("ok"), count("skipped"), count("failed"));
    if args.json {
        let report = BatchReport {
            ok,
            skipped,
            failed,
            cases: &results,
        };
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!(
            "{} cases: {ok} done, {skipped} already done, {failed} failed; {}",
            results.len(),
            args.out.join("index.html").display()
        );
    }
    if failed > 0 {
        anyhow::bail!(
            "{}: {failed} of {} cases failed (see metrics.csv)",
            args.out.display(),
            results.len()
        );
    }
    Ok(())
}

/// Runs one case in a child process and reads its result; a child that dies is the case's
/// failure.
fn child_case(exe: &Path, args: &BatchArgs, dir: &Path, recipe: &Recipe) -> CaseResult {
    let output = Command::new(exe)
        .arg("batch")
        .arg(&args.recipe)
        .arg(dir)
        .arg("--out")
        .arg(&args.out)
        .arg("--one-case")
        .stdin(std::process::Stdio::null())
        .output();
    let died = |why: String| {
        let error = anyhow::anyhow!(why).context(dir.display().to_string());
        CaseResult::failed(&crate::batch::case::case_name(dir), recipe, 0.0, &error)
    };
    match output {
        Err(e) => died(format!("could not start the case's process: {e}")),
        Ok(out) => match serde_json::from_slice::<CaseResult>(&out.stdout) {
            Ok(result) => result,
            Err(_) => {
                let stderr = String::from_utf8_lossy(&out.stderr);
                let last = stderr.lines().last().unwrap_or("").trim();
                died(format!("the case's process ended ({}) {last}", out.status))
            }
        },
    }
}
