"""Shared helpers: the shared anatomy (CUTAWAY_ANATOMY), the `cutaway` binary the results are
compared with (CUTAWAY_BIN, else the cargo target folder's debug build), OBJ and PNG readers.

Where data or the binary is missing a test skips and says why; with CUTAWAY_REQUIRE_DATA=1 (CI)
it fails instead, as the Rust tests do.
"""

import os
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest


def _missing(why: str):
    if os.environ.get("CUTAWAY_REQUIRE_DATA") == "1":
        pytest.fail(f"{why} (CUTAWAY_REQUIRE_DATA=1)")
    pytest.skip(why)


@pytest.fixture(scope="session")
def anatomy() -> Path:
    root = os.environ.get("CUTAWAY_ANATOMY")
    if not root or not Path(root, "volumes").is_dir():
        _missing("CUTAWAY_ANATOMY does not name the shared anatomy folder")
    return Path(root)


def _binary() -> Path:
    given = os.environ.get("CUTAWAY_BIN")
    if given:
        return Path(given)
    target = os.environ.get("CARGO_TARGET_DIR") or str(Path(__file__).resolve().parents[3] / "target")
    return Path(target, "debug", "cutaway")


@pytest.fixture(scope="session")
def cli() -> Path:
    exe = _binary()
    if not exe.is_file():
        _missing(f"no cutaway binary at {exe} (set CUTAWAY_BIN or build it with cargo build)")
    return exe


def run_cli(exe: Path, *args, check: bool = True) -> subprocess.CompletedProcess:
    result = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"cutaway {' '.join(map(str, args))} failed: {result.stderr}")
    return result


def read_obj(path: Path):
    """Vertices and triangles of an OBJ file the CLI wrote (`v x y z`, `f a b c`)."""
    vertices, triangles = [], []
    for line in Path(path).read_text().splitlines():
        if line.startswith("v "):
            vertices.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            triangles.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return (np.array(vertices, dtype=np.float64).reshape(-1, 3), np.array(triangles, dtype=np.uint32).reshape(-1, 3))


def read_png(path: Path) -> np.ndarray:
    """An 8-bit RGBA or RGB, non-interlaced PNG as a uint8 (h, w, 4) array (numpy only)."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    assert depth == 8 and interlace == 0 and color in (2, 6), header
    channels = 4 if color == 6 else 3
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8)
    stride = width * channels
    rows = raw.reshape(height, stride + 1)
    out = np.zeros((height, stride), dtype=np.int32)
    for y in range(height):
        f, line = rows[y, 0], rows[y, 1:].astype(np.int32)
        prior = out[y - 1] if y else np.zeros(stride, dtype=np.int32)
        if f == 0:
            out[y] = line
        elif f == 2:
            out[y] = (line + prior) & 0xFF
        else:
            cur = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                a = cur[x - channels] if x >= channels else 0
                b = prior[x]
                c = prior[x - channels] if x >= channels else 0
                if f == 1:
                    p = a
                elif f == 3:
                    p = (a + b) // 2
                else:
                    pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + p) & 0xFF
            out[y] = cur
    image = out.astype(np.uint8).reshape(height, width, channels)
    if channels == 3:
        image = np.concatenate([image, np.full((height, width, 1), 255, np.uint8)], axis=2)
    return image
