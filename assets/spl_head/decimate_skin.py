"""Decimates the SPL atlas skin surface for embedding (run once, offline; see assets/README.md).

Reads the legacy binary VTK POLYDATA skin (`POINTS … float`, `POLYGONS` of triangles), keeps
`TARGET` triangles with fast-simplification (quadric edge collapse), and writes a binary
little-endian PLY in the format of the other embedded meshes (`float x y z`,
`list uchar uint vertex_indices`).

    python decimate_skin.py SKIN.vtk skin.ply
"""

import sys

import fast_simplification
import numpy as np

TARGET = 40_000


def read_vtk_triangles(path):
    data = open(path, "rb").read()
    at = data.index(b"POINTS ")
    line_end = data.index(b"\n", at)
    count = int(data[at:line_end].split()[1])
    start = line_end + 1
    points = np.frombuffer(data, dtype=">f4", count=count * 3, offset=start).reshape(-1, 3)
    at = data.index(b"POLYGONS ", start + count * 12)
    line_end = data.index(b"\n", at)
    cells, size = (int(v) for v in data[at:line_end].split()[1:3])
    cell_data = np.frombuffer(data, dtype=">i4", count=size, offset=line_end + 1).reshape(-1, 4)
    assert cells == len(cell_data) and (cell_data[:, 0] == 3).all(), "triangles only"
    return points.astype(np.float64), cell_data[:, 1:].astype(np.int64)


def write_ply(path, points, faces):
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(points)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar uint vertex_indices\nend_header\n"
    )
    face_records = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<u4", 3)])
    face_records["n"] = 3
    face_records["i"] = faces
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(points.astype("<f4").tobytes())
        out.write(face_records.tobytes())


def main():
    points, faces = read_vtk_triangles(sys.argv[1])
    reduction = 1.0 - TARGET / len(faces)
    points, faces = fast_simplification.simplify(points, faces, target_reduction=reduction)
    used = np.unique(faces)
    remap = np.full(len(points), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    write_ply(sys.argv[2], points[used], remap[faces])
    print(f"{len(faces)} triangles, {len(used)} vertices")


if __name__ == "__main__":
    main()
