"""Benchmark: cases per minute of a batch in one process against two Dask workers, and the
Python call against the `cutaway` command on the head atlas (the overhead of the binding).

    CUTAWAY_ANATOMY=…/anatomy CUTAWAY_BIN=target/release/cutaway python app/python/benches/batch.py [--cases N]

Prints figures; checks nothing. The cases are copies of the shared chest volume (the batch
test's recipe); the atlas is `assets/spl_head/hncma-atlas.nrrd` (256³, 312 labels).
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import cutaway

REPO = Path(__file__).resolve().parents[3]
RECIPE = {
    "format": "cutaway-batch/1",
    "volume": "chest_labels.nii.gz",
    "structures": ["tissue", "ribs", "right_lung", "left_lung"],
    "view": "anterior",
    "expose": {"focus": "right_lung"},
    "outputs": {"png": {"width": 400, "height": 300}, "glb": True},
}


def make_cases(root: Path, n: int, anatomy: Path):
    src = anatomy / "volumes" / "nifti_chest"
    dirs = []
    for i in range(n):
        d = root / f"case_{i:03d}"
        d.mkdir(parents=True)
        for name in ("chest_labels.nii.gz", "chest_labels.txt"):
            shutil.copy(src / name, d / name)
        dirs.append(d)
    return dirs


def cases_per_minute(cases, out, executor=None):
    start = time.perf_counter()
    result = cutaway.batch(RECIPE, cases, out=out, executor=executor, progress=False)
    elapsed = time.perf_counter() - start
    assert result.ok == len(cases), result.cases
    memory = max(c["memory_mb"] for c in result.cases)
    return len(cases) / elapsed * 60.0, elapsed, memory


def overhead(exe: Path, tmp: Path, repeats: int):
    atlas = REPO / "assets" / "spl_head" / "hncma-atlas.nrrd"
    cli_ms, py_ms = [], []
    for _ in range(repeats):
        out = subprocess.run(
            [str(exe), "surfaces", str(atlas), "--out", str(tmp / "surfaces"), "--json"],
            capture_output=True, text=True, check=True,
        )
        cli_ms.append(json.loads(out.stdout)["surfaces_ms"])
        start = time.perf_counter()
        found = cutaway.surfaces(atlas)
        py_ms.append((time.perf_counter() - start) * 1e3)
        assert len(found) > 300
    cli, py = statistics.median(cli_ms), statistics.median(py_ms)
    print(f"surfaces of the atlas: command {cli:.0f} ms (surfaces_ms: read, surface, write files), "
          f"Python cutaway.surfaces {py:.0f} ms (read, surface, numpy arrays); "
          f"Python/command = {py / cli:.3f} (median of {repeats})")
    session = REPO / "tests" / "data" / "main_default_scene.session.json"
    cli_wall, py_wall = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run([str(exe), "render", str(session), "--out", str(tmp / "head.png"),
                        "--width", "1280", "--height", "800"], check=True, capture_output=True)
        cli_wall.append(time.perf_counter() - start)
        start = time.perf_counter()
        cutaway.Session.load(session).render(1280, 800)
        py_wall.append(time.perf_counter() - start)
    c, p = statistics.median(cli_wall), statistics.median(py_wall)
    print(f"render of the embedded head 1280×800: command {c * 1e3:.0f} ms (process, load, cut, draw, PNG), "
          f"Python Session.load + render {p * 1e3:.0f} ms; Python/command = {p / c:.3f}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=8)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    anatomy = Path(os.environ.get("CUTAWAY_ANATOMY", REPO.parent / "shared" / "anatomy"))
    exe = Path(os.environ.get("CUTAWAY_BIN", REPO / "target" / "release" / "cutaway"))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cases = make_cases(tmp / "cases", args.cases, anatomy)
        per_min, secs, mem = cases_per_minute(cases, tmp / "serial")
        print(f"1 process: {args.cases} cases in {secs:.1f} s = {per_min:.1f} cases/min (peak {mem:.0f} MiB per case)")
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with Client(cluster) as client:
                client.run(lambda: __import__("cutaway"))
                per_min2, secs2, mem2 = cases_per_minute(cases, tmp / "dask", client.get_executor())
        print(f"2 Dask workers: {args.cases} cases in {secs2:.1f} s = {per_min2:.1f} cases/min "
              f"(x{per_min2 / per_min:.2f}; peak {mem2:.0f} MiB per case; {os.cpu_count()} CPUs)")
        overhead(exe, tmp, args.repeats)


if __name__ == "__main__":
    sys.exit(main())
