"""``cutaway.batch``: a recipe's cutaway for every case folder of a cohort, on any
``concurrent.futures`` executor.

Each case runs :func:`_run_case` (the native ``batch_case``: the code of ``cutaway batch``'s
children) in whatever process the executor gives it; the summary (``metrics.csv``,
``index.html``) is written by the same Rust code as the command's. A case complete in ``out``
with the same recipe is skipped before anything is submitted, so a killed batch run again
finishes the rest.
"""

from __future__ import annotations

import concurrent.futures
import json
import os
import sys
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _cutaway


def _run_case(recipe_json: str, case_dir: str, out: str) -> str:
    """One case, in the worker's process (module-level, so executors can pickle it)."""
    return _cutaway.batch_case(recipe_json, case_dir, out)


@dataclass
class BatchResult:
    """What :func:`batch` did: one dict per case (the row of ``metrics.csv``: ``case``,
    ``status`` ok/skipped/failed, ``error``, ``seconds``, ``memory_mb``, measures,
    ``outputs``), in case order."""

    out: str
    cases: List[Dict[str, Any]]

    def _count(self, status: str) -> int:
        return sum(1 for c in self.cases if c["status"] == status)

    @property
    def ok(self) -> int:
        return self._count("ok")

    @property
    def skipped(self) -> int:
        return self._count("skipped")

    @property
    def failed(self) -> int:
        return self._count("failed")

    @property
    def index_html(self) -> str:
        return os.path.join(self.out, "index.html")

    def __repr__(self) -> str:
        return (
            f"<cutaway.BatchResult {len(self.cases)} cases: {self.ok} done, "
            f"{self.skipped} already done, {self.failed} failed; {self.index_html}>"
        )


class _Progress:
    """A tqdm bar on a terminal when tqdm is installed, else one status line per case."""

    def __init__(self, total: int, enabled: Optional[bool]):
        self.total = total
        self.done = 0
        self.bar = None
        self.lines = enabled is True or (enabled is None and sys.stderr.isatty())
        if enabled is not False and sys.stderr.isatty():
            try:
                from tqdm.auto import tqdm

                self.bar = tqdm(total=total, unit="case", desc="cutaway batch")
                self.lines = False
            except ImportError:
                pass

    def case(self, result_json: str) -> None:
        self.done += 1
        line = _cutaway.batch_status_line(self.done, self.total, result_json)
        if self.bar is not None:
            self.bar.update(1)
            status = json.loads(result_json)["status"]
            if status == "failed":
                self.bar.write(line)
        elif self.lines:
            print(line, file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def batch(
    recipe: Union[str, "os.PathLike[str]", Mapping[str, Any]],
    cases: Sequence[Union[str, "os.PathLike[str]"]],
    out: Union[str, "os.PathLike[str]"],
    executor: Optional[concurrent.futures.Executor] = None,
    progress: Optional[bool] = None,
) -> BatchResult:
    """Runs ``recipe`` (a ``cutaway-batch/1`` file or dict) on every case folder into ``out``:
    ``out/<case>/…``, ``out/metrics.csv`` and the gallery ``out/index.html``.

    ``executor``: ``None`` runs the cases one after another in this process; otherwise any
    ``concurrent.futures.Executor`` — Dask's ``client.get_executor()`` (a ``LocalCluster``, or a
    cluster from dask-jobqueue on Slurm), or a ``ProcessPoolExecutor``. Give each worker one
    thread: a case's peak memory is then its own (``memory_mb``). ``progress``: a bar (tqdm) or
    status lines; default on when stderr is a terminal.

    A failed case is reported in the result and ``metrics.csv`` with its error and stops none
    of the others; it raises nothing.
    """
    if isinstance(recipe, Mapping):
        recipe_text, title = json.dumps(dict(recipe)), "Cutaway batch"
    else:
        path = os.fspath(recipe)
        recipe_text, title = path, f"Cutaway batch: {os.path.basename(path)}"
    case_dirs = [os.fspath(c) for c in cases]
    out = os.fspath(out)
    recipe_json = _cutaway.batch_prepare(recipe_text, case_dirs, out)
    results: List[Optional[str]] = [None] * len(case_dirs)
    bar = _Progress(len(case_dirs), progress)
    pending = []
    for i, case in enumerate(case_dirs):
        done = _cutaway.batch_completed(recipe_json, case, out)
        if done is not None:
            results[i] = done
            bar.case(done)
        else:
            pending.append(i)
    try:
        if executor is None:
            for i in pending:
                results[i] = _run_case(recipe_json, case_dirs[i], out)
                bar.case(results[i])
        else:
            futures = {executor.submit(_run_case, recipe_json, case_dirs[i], out): i for i in pending}
            for future in concurrent.futures.as_completed(futures):
                i = futures[future]
                try:
                    results[i] = future.result()
                except Exception as e:  # a worker that died: the case failed, the others go on
                    results[i] = _cutaway.batch_failed(recipe_json, case_dirs[i], f"{type(e).__name__}: {e}")
                bar.case(results[i])
    finally:
        bar.close()
    finished = [r for r in results if r is not None]
    _cutaway.batch_summary(out, title, finished)
    return BatchResult(out=out, cases=[json.loads(r) for r in finished])
