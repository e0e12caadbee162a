"""Cutaway from Python: context-preserving cutaways of segmented anatomy.

The same Rust code as the ``cutaway`` command, with numpy in and out::

    import cutaway
    vol = cutaway.read_volume("hncma-atlas.nrrd")          # labels, affine, names, colours
    parts = cutaway.surfaces(vol, smoothing=0.5)            # closed, named surfaces
    s = cutaway.Session(models=parts, view="anterior")
    s.expose("left hippocampus")                            # cutters that open the view
    image = s.render(800, 600)                              # uint8 (h, w, 4)
    s.export("head.html"); s.save("head.json")

Vertices are ``float64 (n, 3)``, triangles ``uint32 (m, 3)``. Errors raise
:class:`CutawayError` with the one-line message the command prints. Work runs with the GIL
released, so threads run cases in parallel; :func:`batch` runs a recipe over many case folders
on any ``concurrent.futures`` executor (Dask ``client.get_executor()``, a process pool).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _cutaway
from ._cutaway import CutawayError
from ._batch import BatchResult, batch

__all__ = [
    "CutawayError",
    "Volume",
    "Surface",
    "Mesh",
    "Cut",
    "RegionCut",
    "Session",
    "BatchResult",
    "read_volume",
    "surfaces",
    "subtract",
    "batch",
]
__version__ = _cutaway.__version__

PathLike = Union[str, "os.PathLike[str]"]


class Volume:
    """A label volume: label maps on a grid placed in RAS millimetres by ``affine``, and one
    structure per label value present (value, name, colour)."""

    def __init__(self, native: "_cutaway.Volume"):
        self._native = native
        self._labels: Optional[np.ndarray] = None

    @property
    def source(self) -> str:
        """The file the volume came from (or the name given to an array)."""
        return self._native.source

    @property
    def shape(self) -> Tuple[int, int, int]:
        """Grid size (i, j, k)."""
        return self._native.shape

    @property
    def affine(self) -> np.ndarray:
        """Voxel index to world RAS millimetres, a 4×4 ``float64`` matrix (as nibabel's)."""
        return self._native.affine

    @property
    def labels(self) -> np.ndarray:
        """The (first) label map, an (i, j, k) integer array in Fortran order."""
        if self._labels is None:
            self._labels = self._native.labels(0)
        return self._labels

    def layer(self, index: int) -> np.ndarray:
        """Label map ``index`` (overlapping Slicer segmentations hold several)."""
        return self._native.labels(index)

    @property
    def layer_count(self) -> int:
        return self._native.layer_count

    @property
    def structures(self) -> List[Dict[str, Any]]:
        """One dict per structure: layer, value, name, color (sRGB 0..255), voxels."""
        return [
            {"layer": l, "value": v, "name": n, "color": c, "voxels": x}
            for (l, v, n, c, x) in self._native.structures
        ]

    @property
    def names(self) -> Dict[int, str]:
        """Label value → name."""
        return {v: n for (_, v, n, _, _) in self._native.structures}

    @property
    def colors(self) -> Dict[int, Tuple[int, int, int]]:
        """Label value → sRGB colour (0..255)."""
        return {v: c for (_, v, _, c, _) in self._native.structures}

    def __repr__(self) -> str:
        return f"<cutaway.Volume {self.source!r} {self.shape} {len(self.names)} labels>"


def read_volume(path: PathLike, labels: Optional[PathLike] = None) -> Volume:
    """Reads a label volume (.nrrd, .seg.nrrd, .nhdr, .nii, .nii.gz, or a folder of masks), as
    ``cutaway surfaces`` does. ``labels``: a colour table naming the labels (Slicer .ctbl/.txt,
    FreeSurfer LUT, ITK-SNAP); without one, names come from the file or a table beside it."""
    return Volume(_cutaway.read_volume_file(os.fspath(path), None if labels is None else os.fspath(labels)))


@dataclass
class Surface:
    """One closed surface of a label: ``vertices`` float64 (n,3) in RAS mm, ``triangles``
    uint32 (m,3), outward-facing."""

    value: int
    name: str
    color: Tuple[int, int, int]
    vertices: np.ndarray
    triangles: np.ndarray
    layer: int = 0
    voxels: int = 0

    @property
    def faces(self) -> np.ndarray:
        """``triangles`` (trimesh's name)."""
        return self.triangles

    def to_trimesh(self):
        """The surface as a ``trimesh.Trimesh`` (trimesh must be installed)."""
        import trimesh

        return trimesh.Trimesh(self.vertices, self.triangles, process=False)


def _label_array(array: np.ndarray) -> Tuple[np.ndarray, Tuple[int, int, int]]:
    """A 3-D integer label array as a flat, i-fastest uint8/16/32 array (no copy when it is
    Fortran-ordered already, as nibabel's are)."""
    a = np.asanyarray(array)
    if a.ndim != 3:
        raise ValueError(f"a label volume must be 3-D, not of shape {a.shape}")
    if a.dtype.kind == "f":
        if not np.all(np.isfinite(a)) or np.any(a != np.round(a)):
            raise ValueError("a label volume must hold whole numbers (labels), not intensities")
    elif a.dtype.kind not in "iub":
        raise ValueError(f"a label volume must hold integers, not {a.dtype}")
    if a.size and (a.min() < 0 or a.max() > 0xFFFFFFFF):
        raise ValueError("labels must be in 0..4294967295")
    top = int(a.max()) if a.size else 0
    kind = np.uint8 if top <= 0xFF else np.uint16 if top <= 0xFFFF else np.uint32
    flat = np.ravel(a, order="F")
    if flat.dtype != kind:
        flat = flat.astype(kind)
    return np.ascontiguousarray(flat), a.shape


def _names(labels: Any) -> Tuple[List[Tuple[int, str, Optional[Tuple[int, int, int]]]], Optional[str]]:
    if labels is None:
        return [], None
    if isinstance(labels, (str, os.PathLike)):
        return [], os.fspath(labels)
    out = []
    for value, info in dict(labels).items():
        if isinstance(info, str):
            out.append((int(value), info, None))
        else:
            name, color = info
            out.append((int(value), str(name), tuple(int(c) for c in color)))
    return out, None


def surfaces(
    volume_or_array: Union[Volume, np.ndarray, PathLike],
    affine: Optional[np.ndarray] = None,
    labels: Union[None, PathLike, Mapping[int, Any]] = None,
    smoothing: Optional[float] = None,
    decimate: Optional[float] = None,
    only: Optional[Iterable[int]] = None,
) -> List[Surface]:
    """One closed surface per label, as ``cutaway surfaces`` makes them.

    ``volume_or_array``: a :class:`Volume`, a path, or a 3-D integer array indexed (i, j, k)
    (nibabel's ``img.dataobj``) with ``affine`` its 4×4 voxel-to-RAS matrix (identity if
    omitted). ``labels`` names the labels: a colour table path, or ``{value: name}`` /
    ``{value: (name, (r, g, b))}``. ``smoothing`` 0 (voxel surface) .. 1; ``decimate`` keeps
    that fraction of each surface's triangles (checked to stay closed); ``only`` picks label
    values.
    """
    if isinstance(volume_or_array, Volume):
        vol = volume_or_array
        if affine is not None or (labels is not None and not isinstance(labels, (str, os.PathLike))):
            raise ValueError("affine and label names apply to an array; a Volume has its own")
        if labels is not None:
            vol = read_volume(vol.source, labels)
    elif isinstance(volume_or_array, (str, os.PathLike)):
        names, table = _names(labels)
        if names:
            raise ValueError("name a file's labels with a colour table path")
        vol = read_volume(volume_or_array, table)
    else:
        flat, shape = _label_array(volume_or_array)
        matrix = np.eye(4) if affine is None else np.asarray(affine, dtype=np.float64)
        names, table = _names(labels)
        vol = Volume(_cutaway.volume_from_array("array", shape, np.ascontiguousarray(matrix), flat, names, table))
    found = _cutaway.surfaces(
        vol._native, smoothing, decimate, None if only is None else [int(v) for v in only]
    )
    return [
        Surface(value=v, name=n, color=c, vertices=vx, triangles=tr, layer=l, voxels=x)
        for (l, v, n, c, x, vx, tr) in found
    ]


@dataclass
class Mesh:
    """A triangle mesh: ``vertices`` float64 (n,3), ``triangles`` uint32 (m,3)."""

    vertices: np.ndarray
    triangles: np.ndarray

    @property
    def faces(self) -> np.ndarray:
        return self.triangles


@dataclass
class RegionCut:
    """One region's share of a cut: its kept part, walls and removed part, the volume of its
    removed solid and whether both of its solids are closed."""

    index: int
    kept: Mesh
    walls: Mesh
    removed: Mesh
    removed_volume: float
    closed: bool


@dataclass
class Cut:
    """What :func:`subtract` returns: ``kept`` (the target outside the cutter), ``walls`` (the
    cutter's surface inside the target), ``removed`` (the target inside the cutter),
    ``contour`` (closed polylines, first point repeated), ``regions`` (per region, when the
    target has more than one) and the timings of ``cutaway subtract --json``."""

    kept: Mesh
    walls: Mesh
    removed: Mesh
    contour: List[np.ndarray]
    regions: List[RegionCut]
    target_triangles: int
    cutter_triangles: int
    cut_ms: float
    materialize_ms: float


def _mesh_arg(mesh: Any) -> Any:
    """A path, a ``(vertices, triangles)`` pair, or anything with ``vertices`` and
    ``triangles``/``faces`` (a Surface, a trimesh), as the native module takes it."""
    if isinstance(mesh, (str, os.PathLike)):
        return os.fspath(mesh)
    if isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        v, t = mesh
    else:
        v = mesh.vertices
        t = getattr(mesh, "triangles", None)
        if t is None:
            t = mesh.faces
    v = np.ascontiguousarray(v, dtype=np.float64)
    t = np.asarray(t)
    if t.size and (t.min() < 0 or t.max() > 0xFFFFFFFF):
        raise ValueError("triangle indices must be in 0..4294967295")
    return (v, np.ascontiguousarray(t, dtype=np.uint32))


def _mesh(pair: Tuple[np.ndarray, np.ndarray]) -> Mesh:
    return Mesh(vertices=pair[0], triangles=pair[1])


def subtract(target: Any, cutter: Any) -> Cut:
    """Cuts the closed ``cutter`` out of every region of ``target`` with Cutaway's exact
    boolean (``cutaway subtract``). Each may be a path, a ``(vertices, triangles)`` pair, a
    :class:`Surface` or a trimesh."""
    r = _cutaway.subtract(_mesh_arg(target), _mesh_arg(cutter))
    regions = [
        RegionCut(
            index=g["index"],
            kept=_mesh(g["kept"]),
            walls=_mesh(g["walls"]),
            removed=_mesh(g["removed"]),
            removed_volume=g["removed_volume"],
            closed=g["closed"],
        )
        for g in r["regions"]
    ]
    return Cut(
        kept=_mesh(r["kept"]),
        walls=_mesh(r["walls"]),
        removed=_mesh(r["removed"]),
        contour=list(r["contour"]),
        regions=regions,
        target_triangles=r["target_triangles"],
        cutter_triangles=r["cutter_triangles"],
        cut_ms=r["cut_ms"],
        materialize_ms=r["materialize_ms"],
    )


def _model(i: int, m: Any) -> Tuple[Tuple[str, np.ndarray, np.ndarray, str], Dict[str, Any]]:
    """One in-memory model and its session entry."""
    entry: Dict[str, Any] = {"path": f"memory/{i}"}
    if isinstance(m, Mapping):
        name = str(m.get("name", f"model {i}"))
        v, t = _mesh_arg((m["vertices"], m.get("triangles", m.get("faces"))))
        for key in ("opacity", "style", "visible"):
            if key in m:
                entry[key] = m[key]
        color = m.get("color")
        group = str(m.get("group", ""))
    else:
        name = str(getattr(m, "name", None) or f"model {i}")
        v, t = _mesh_arg(m)
        color = getattr(m, "color", None)
        group = ""
    if color is not None:
        c = [float(x) for x in color]
        entry["color"] = [x / 255.0 for x in c] if max(c) > 1.0 or isinstance(color[0], (int, np.integer)) else c
    entry["name"] = name
    return (name, v, t, group), entry


class Session:
    """A scene as a Cutaway session holds it: models, cutters, camera, render settings.

    ``Session.load(path)`` reads a ``cutaway-session/2`` file; ``Session(models=…,
    cutters=…, camera=…)`` builds one in memory: ``models`` are :class:`Surface` objects,
    ``(vertices, triangles)`` pairs, trimeshes or dicts (``name``, ``vertices``,
    ``triangles``, ``color``, ``opacity``, ``style``, ``visible``); ``cutters`` are cutter
    entries as in a session file; ``camera`` is a session camera dict (``eye``, ``target``,
    ``up``, ``fov_y_deg``) or a view name (anterior, posterior, left, right, superior,
    inferior; also ``view=``). Without either the scene is framed from the front.
    """

    def __init__(
        self,
        models: Sequence[Any] = (),
        cutters: Sequence[Mapping[str, Any]] = (),
        camera: Union[None, str, Mapping[str, Any]] = None,
        view: Optional[str] = None,
        render: Optional[Mapping[str, Any]] = None,
        _native: Optional["_cutaway.Session"] = None,
    ):
        if _native is not None:
            self._native = _native
            return
        parts, entries = [], []
        for i, m in enumerate(models):
            part, entry = _model(i, m)
            parts.append(part)
            entries.append(entry)
        doc: Dict[str, Any] = {"format": "cutaway-session/2", "models": entries, "cutters": list(cutters)}
        if isinstance(camera, str):
            view = camera
        elif camera is not None:
            doc["camera"] = dict(camera)
        if render is not None:
            doc["render"] = dict(render)
        if camera is None and view is None and not cutters:
            view = "anterior"
        self._native = _cutaway.Session.from_parts(parts, json.dumps(doc), view)

    @classmethod
    def load(cls, path: PathLike) -> "Session":
        """Reads a session file (``cutaway-session/2`` or ``/1``) and its models."""
        return cls(_native=_cutaway.Session.load(os.fspath(path)))

    @property
    def models(self) -> List[str]:
        """The models' names, in order."""
        return self._native.models

    @property
    def cutter_count(self) -> int:
        return self._native.cutter_count

    def set_view(self, view: str) -> None:
        """Frames the scene from a view (anterior, posterior, left, right, superior, inferior)."""
        self._native.set_view(view)

    def metrics(
        self, focus: Optional[str] = None, critical: Sequence[str] = (), samples: Optional[int] = None
    ) -> Dict[str, Any]:
        """The measures of ``cutaway metrics --json``: per cutter and structure removed volume
        and area, wall area and depth; the focus's exposure before and after; the critical
        structures' distance to the cut walls."""
        return json.loads(self._native.metrics(focus, list(critical), samples))

    def render(
        self,
        width: int = 1280,
        height: int = 800,
        labels: Union[None, bool, Sequence[str]] = None,
        transparent: bool = False,
        critical: Sequence[str] = (),
    ) -> np.ndarray:
        """The picture ``cutaway render`` writes, as a ``uint8 (height, width, 4)`` RGBA array.
        ``labels=True`` labels every opaque structure (a list: those named); ``critical``
        colours the cut walls by their distance to those structures. The cutters' report is in
        :attr:`last_render`."""
        names = None if labels in (None, False) else ([] if labels is True else list(labels))
        image, report = self._native.render(width, height, names, transparent, list(critical))
        self.last_render = json.loads(report)
        return image

    def export(
        self,
        path: PathLike,
        title: Optional[str] = None,
        focus: Optional[str] = None,
        critical: Sequence[str] = (),
        samples: Optional[int] = None,
    ) -> Dict[str, Any]:
        """Writes the cut scene as ``cutaway export`` does: ``.glb`` (glTF 2.0) or ``.html`` (one
        self-contained web page, with ``title`` and a metrics table for ``focus`` and
        ``critical``). Returns ``cutaway export --json``'s object."""
        return json.loads(self._native.export(os.fspath(path), title, focus, list(critical), samples))

    def save(self, path: PathLike) -> None:
        """Saves the session (``.json``, atomically); meshes made in memory are written beside it."""
        self._native.save(os.fspath(path))

    def expose(self, focus: str, margin: Optional[float] = None, samples: Optional[int] = None) -> Dict[str, Any]:
        """Adds the cutters that open the camera's view onto ``focus`` (``cutaway expose``);
        returns its report (exposure before, after, unoccluded; removed volume; structures
        opened)."""
        return json.loads(self._native.expose(focus, margin, samples))

    def __repr__(self) -> str:
        return f"<cutaway.Session {len(self.models)} models, {self.cutter_count} cutters>"
