"""Type hints of the native module (Rust, PyO3). Use the `cutaway` package's API instead."""

from typing import List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class CutawayError(Exception):
    """The one line the `cutaway` command would print, without its `error: ` prefix."""

Color = Tuple[int, int, int]
Vertices = npt.NDArray[np.float64]
Triangles = npt.NDArray[np.uint32]
MeshArg = Union[str, Tuple[Vertices, Triangles]]

class Volume:
    @property
    def source(self) -> str: ...
    @property
    def shape(self) -> Tuple[int, int, int]: ...
    @property
    def layer_count(self) -> int: ...
    @property
    def affine(self) -> npt.NDArray[np.float64]: ...
    @property
    def structures(self) -> List[Tuple[int, int, str, Color, int]]: ...
    def labels(self, layer: int) -> np.ndarray: ...

def read_volume_file(path: str, labels: Optional[str] = None) -> Volume: ...
def volume_from_array(
    source: str,
    dims: Tuple[int, int, int],
    affine: npt.NDArray[np.float64],
    data: np.ndarray,
    names: Sequence[Tuple[int, str, Optional[Color]]],
    table: Optional[str] = None,
) -> Volume: ...
def surfaces(
    volume: Volume,
    smoothing: Optional[float] = None,
    decimate: Optional[float] = None,
    only: Optional[Sequence[int]] = None,
) -> List[Tuple[int, int, str, Color, int, Vertices, Triangles]]: ...
def load_mesh(mesh: MeshArg) -> Tuple[Vertices, Triangles]: ...
def subtract(target: MeshArg, cutter: MeshArg) -> dict: ...

class Session:
    @staticmethod
    def load(path: str) -> "Session": ...
    @staticmethod
    def from_parts(
        models: Sequence[Tuple[str, Vertices, Triangles, str]],
        session_json: str,
        view: Optional[str] = None,
    ) -> "Session": ...
    @property
    def models(self) -> List[str]: ...
    @property
    def cutter_count(self) -> int: ...
    def set_view(self, view: str) -> None: ...
    def metrics(
        self, focus: Optional[str] = None, critical: Sequence[str] = ..., samples: Optional[int] = None
    ) -> str: ...
    def render(
        self,
        width: int = 1280,
        height: int = 800,
        labels: Optional[Sequence[str]] = None,
        transparent: bool = False,
        critical: Sequence[str] = ...,
    ) -> Tuple[npt.NDArray[np.uint8], str]: ...
    def export(
        self,
        path: str,
        title: Optional[str] = None,
        focus: Optional[str] = None,
        critical: Sequence[str] = ...,
        samples: Optional[int] = None,
    ) -> str: ...
    def save(self, path: str) -> None: ...
    def expose(self, focus: str, margin: Optional[float] = None, samples: Optional[int] = None) -> str: ...

def batch_prepare(recipe: str, cases: Sequence[str], out: str) -> str: ...
def batch_completed(recipe: str, case_dir: str, out: str) -> Optional[str]: ...
def batch_case(recipe: str, case_dir: str, out: str) -> str: ...
def batch_failed(recipe: str, case_dir: str, why: str) -> str: ...
def batch_summary(out: str, title: str, results: Sequence[str]) -> None: ...
def batch_status_line(done: int, total: int, result: str) -> str: ...
