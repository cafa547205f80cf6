# Type hints of the grainshock package (the C++ extension and the Python wrappers beside it).
from os import PathLike
from typing import Any, Iterable, Sequence

import numpy as np
import numpy.typing as npt

_Path = str | PathLike[str]
_Floats = npt.NDArray[np.float64]

class Snapshot:
    positions: _Floats
    velocities: _Floats | None
    radius: _Floats
    active: npt.NDArray[np.bool_]
    first_collision: _Floats | None
    columns: dict[str, _Floats]
    box: _Floats
    origin: _Floats
    dim: int
    time: float
    step: int | None
    notes: list[str]
    def __len__(self) -> int: ...
    @staticmethod
    def from_arrays(positions: npt.ArrayLike, *, velocities: npt.ArrayLike | None = ...,
                    radius: npt.ArrayLike | None = ..., active: npt.ArrayLike | None = ...,
                    first_collision: npt.ArrayLike | None = ..., box: npt.ArrayLike | None = ...,
                    time: float | None = ..., dim: int = ...,
                    columns: dict[str, npt.ArrayLike] = ...) -> Snapshot: ...

class Simulation:
    def __init__(self, *, dim: int = 2, particles: int | float = 250000, density: float = 0.25,
                 restitution: float = 0.1, cutoff: float = 1e-4, speed: float = 1.0,
                 seed: int = 1, realisation: int = 0, initial: str = "kick",
                 kick_site: str = "random", temperature: float = 1.0, lattice: float = 0.0,
                 t_max: float = 100000.0, medium: str | None = None) -> None: ...
    def run_until(self, t: float) -> None: ...
    def snapshot(self, active_only: bool = True) -> Snapshot: ...
    def sample(self) -> dict[str, Any]: ...
    def save(self, path: _Path) -> None: ...
    @staticmethod
    def load(path: _Path) -> Simulation: ...
    time: float
    paper_time: float
    collisions: int
    events: int
    dim: int
    config: dict[str, Any]

class Image:
    array: npt.NDArray[np.uint8]
    rgba: npt.NDArray[np.uint8]
    width: int
    height: int
    text: list[tuple[str, str]]
    def save(self, path: _Path, compression: int = 1) -> None: ...
    def _repr_png_(self) -> bytes: ...
    @staticmethod
    def load(path: _Path) -> Image: ...
    @staticmethod
    def from_array(array: npt.ArrayLike) -> Image: ...

class Comparison:
    alike: bool
    fraction: float
    differing: int
    blobs: int
    largest_blob_pixels: int
    largest_blob_mass: int
    same_size: bool
    max_channel_difference: int
    psnr: float
    ssim: float
    diff: Image
    def __bool__(self) -> bool: ...

class Movie:
    path: str
    frames: int
    def __init__(self, path: _Path, *, width: int = 1920, height: int = 1080,
                 fps: float | None = None, codec: str | None = None, crf: int | None = None,
                 preset: str | None = None, **render_options: Any) -> None: ...
    def add(self, frame: Snapshot | Image) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> Movie: ...
    def __exit__(self, kind: Any, value: Any, traceback: Any) -> bool: ...

def read(path: _Path, frame: int = -1, *, dim: int = 0, dt: float = 0.0,
         unwrap: bool = False) -> Snapshot: ...
def frame_count(path: _Path) -> int: ...
class Page:
    html: str
    def __init__(self, html: str) -> None: ...
    def save(self, path: str | PathLike[str]) -> None: ...
    def _repr_html_(self) -> str: ...

def view(x: Simulation | Snapshot | Sequence[Snapshot] | str | PathLike[str]
         | Sequence[str | PathLike[str]], *, color_by: str = "auto", colormap: str = "magma",
         background: str = "light", max_mb: float = 50, show_inactive: bool = False) -> Page: ...

def render(snapshots: Snapshot | Sequence[Snapshot], *, color_by: str = "auto",
           width: int = 1920, height: int = 1080, inset: bool | None = None,
           colormap: str = "magma", background: str = "light", scale: str = "auto",
           range: Sequence[float] = ..., percentiles: Sequence[float] = ...,
           range_per_frame: bool = False, framing: str = "fit", centre: Sequence[float] = ...,
           zoom: float = 1.0, azimuth: float = 30.0, elevation: float = 20.0,
           distance: float = 0.0, fov: float = 30.0, slab: float = 6.0, clip: bool = False,
           show_inactive: bool = False, colorbar: bool = True, time_label: bool = True,
           legend: bool = True, scale_bar: bool = False, msaa: int = 4, font: str = ...,
           backend: str = "auto") -> Image: ...
def compare(expected: Image | _Path | npt.ArrayLike, actual: Image | _Path | npt.ArrayLike, *,
            tolerance: int = 10, max_blob_pixels: int = 5,
            max_blob_mass: int = 150) -> Comparison: ...
def observables(snapshot: Snapshot) -> dict[str, Any]: ...
def radial_distribution(snapshot: Snapshot, *, bins: int = 50, lo: float = 0.0,
                        hi: float = 0.0) -> dict[str, Any]: ...
def speed_distribution(snapshot: Snapshot, *, bins: int = 50, lo: float = 0.0,
                       hi: float = 0.0) -> dict[str, Any]: ...
def scaled_radial_distribution(snapshot: Snapshot, alpha: float, *,
                               bins: int = 50) -> dict[str, Any]: ...
def scaled_speed_distribution(snapshot: Snapshot, alpha: float, *,
                              bins: int = 50) -> dict[str, Any]: ...
def radial_profile(snapshot: Snapshot, *, bins: int = 50) -> dict[str, Any]: ...
def band_packing(snapshot: Snapshot, *, cell: float = 10.0,
                 upper_quantile: float = 0.9) -> dict[str, Any]: ...
def inner_edge_speed(snapshot: Snapshot) -> dict[str, float]: ...
def to_ase(snapshot: Snapshot) -> Any: ...
def from_ase(atoms: Any, *, dim: int | None = None, time: float | None = None) -> Snapshot: ...
def ensemble(*, realisations: int = 8, threads: int = 1, per_decade: int = 20, bins: int = 60,
             resamples: int = 200, window: Sequence[float] = ...,
             **physics: Any) -> dict[str, Any]: ...
