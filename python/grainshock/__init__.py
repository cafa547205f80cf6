"""grainshock: the kicked granular gas of Jabeen, Rajesh and Ray (EPL 2010) from Python.

The engine, the snapshot readers, the observables, the renderer, the movie encoder and the
golden-image comparison of the `grainshock` command, over the same C++ libraries:

    import grainshock as gs
    sim = gs.Simulation(dim=2, particles=20000, restitution=0.1, seed=1)
    sim.run_until(1000)
    snap = sim.snapshot()             # the active particles, numpy arrays
    gs.observables(snap)["radius_rms"]
    gs.render(snap).save("t1000.png") # the pixels of `grainshock render`

Wrong inputs raise ValueError with the command line's one-line message.
"""
from __future__ import annotations

from . import _grainshock as _c
from ._grainshock import (Comparison, Image, Simulation, Snapshot, band_packing, compare,
                          frame_count, inner_edge_speed, observables, radial_distribution,
                          radial_profile, read, scaled_radial_distribution,
                          scaled_speed_distribution, speed_distribution, ensemble)

__all__ = [
    "Comparison", "Image", "Movie", "Simulation", "Snapshot", "band_packing", "compare", "ensemble",
    "frame_count", "from_ase", "inner_edge_speed", "observables", "radial_distribution",
    "radial_profile", "read", "render", "scaled_radial_distribution",
    "scaled_speed_distribution", "speed_distribution", "to_ase", "view", "Page",
]


def render(snapshots, *, color_by="auto", width=1920, height=1080, inset=None, **options):
    """Draws a Snapshot (or a list of them: the Fig. 1(a) overlay, one colour per time).

    The arguments are the flags of `grainshock render` (dashes become underscores) and give the
    same pixels: color_by ("auto", "scaled-speed", "speed", "scaled-radial-velocity",
    "radial-velocity", "first-collision", "none" or a column name), width, height,
    inset (None: as the command decides, True/False: --inset/--no-inset), colormap, background
    ("light"/"dark"), scale ("auto"/"lin"/"log"), range (MIN, MAX), percentiles (LOW, HIGH),
    range_per_frame, framing ("fit"/"box"), centre, zoom, azimuth, elevation, distance, fov,
    slab (None: 6 for a kick's snapshot, 0 for others' files), clip, show_inactive, colorbar,
    time_label, legend, scale_bar, msaa, font, backend.
    snapshots may also be a path of a snapshot file (or a list of them): its last frame is
    drawn, as grainshock.read and `grainshock render` take it.
    Returns an Image (.array, .save(path); a notebook shows it).
    """
    import os

    def snapshot_of(s):
        if isinstance(s, (str, os.PathLike)):
            return read(os.fspath(s))
        if not isinstance(s, Snapshot):
            raise TypeError(f"render() takes a Snapshot, a path of a snapshot file or a list of "
                            f"them, not {type(s).__name__}")
        return s

    if isinstance(snapshots, (list, tuple)):
        snapshots = [snapshot_of(s) for s in snapshots]
    else:
        snapshots = snapshot_of(snapshots)
    return _c._render(snapshots, color_by=color_by, width=width, height=height, inset=inset,
                      **options)


class Page:
    """The page of `grainshock view`: one self-contained HTML file (no network request).

    A notebook shows it inline (an iframe whose srcdoc is the page); save(path) writes it.
    """

    def __init__(self, html):
        self.html = html

    def save(self, path):
        """Writes the page to `path` (NAME.html)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.html)

    def _repr_html_(self):
        import html as _html
        return ('<iframe style="width:100%;height:760px;border:1px solid #ccc" '
                'sandbox="allow-scripts" srcdoc="' + _html.escape(self.html, quote=True) +
                '"></iframe>')


def view(x, *, color_by="auto", colormap="magma", background="light", max_mb=50,
         show_inactive=False):
    """The page of `grainshock view` for a Simulation (its snapshot now), a Snapshot, a list of
    snapshots, or a folder or file path (a run, ensemble or figures folder, snapshot files), or
    a list of paths. The colours are those of render() with the same color_by, colormap and
    background. Returns a Page: shown inline in Jupyter, .save(path) writes it.
    """
    import os
    if isinstance(x, Simulation):
        x = x.snapshot()
    if isinstance(x, Snapshot):
        x = [x]
    if isinstance(x, (str, os.PathLike)):
        x = [x]
    items = list(x)
    if items and all(isinstance(i, Snapshot) for i in items):
        return Page(_c._view_snapshots(items, color_by, colormap, background, max_mb,
                                       show_inactive))
    if items and all(isinstance(i, (str, os.PathLike)) for i in items):
        return Page(_c._view_paths([os.fspath(i) for i in items], color_by, colormap,
                                   background, max_mb, show_inactive))
    raise TypeError("view: give a Simulation, a Snapshot, a list of snapshots, or paths")


class Movie:
    """An MP4 (or .mkv, ...) written with the encoder of `grainshock movie`.

        with grainshock.Movie("blast.mp4", fps=30) as m:
            for t in times:
                sim.run_until(t)
                m.add(sim.snapshot())

    add() takes a Snapshot (drawn with the render options given here, at the movie's size) or
    an Image of the movie's size. The file appears complete when the block ends, and not at all
    if it ends with an exception. fps, codec, crf and preset not given are those of `grainshock
    movie` (30 frames/s, H.264 at CRF 18, x264's ultrafast preset).
    """

    def __init__(self, path, *, width=1920, height=1080, fps=None, codec=None, crf=None,
                 preset=None, **render_options):
        self.path = str(path)
        # Only what was given goes to the encoder, whose defaults are the C++ MovieOptions' own.
        given = {k: v for k, v in dict(fps=fps, codec=codec, crf=crf, preset=preset).items()
                 if v is not None}
        self._writer = _c._MovieWriter(self.path, width, height, **given)
        self._size = (width, height)
        self._render = render_options
        self._closed = False

    def add(self, frame):
        """Appends one frame: a Snapshot (rendered) or an Image of the movie's size."""
        if isinstance(frame, Snapshot):
            frame = render(frame, width=self._size[0], height=self._size[1], **self._render)
        if self._closed:
            raise ValueError("Movie.add: the movie is finished")
        self._writer.add(frame, *self._size)

    @property
    def frames(self) -> int:
        """Frames added so far."""
        return self._writer.frames

    def close(self):
        """Finishes the file (idempotent)."""
        self._closed = True
        self._writer.finish()

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        self._closed = True
        if kind is None:
            self._writer.finish()
        else:
            self._writer.discard()
        return False


def to_ase(snapshot):
    """An ase.Atoms of the snapshot (needs ASE): positions (z = 0 in 2D), velocities, the box as
    the cell with pbc on the snapshot's axes, radius and active as per-atom arrays."""
    import ase
    import numpy as np

    n, d = len(snapshot), snapshot.dim
    positions = np.zeros((n, 3))
    positions[:, :d] = snapshot.positions
    cell = np.zeros(3)
    cell[:d] = snapshot.box
    atoms = ase.Atoms(numbers=np.zeros(n, dtype=int), positions=positions, cell=cell,
                      pbc=[k < d and cell[k] > 0 for k in range(3)])
    atoms.set_masses(np.ones(n))  # the engine's unit masses
    if snapshot.velocities is not None:
        velocities = np.zeros((n, 3))
        velocities[:, :d] = snapshot.velocities
        atoms.set_velocities(velocities)
    atoms.new_array("radius", np.array(snapshot.radius))
    atoms.new_array("active", np.array(snapshot.active, dtype=int))
    atoms.info["time"] = snapshot.time
    atoms.info["dim"] = d
    return atoms


def from_ase(atoms, *, dim=None, time=None):
    """A Snapshot of an ase.Atoms: positions, velocities (from momenta and masses), the cell's
    diagonal as the box; dim as atoms.info['dim'], else 2 when every z is 0, else 3."""
    import numpy as np

    positions = atoms.get_positions()
    cell = atoms.get_cell().array
    if atoms.cell.rank and np.any(cell - np.diag(np.diag(cell))):
        # As the file readers: the box is rectangular, a diagonal alone would move particles.
        raise ValueError("the cell is triclinic (non-zero tilt); only rectangular boxes are "
                         "supported")
    if dim is None:
        dim = int(atoms.info.get("dim", 2 if np.all(positions[:, 2] == 0) else 3))
    velocities = atoms.get_velocities() if atoms.has("momenta") else None
    extra = {k: atoms.arrays[k] for k in ("radius", "active") if k in atoms.arrays}
    return Snapshot.from_arrays(
        positions[:, :dim],
        velocities=None if velocities is None else velocities[:, :dim],
        radius=extra.get("radius"), active=extra.get("active"),
        box=np.diag(atoms.get_cell().array)[:dim] if atoms.cell.rank else None,
        time=atoms.info.get("time") if time is None else time, dim=dim)
