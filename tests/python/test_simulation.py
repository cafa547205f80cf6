"""Simulation: the flags' names, defaults and checks; run_until (GIL, Ctrl-C); save/load."""
import _thread
import csv
import threading
import time

import numpy as np
import pytest

import grainshock as gs
from conftest import run_command


def test_defaults_are_the_flags():
    c = gs.Simulation(particles=500).config
    assert (c["dim"], c["density"], c["restitution"], c["cutoff"], c["speed"], c["seed"]) == (
        2, 0.25, 0.1, 1e-4, 1.0, 1)
    assert c["initial"] == "kick" and c["kick_site"] == "random"
    # The command's default medium: unbounded for kicks in 2D and 3D, the box otherwise.
    assert c["medium"] == "unbounded"
    assert gs.Simulation(particles=500, dim=3).config["medium"] == "unbounded"
    assert gs.Simulation(particles=500, initial="thermal").config["medium"] == "box"
    assert gs.Simulation(particles=500, dim=1).config["medium"] == "box"
    assert gs.Simulation(particles=500, medium="box").config["medium"] == "box"


@pytest.mark.parametrize("flag,value", [("restitution", 2.0), ("density", -1.0), ("dim", 4),
                                        ("initial", "hot"), ("kick_site", "edge"),
                                        ("particles", 1.5), ("medium", "open")])
def test_bad_value_raises_the_command_lines_message(out_dir, flag, value):
    with pytest.raises(ValueError) as e:
        gs.Simulation(**{"particles": 500, flag: value})
    message = str(e.value)
    assert "\n" not in message and ("--" + flag.replace("_", "-")) in message
    cli = run_command("run", *(["--particles", 500] if flag != "particles" else []),
                      "--" + flag.replace("_", "-"), value,
                      "--t-max", 1, "--out", out_dir / "run")
    assert cli.returncode != 0
    if flag != "particles":  # the command's integer parser words that one itself
        assert message in cli.stderr


def test_unbounded_medium_holds_what_it_made(tmp_path):
    sim = gs.Simulation(particles=20000, restitution=0.5, medium="unbounded")
    assert sim.config["medium"] == "unbounded"
    sim.run_until(200)
    made = sim.snapshot(active_only=False)
    assert sim.sample()["active"] < len(made) < 20000
    # Its box is only the region the engine addresses: framing it whole is refused.
    with pytest.raises(ValueError, match="--framing box: the snapshot is of the unbounded medium"):
        gs.render(made, framing="box", width=64, height=64)
    sim.save(tmp_path / "sim.bin")
    again = gs.Simulation.load(tmp_path / "sim.bin")
    sim.run_until(400)
    again.run_until(400)
    assert np.array_equal(sim.snapshot(active_only=False).positions,
                          again.snapshot(active_only=False).positions)


def test_run_until_matches_the_command(out_dir):
    sim = gs.Simulation(particles=3000, restitution=0.5, seed=11)
    sim.run_until(80)
    assert sim.time == 80
    cli = run_command("run", "--particles", 3000, "--restitution", 0.5, "--seed", 11,
                      "--t-max", 80, "--out", out_dir / "run", "--quiet")
    assert cli.returncode == 0, cli.stderr
    with open(out_dir / "run" / "timeseries.csv") as f:
        last = list(csv.DictReader(f))[-1]
    assert float(last["t"]) == 80
    assert int(last["collisions"]) == sim.collisions > 0
    s = sim.sample()
    assert s["active"] == int(last["active"])
    assert s["radius_rms"] == pytest.approx(float(last["radius_rms"]), rel=1e-12)


def test_run_until_refuses_the_past():
    sim = gs.Simulation(particles=500)
    sim.run_until(5)
    with pytest.raises(ValueError, match="before the simulation's time"):
        sim.run_until(1)


def test_another_thread_runs_during_run_until():
    sim = gs.Simulation(particles=50000, restitution=0.5, seed=2)
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = len(ticks)
    sim.run_until(30000)  # ~0.3 s
    during = len(ticks) - start
    stop.set()
    t.join()
    assert sim.collisions > 0
    assert during > 5  # with the GIL held the counter would not move at all


def test_a_call_from_another_thread_while_running_is_refused():
    sim = gs.Simulation(particles=50000, restitution=0.5, seed=2)
    errors = []
    t = threading.Thread(target=lambda: sim.run_until(30000))
    t.start()
    deadline = time.time() + 30
    while not errors and t.is_alive() and time.time() < deadline:
        try:
            sim.snapshot()
        except RuntimeError as e:
            errors.append(str(e))
    t.join()
    assert errors and "another thread" in errors[0]


def test_ctrl_c_stops_between_chunks_and_leaves_a_valid_simulation():
    # A box: the unbounded medium would stop at its cap of made particles before the timer.
    sim = gs.Simulation(particles=20000, restitution=0.5, seed=2, medium="box")
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run_until(1e9)
    timer.join()
    reached = sim.time
    assert 0 < reached < 1e9
    sim.run_until(reached + 1)  # still usable
    assert sim.time == reached + 1


def test_save_and_load_continue_the_same_history(out_dir):
    a = gs.Simulation(particles=3000, restitution=0.5, seed=5)
    a.run_until(30)
    a.save(out_dir / "sim.ckpt")
    b = gs.Simulation.load(str(out_dir / "sim.ckpt"))
    assert b.time == 30 and b.config == a.config
    a.run_until(70)
    b.run_until(70)
    assert a.collisions == b.collisions
    np.testing.assert_array_equal(a.snapshot().positions, b.snapshot().positions)


def test_load_refuses_what_is_not_a_saved_simulation(out_dir):
    (out_dir / "junk").write_bytes(b"not a checkpoint")
    with pytest.raises(ValueError, match="junk"):
        gs.Simulation.load(str(out_dir / "junk"))
