"""Batches: four cases derived from the shared chest volume, run serially and on a Dask
LocalCluster (two single-threaded workers) with the same outputs; a killed batch run again
finishes without redoing complete cases; a failed case is reported and stops nothing."""

import csv
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import cutaway

RECIPE = {
    "format": "cutaway-batch/1",
    "volume": "chest_labels.n*",
    "structures": ["tissue", "ribs", "right_lung", "left_lung"],
    "view": "anterior",
    "expose": {"focus": "right_lung"},
    "outputs": {"png": {"width": 160, "height": 120}, "glb": True, "metrics": {"critical": ["left_lung"]}},
}


def write_nrrd(path: Path, labels: np.ndarray, affine: np.ndarray):
    """A raw little-endian uint8 NRRD in RAS (i fastest)."""
    d = affine[:3, :3]
    vec = lambda c: "(" + ",".join(repr(float(x)) for x in c) + ")"  # noqa: E731
    header = (
        "NRRD0004\ntype: uint8\ndimension: 3\nspace: right-anterior-superior\n"
        f"sizes: {labels.shape[0]} {labels.shape[1]} {labels.shape[2]}\n"
        f"space directions: {vec(d[:, 0])} {vec(d[:, 1])} {vec(d[:, 2])}\n"
        f"space origin: {vec(affine[:3, 3])}\nencoding: raw\nendian: little\n\n"
    )
    path.write_bytes(header.encode() + np.ravel(labels.astype(np.uint8), order="F").tobytes())


@pytest.fixture(scope="module")
def cases(anatomy, tmp_path_factory):
    """a: the file itself; b: cropped; c: stored with its first axis flipped (same anatomy);
    d: the ribs' labels dropped below the lungs' top (a different cohort member)."""
    src = anatomy / "volumes" / "nifti_chest"
    root = tmp_path_factory.mktemp("cases")
    vol = cutaway.read_volume(src / "chest_labels.nii.gz")
    labels, affine = np.asarray(vol.labels), vol.affine
    dirs = []
    for name in "abcd":
        d = root / f"case_{name}"
        d.mkdir()
        shutil.copy(src / "chest_labels.txt", d / "chest_labels.txt")
        dirs.append(d)
    os.symlink(src / "chest_labels.nii.gz", dirs[0] / "chest_labels.nii.gz")
    write_nrrd(dirs[1] / "chest_labels.nrrd", labels[:, :, 1:], affine @ _shift(0, 0, 1))
    flip = np.eye(4)
    flip[0, 0], flip[0, 3] = -1, labels.shape[0] - 1
    write_nrrd(dirs[2] / "chest_labels.nrrd", labels[::-1], affine @ flip)
    fewer = labels.copy()
    fewer[:, :, : labels.shape[2] // 3][fewer[:, :, : labels.shape[2] // 3] == 1] = 7
    write_nrrd(dirs[3] / "chest_labels.nrrd", fewer, affine)
    return dirs


def _shift(i, j, k):
    m = np.eye(4)
    m[:3, 3] = [i, j, k]
    return m


def rows(out: Path):
    with open(out / "metrics.csv", newline="") as f:
        return list(csv.DictReader(f))


def comparable(row):
    return {k: v for k, v in row.items() if k not in ("seconds", "memory_mb")}


def test_local_cluster_equals_serial(cases, tmp_path):
    distributed = pytest.importorskip("distributed")
    serial = cutaway.batch(RECIPE, cases, out=tmp_path / "serial", progress=False)
    assert serial.ok == 4 and serial.failed == 0, serial.cases
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            parallel = cutaway.batch(RECIPE, cases, out=tmp_path / "dask", executor=client.get_executor(), progress=False)
    assert parallel.ok == 4, parallel.cases
    assert [comparable(r) for r in rows(tmp_path / "serial")] == [comparable(r) for r in rows(tmp_path / "dask")]
    for case in cases:
        for name in ("picture.png", "scene.glb", "metrics.json"):
            a = (tmp_path / "serial" / case.name / name).read_bytes()
            b = (tmp_path / "dask" / case.name / name).read_bytes()
            assert a == b, f"{case.name}/{name}"
    first = rows(tmp_path / "serial")[0]
    assert first["status"] == "ok" and int(first["cutters"]) > 0
    assert float(first["exposure_after"]) > float(first["exposure_before"])
    assert all(float(r["memory_mb"]) > 0 for r in rows(tmp_path / "dask"))
    index = (tmp_path / "dask" / "index.html").read_text()
    for case in cases:
        assert f'src="{case.name}/picture.png"' in index
    # The flipped and cropped copies are the same anatomy: the same structures, exposure close.
    by_case = {r["case"]: r for r in rows(tmp_path / "serial")}
    assert by_case["case_c"]["structures"] == by_case["case_a"]["structures"] == "4"


def test_killed_batch_finishes_without_redoing_complete_cases(cases, tmp_path):
    out = tmp_path / "out"
    script = (
        "import sys, cutaway, json\n"
        f"cutaway.batch(json.loads(sys.argv[1]), sys.argv[2:], out={str(out)!r}, progress=False)\n"
    )
    import json

    child = subprocess.Popen([sys.executable, "-c", script, json.dumps(RECIPE), *map(str, cases)])
    deadline = time.time() + 600
    while not (out / cases[0].name / "case.json").exists():
        assert child.poll() is None, "the batch ended before it could be killed"
        assert time.time() < deadline
        time.sleep(0.05)
    child.send_signal(signal.SIGKILL)
    child.wait()
    complete = [c for c in cases if (out / c.name / "case.json").exists()]
    assert 1 <= len(complete) < len(cases), "kill the batch between cases"
    before = {c.name: (out / c.name / "case.json").stat().st_mtime_ns for c in complete}
    result = cutaway.batch(RECIPE, cases, out=out, progress=False)
    status = {c["case"]: c["status"] for c in result.cases}
    for c in cases:
        assert status[c.name] == ("skipped" if c in complete else "ok"), status
    for name, mtime in before.items():
        assert (out / name / "case.json").stat().st_mtime_ns == mtime
    assert not list(out.glob("*/.cutaway-set.*")), "an interrupted set left behind"
    assert [r["status"] for r in rows(out)] == [status[c.name] for c in cases]


def test_failed_case_is_reported_and_stops_nothing(cases, tmp_path, cli):
    empty = tmp_path / "case_empty"
    empty.mkdir()
    order = [cases[0], empty]
    result = cutaway.batch(RECIPE, order, out=tmp_path / "py", progress=False)
    assert [c["status"] for c in result.cases] == ["ok", "failed"]
    assert "no volume named like 'chest_labels.n*'" in result.cases[1]["error"]
    assert str(empty) in result.cases[1]["error"]
    # The command does the same, reports the failure and exits non-zero after the summary.
    recipe = tmp_path / "recipe.json"
    import json

    recipe.write_text(json.dumps(RECIPE))
    done = subprocess.run(
        [str(cli), "batch", str(recipe), *map(str, order), "--out", str(tmp_path / "cli"), "--jobs", "2"],
        capture_output=True,
        text=True,
    )
    assert done.returncode != 0
    assert "1 of 2 cases failed" in done.stderr
    assert "[2/2]" in done.stderr or "[1/2]" in done.stderr
    cli_rows = rows(tmp_path / "cli")
    assert [r["status"] for r in cli_rows] == ["ok", "failed"]
    assert comparable(cli_rows[0]) == comparable(rows(tmp_path / "py")[0])
    assert (tmp_path / "cli" / cases[0].name / "picture.png").read_bytes() == (
        tmp_path / "py" / cases[0].name / "picture.png"
    ).read_bytes()
