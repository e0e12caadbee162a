"""numpy in and out: shapes and dtypes, closed surfaces, memory order, round trips through
Volume, Surface, subtract and Session. Needs no shared data."""

import numpy as np
import pytest

import cutaway


def blobs(order="C"):
    """Two labels: a box (1) and a ball (2) in a 24³ grid."""
    grid = np.zeros((24, 20, 16), dtype=np.uint8, order=order)
    grid[3:10, 4:12, 3:9] = 1
    i, j, k = np.indices(grid.shape)
    grid[(i - 16) ** 2 + (j - 10) ** 2 + (k - 8) ** 2 <= 25] = 2
    return grid


def edges_twice(triangles):
    """Each undirected edge in exactly two triangles, once each way: closed and oriented."""
    t = triangles.astype(np.int64)
    directed = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    keys = set(map(tuple, directed))
    return len(keys) == len(directed) and all((b, a) in keys for (a, b) in keys)


def test_surfaces_of_an_array_are_closed_float64_and_uint32():
    affine = np.diag([0.5, 0.75, 2.0, 1.0])
    affine[:3, 3] = [10, -5, 3]
    found = cutaway.surfaces(blobs(), affine=affine, labels={1: "box", 2: ("ball", (255, 0, 0))})
    assert [(s.value, s.name) for s in found] == [(1, "box"), (2, "ball")]
    assert found[1].color == (255, 0, 0)
    for s in found:
        assert s.vertices.dtype == np.float64 and s.vertices.shape[1] == 3
        assert s.triangles.dtype == np.uint32 and s.triangles.shape[1] == 3
        assert s.vertices.flags["C_CONTIGUOUS"] and s.triangles.flags["C_CONTIGUOUS"]
        assert edges_twice(s.triangles)
        assert s.faces is s.triangles
    # The box spans voxels 3..9 along i: world x from 10 + 0.5 * ~3 to 10 + 0.5 * ~9.
    box = found[0].vertices
    assert 10 + 0.5 * 2 <= box[:, 0].min() and box[:, 0].max() <= 10 + 0.5 * 10


def test_memory_order_and_dtype_do_not_change_the_surfaces():
    c = cutaway.surfaces(blobs("C"), smoothing=0.3)
    f = cutaway.surfaces(np.asfortranarray(blobs()), smoothing=0.3)
    wide = cutaway.surfaces(blobs().astype(np.int64), smoothing=0.3)
    for a, b, w in zip(c, f, wide):
        np.testing.assert_array_equal(a.vertices, b.vertices)
        np.testing.assert_array_equal(a.triangles, b.triangles)
        np.testing.assert_array_equal(a.vertices, w.vertices)


def test_only_and_decimate():
    full = cutaway.surfaces(blobs(), only=[2])
    assert [s.value for s in full] == [2]
    fewer = cutaway.surfaces(blobs(), only=[2], decimate=0.5)
    assert len(fewer[0].triangles) < len(full[0].triangles)
    assert edges_twice(fewer[0].triangles)


def test_volume_round_trip_through_numpy():
    grid = blobs()
    affine = np.diag([1.0, 1.0, 1.0, 1.0])
    direct = cutaway.surfaces(grid, affine=affine)
    # A Volume's labels and affine give the same surfaces back.
    native = cutaway._cutaway.volume_from_array(
        "array", grid.shape, affine, np.ravel(grid, order="F"), []
    )
    volume = cutaway.Volume(native)
    assert volume.shape == grid.shape
    np.testing.assert_array_equal(volume.labels, grid)
    np.testing.assert_array_equal(volume.affine, affine)
    again = cutaway.surfaces(volume.labels, affine=volume.affine)
    for a, b in zip(direct, again):
        np.testing.assert_array_equal(a.vertices, b.vertices)
        np.testing.assert_array_equal(a.triangles, b.triangles)


def box_mesh(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array(
        [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0], [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
        dtype=np.float64,
    )
    t = np.array(
        [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [2, 3, 7], [2, 7, 6], [1, 2, 6], [1, 6, 5], [0, 4, 7], [0, 7, 3]],
        dtype=np.uint32,
    )
    return v, t


def test_subtract_takes_surfaces_pairs_and_gives_closed_parts():
    ball = cutaway.surfaces(blobs(), only=[2])[0]
    cutter = box_mesh((15.5, 9.5, -1.0), (30.0, 30.0, 30.0))
    a = cutaway.subtract(ball, cutter)
    b = cutaway.subtract((ball.vertices, ball.triangles), cutter)
    np.testing.assert_array_equal(a.kept.vertices, b.kept.vertices)
    np.testing.assert_array_equal(a.walls.triangles, b.walls.triangles)
    assert len(a.walls.triangles) > 0 and len(a.contour) == 1
    assert a.contour[0].shape[1] == 3
    np.testing.assert_array_equal(a.contour[0][0], a.contour[0][-1])
    assert a.kept.vertices.dtype == np.float64 and a.kept.triangles.dtype == np.uint32
    assert a.target_triangles == len(ball.triangles) and a.cutter_triangles == 12


def test_bad_arrays_raise_clearly():
    with pytest.raises(ValueError, match="3-D"):
        cutaway.surfaces(np.zeros((4, 4)))
    with pytest.raises(ValueError, match="whole numbers"):
        cutaway.surfaces(np.full((4, 4, 4), 0.5))
    with pytest.raises(cutaway.CutawayError, match="every voxel is 0"):
        cutaway.surfaces(np.zeros((4, 4, 4), dtype=np.uint8))
    with pytest.raises(cutaway.CutawayError, match="singular"):
        cutaway.surfaces(blobs(), affine=np.zeros((4, 4)))
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        cutaway.subtract((np.zeros((3, 2)), np.zeros((1, 3), np.uint32)), box_mesh((0, 0, 0), (1, 1, 1)))
    with pytest.raises(cutaway.CutawayError, match="cutter"):
        v, t = box_mesh((0, 0, 0), (1, 1, 1))
        cutaway.subtract(box_mesh((0, 0, 0), (2, 2, 2)), (v, t[:-1]))


def test_session_in_memory_saves_and_loads(tmp_path):
    parts = cutaway.surfaces(blobs(), labels={1: "box", 2: "ball"})
    s = cutaway.Session(models=parts, view="left")
    assert s.models == ["box", "ball"] and s.cutter_count == 0
    s.save(tmp_path / "blobs.json")
    back = cutaway.Session.load(tmp_path / "blobs.json")
    assert back.models == ["box", "ball"]
    metrics = back.metrics()
    assert [m["name"] for m in metrics["structures"]] == ["box", "ball"]
    with pytest.raises(cutaway.CutawayError, match="unknown view"):
        cutaway.Session(models=parts, view="sideways")
    with pytest.raises(cutaway.CutawayError, match=r"\.json"):
        s.save(tmp_path / "blobs.txt")
