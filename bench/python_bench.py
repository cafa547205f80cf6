#!/usr/bin/python3
"""Speed of the Python module against the command.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--binary build/apps/grainshock]
        [--t-max 3000] [--particles 250000] [--big 2000000] [--repeat 3]

1. run_until per collision on the 2D paper kick (N = 2.5e5, r = 0.1) against the `run` command's
   engine time (timing.json run_seconds: the engine, samples and timeseries.csv; setup excluded).
2. snapshot() of --big spheres (3D) into numpy, all and active only.
3. render of the 2.5e5 discs (all drawn, --show-inactive) from Python against `grainshock render`
   of the same snapshot file: the command's whole run (read, GL context, draw, PNG) and Python's
   read + render + save; and the drawing alone: CPU per render() call once the GL context exists,
   against the command's drawing of the same kind of scene (`grainshock bench render/discs_2.5e5`:
   2.5e5 discs of a 2D kick, whole box, inactive shown, 1920x1080), CPU time of all threads.
Medians of --repeat runs; nothing here is a test.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import grainshock as gs


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    here = pathlib.Path(__file__).resolve().parent.parent
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--binary", default=str(here / "build" / "apps" / "grainshock"))
    p.add_argument("--t-max", type=float, default=3000)
    p.add_argument("--particles", type=float, default=250000)
    p.add_argument("--big", type=float, default=2e6)
    p.add_argument("--repeat", type=int, default=3)
    a = p.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="gs_pybench_"))
    physics = dict(dim=2, particles=int(a.particles), restitution=0.1, seed=1)

    # 1. run_until per collision
    py_rates, cli_rates = [], []
    for k in range(a.repeat):
        sim = gs.Simulation(**physics)
        t0 = time.perf_counter()
        sim.run_until(a.t_max)
        py_rates.append((time.perf_counter() - t0) / sim.collisions)
        out = tmp / f"run{k}"
        subprocess.run([a.binary, "run", "--particles", str(int(a.particles)), "--restitution",
                        "0.1", "--seed", "1", "--t-max", str(a.t_max), "--out", str(out),
                        "--quiet"], check=True)
        timing = json.loads((out / "timing.json").read_text())
        cli_rates.append(timing["run_seconds"] / sim.collisions)
    py, cli = statistics.median(py_rates), statistics.median(cli_rates)
    print(f"run_until, 2D kick N={int(a.particles)} to t={a.t_max:g} ({sim.collisions} collisions):"
          f" python {py * 1e9:.1f} ns/collision, command {cli * 1e9:.1f} ns/collision,"
          f" {100 * (py / cli - 1):+.1f}%")

    # 2. snapshot() of a big 3D gas
    big = gs.Simulation(dim=3, particles=int(a.big), restitution=0.1, seed=1)
    big.run_until(200)
    full = median_time(lambda: big.snapshot(active_only=False), a.repeat)
    active = median_time(lambda: big.snapshot(), a.repeat)
    print(f"snapshot() of {int(a.big)} spheres (3D, t=200): all {full * 1e3:.1f} ms, "
          f"active only ({len(big.snapshot())}) {active * 1e3:.1f} ms")
    del big

    # 3. render of 2.5e5 discs
    sim = gs.Simulation(**physics)
    sim.run_until(a.t_max)
    snap_file = tmp / "snap.xyz"
    subprocess.run([a.binary, "run", "--particles", str(int(a.particles)), "--restitution", "0.1",
                    "--seed", "1", "--t-max", str(a.t_max), "--snapshot-times", str(a.t_max),
                    "--out", str(tmp / "snaprun"), "--quiet"], check=True)
    snap_file = next((tmp / "snaprun" / "snapshots").iterdir())
    flags = ["--show-inactive", "--framing", "box"]
    cli = median_time(lambda: subprocess.run([a.binary, "render", str(snap_file), "--out",
                                              str(tmp / "cli.png"), *flags], check=True), a.repeat)
    snap = gs.read(snap_file)
    gs.render(snap, show_inactive=True, framing="box")  # makes the GL context
    whole = median_time(lambda: gs.render(gs.read(snap_file), show_inactive=True,
                                          framing="box").save(tmp / "py.png"), a.repeat)
    alone = median_time(lambda: gs.render(snap, show_inactive=True, framing="box"), a.repeat)
    calls = 20
    c0 = time.process_time()
    for _ in range(calls):
        gs.render(snap, show_inactive=True, framing="box")
    py_cpu = (time.process_time() - c0) / calls
    subprocess.run([a.binary, "bench", "render/discs_2.5e5", "--json", str(tmp / "bench.json")],
                   check=True, stdout=subprocess.DEVNULL)
    figures = json.loads((tmp / "bench.json").read_text())
    cli_cpu = next(f["value"] for f in figures if f["figure"] == "cpu_ms_per_frame") / 1e3
    print(f"render of {len(snap)} discs at 1920x1080: command {cli * 1e3:.0f} ms (whole process), "
          f"python read+render+save {whole * 1e3:.0f} ms ({100 * (whole / cli - 1):+.1f}%), "
          f"render() alone {alone * 1e3:.0f} ms wall; drawing CPU per frame: python "
          f"{py_cpu * 1e3:.1f} ms, command (bench render/discs_2.5e5) {cli_cpu * 1e3:.1f} ms, "
          f"{100 * (py_cpu / cli_cpu - 1):+.1f}%")
    subprocess.run(["rm", "-rf", str(tmp)])


if __name__ == "__main__":
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    main()
