"""Snapshot: numpy views that keep their owner alive and never change; read(); from_arrays."""
import gc

import numpy as np
import pytest

import grainshock as gs
from conftest import run_command


def test_a_snapshot_stays_valid_and_unchanged_after_the_simulation_moves_on(small_sim):
    snap = small_sim.snapshot(active_only=False)
    positions, velocities = snap.positions, snap.velocities
    before = positions.copy(), velocities.copy(), snap.active.copy()
    small_sim.run_until(200)
    later = small_sim.snapshot(active_only=False)
    assert not np.array_equal(later.positions, before[0])
    del snap, small_sim, later
    gc.collect()
    # The arrays alone keep the snapshot's memory alive.
    np.testing.assert_array_equal(positions, before[0])
    np.testing.assert_array_equal(velocities, before[1])


def test_arrays_are_read_only_views_of_the_right_shape(small_sim):
    snap = small_sim.snapshot(active_only=False)
    n = len(snap)
    assert n == 4000 and snap.dim == 2
    assert snap.positions.shape == (n, 2) and snap.positions.dtype == np.float64
    assert snap.velocities.shape == (n, 2)
    assert snap.radius.shape == (n,) and np.all(snap.radius == 0.5)
    assert snap.active.dtype == np.bool_ and snap.first_collision.shape == (n,)
    assert snap.time == 60 and snap.box.shape == (2,)
    with pytest.raises(ValueError):
        snap.positions[0, 0] = 1.0
    # No copy: the same memory each time.
    assert snap.positions.__array_interface__["data"] == snap.positions.__array_interface__["data"]


def test_active_only_keeps_the_particles_that_collided(small_sim):
    every = small_sim.snapshot(active_only=False)
    active = small_sim.snapshot()
    assert len(active) == int(every.active.sum()) == small_sim.sample()["active"] > 1
    np.testing.assert_array_equal(active.positions, every.positions[every.active])


@pytest.mark.parametrize("fmt,name", [("xyz", "snap_t000050.xyz"),
                                      ("ovito-xyz", "snap_t000050.xyz"),
                                      ("gsd", "snap_t000050.gsd")])
def test_read_gives_the_state_the_command_wrote(out_dir, fmt, name):
    cli = run_command("run", "--particles", 3000, "--restitution", 0.5, "--seed", 4, "--t-max", 50,
                      "--snapshot-times", 50, "--snapshot-format", fmt, "--out", out_dir / "r",
                      "--quiet")
    assert cli.returncode == 0, cli.stderr
    files = sorted((out_dir / "r" / "snapshots").iterdir())
    assert len(files) == 1
    snap = gs.read(files[0])
    sim = gs.Simulation(particles=3000, restitution=0.5, seed=4)
    sim.run_until(50)
    mine = sim.snapshot(active_only=False)
    assert snap.dim == 2 and len(snap) == len(mine)
    tol = 1e-5 if fmt == "gsd" else 1e-9  # GSD holds 32-bit floats
    # GSD boxes are centred on the origin: compare positions modulo the box.
    d = snap.positions - snap.origin - mine.positions
    d -= mine.box * np.round(d / mine.box)
    assert np.max(np.abs(d)) < tol * 100
    np.testing.assert_array_equal(snap.active, mine.active)


def test_read_counts_frames_from_the_end(out_dir):
    cli = run_command("run", "--particles", 2000, "--t-max", 40, "--snapshot-times", "10,20,40",
                      "--trajectory", "traj.gsd", "--out", out_dir / "r", "--quiet")
    assert cli.returncode == 0, cli.stderr
    path = out_dir / "r" / "traj.gsd"
    assert gs.frame_count(path) == 3
    assert gs.read(path, -1).step == gs.read(path, 2).step
    assert gs.read(path, 0).step < gs.read(path).step
    with pytest.raises(ValueError, match="frame"):
        gs.read(path, 3)
    with pytest.raises(ValueError, match="frame"):
        gs.read(path, -4)


def test_read_names_a_bad_file(out_dir):
    (out_dir / "bad.xyz").write_text("3\nnot a header\n1 2\n")
    with pytest.raises(ValueError, match="bad.xyz"):
        gs.read(out_dir / "bad.xyz")


def test_from_arrays_fills_defaults_like_the_readers():
    pos = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 3.0]])
    s = gs.Snapshot.from_arrays(pos, velocities=np.ones((3, 2)), box=[10, 10], time=2.5)
    assert s.dim == 2 and len(s) == 3 and s.time == 2.5
    np.testing.assert_array_equal(s.positions, pos)
    assert np.all(s.radius == 0.5) and np.all(s.active)
    assert list(s.box) == [10, 10]
    s3 = gs.Snapshot.from_arrays(np.zeros((4, 3)), columns={"charge": np.arange(4.0)})
    assert s3.dim == 3 and list(s3.columns["charge"]) == [0, 1, 2, 3]


def test_from_arrays_refuses_mismatched_arrays():
    with pytest.raises(ValueError, match="velocities"):
        gs.Snapshot.from_arrays(np.zeros((3, 2)), velocities=np.zeros((2, 2)))
    with pytest.raises(ValueError, match="positions"):
        gs.Snapshot.from_arrays(np.zeros((3, 5)))


def test_ase_round_trip(small_sim):
    pytest.importorskip("ase")
    snap = small_sim.snapshot()
    atoms = gs.to_ase(snap)
    assert len(atoms) == len(snap)
    back = gs.from_ase(atoms)
    assert back.dim == 2 and back.time == snap.time
    np.testing.assert_allclose(back.positions, snap.positions)
    np.testing.assert_allclose(back.velocities, snap.velocities)


def test_from_ase_refuses_a_triclinic_cell_as_the_readers_do():
    ase = pytest.importorskip("ase", reason="python3-ase is not installed")
    atoms = ase.Atoms("Ar2", positions=[[1, 1, 1], [3, 3, 3]],
                      cell=[[10, 0, 0], [2, 10, 0], [0, 0, 10]], pbc=True)
    with pytest.raises(ValueError, match="triclinic"):
        gs.from_ase(atoms)
    atoms.set_cell([10, 10, 10])
    assert gs.from_ase(atoms).box.tolist() == [10, 10, 10]
