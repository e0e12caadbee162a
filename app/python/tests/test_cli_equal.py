"""The package computes what the `cutaway` command computes: surfaces file for file, subtract's
meshes, the rendered picture pixel for pixel, and the same one-line errors."""

import os
from pathlib import Path

import numpy as np
import pytest

import cutaway
from conftest import read_obj, read_png, run_cli

REPO = Path(__file__).resolve().parents[3]
SESSION = REPO / "tests" / "data" / "main_default_scene.session.json"


def test_surfaces_equal_cutaway_surfaces_file_for_file(anatomy, cli, tmp_path):
    volume = anatomy / "volumes" / "nifti_chest" / "chest_labels.nii.gz"
    run_cli(cli, "surfaces", volume, "--out", tmp_path, "--format", "obj", "--smoothing", "0.4")
    files = sorted(tmp_path.glob("*.obj"), key=lambda p: int(p.name.split("_")[0]))
    found = cutaway.surfaces(volume, smoothing=0.4)
    assert len(files) == len(found) > 3
    for file, surface in zip(files, found):
        assert file.name.startswith(f"{surface.value}_{surface.name}")
        vertices, triangles = read_obj(file)
        np.testing.assert_array_equal(surface.vertices, vertices)
        np.testing.assert_array_equal(surface.triangles, triangles)
    # The same volume handed over as an array with its affine and names gives the same surfaces.
    vol = cutaway.read_volume(volume)
    again = cutaway.surfaces(vol.labels, affine=vol.affine, labels=vol.names, smoothing=0.4)
    for a, b in zip(found, again):
        assert (a.value, a.name) == (b.value, b.name)
        np.testing.assert_array_equal(a.vertices, b.vertices)
        np.testing.assert_array_equal(a.triangles, b.triangles)


def write_box_obj(path, lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (3, 4, 8, 7), (2, 3, 7, 6), (1, 5, 8, 4)]
    text = "".join(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in v) + "".join("f %d %d %d %d\n" % q for q in quads)
    Path(path).write_text(text)


def test_subtract_equals_cutaway_subtract(anatomy, cli, tmp_path):
    target = anatomy / "head_brain_spl_atlas" / "Model_4_left_lateral_ventricle.vtk"
    vertices, _ = cutaway._cutaway.load_mesh(str(target))
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    middle = (lo + hi) / 2
    cutter = tmp_path / "cutter.obj"
    write_box_obj(cutter, lo - 5.0, (middle[0] + 0.37, hi[1] + 5.0, middle[2] + 0.21))
    out = tmp_path / "out"
    run_cli(cli, "subtract", target, cutter, "--out", out)
    by_path = cutaway.subtract(target, cutter)
    for name in ("kept", "walls", "removed"):
        v, t = read_obj(out / f"{name}.obj")
        mesh = getattr(by_path, name)
        assert len(t) > 0, name
        np.testing.assert_array_equal(mesh.vertices, v, err_msg=name)
        np.testing.assert_array_equal(mesh.triangles, t, err_msg=name)
    # Arrays in give the same cut as files in.
    by_arrays = cutaway.subtract(cutaway._cutaway.load_mesh(str(target)), cutaway._cutaway.load_mesh(str(cutter)))
    np.testing.assert_array_equal(by_arrays.walls.vertices, by_path.walls.vertices)
    np.testing.assert_array_equal(by_arrays.kept.triangles, by_path.kept.triangles)


def test_render_equals_cutaway_render(cli, tmp_path):
    png = tmp_path / "head.png"
    result = run_cli(cli, "render", SESSION, "--out", png, "--width", "240", "--height", "160", "--json", check=False)
    if result.returncode != 0 and "adapter" in result.stderr and os.environ.get("CUTAWAY_REQUIRE_GPU") != "1":
        pytest.skip(f"no GPU adapter: {result.stderr.strip()}")
    assert result.returncode == 0, result.stderr
    session = cutaway.Session.load(SESSION)
    image = session.render(240, 160)
    assert image.dtype == np.uint8 and image.shape == (160, 240, 4)
    assert image.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(image, read_png(png))
    import json

    reported = json.loads(result.stdout)["cutters"]
    assert len(session.last_render["cutters"]) == session.cutter_count == len(reported) > 0
    assert [c["exact"] for c in session.last_render["cutters"]] == [c["exact"] for c in reported]


def cli_error(exe, *args):
    result = run_cli(exe, *args, check=False)
    assert result.returncode != 0
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("error: ")
    return line[len("error: "):]


def test_errors_carry_the_cli_message(cli, tmp_path):
    missing = tmp_path / "no-such.nrrd"
    expected = cli_error(cli, "surfaces", missing, "--out", tmp_path / "o")
    with pytest.raises(cutaway.CutawayError) as raised:
        cutaway.read_volume(missing)
    assert str(raised.value) == expected

    expected = cli_error(cli, "surfaces", missing, "--out", tmp_path / "o", "--smoothing", "2")
    with pytest.raises(cutaway.CutawayError) as raised:
        cutaway.surfaces(np.ones((3, 3, 3), np.uint8), smoothing=2)
    assert str(raised.value) == expected

    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "cutaway-session/9", "models": []}')
    expected = cli_error(cli, "metrics", bad, "--json")
    with pytest.raises(cutaway.CutawayError) as raised:
        cutaway.Session.load(bad)
    assert str(raised.value) == expected

    out = tmp_path / "scene.obj"
    expected = cli_error(cli, "export", SESSION, "--out", out)
    with pytest.raises(cutaway.CutawayError) as raised:
        cutaway.Session.load(SESSION).export(out)
    assert str(raised.value) == expected

    expected = cli_error(cli, "metrics", SESSION, "--focus", "no such thing", "--json")
    with pytest.raises(cutaway.CutawayError) as raised:
        cutaway.Session.load(SESSION).metrics(focus="no such thing")
    assert str(raised.value) == expected
