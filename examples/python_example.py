# The README's example: kick a 2D gas at rest, follow R_t, plot it and draw the last frame.
# Run with PYTHONPATH=build/python /usr/bin/python3 examples/python_example.py
import grainshock as gs
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sim = gs.Simulation(dim=2, particles=20000, restitution=0.1, seed=1)
times = [10 * 2 ** (k / 2) for k in range(16)]  # t = 10 .. 1810
radius = []
for t in times:
    sim.run_until(t)
    radius.append(gs.observables(sim.snapshot())["radius_rms"])
plt.loglog(times, radius, "o-"); plt.xlabel("t"); plt.ylabel("$R_t$"); plt.savefig("R_t.png")
gs.render(sim.snapshot(), width=960, height=540).save("frame.png")
