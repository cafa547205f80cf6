"""Observables of a snapshot agree with the engine's own sample and with their definitions."""
import numpy as np
import pytest

import grainshock as gs


def test_observables_are_the_engines_sample(small_sim):
    o = gs.observables(small_sim.snapshot(active_only=False))
    s = small_sim.sample()
    assert o["active"] == s["active"]
    assert o["energy"] == pytest.approx(s["energy"], rel=1e-12)
    assert o["radius_rms"] == pytest.approx(s["radius_rms"], rel=1e-9)
    assert o["speed_rms"] == pytest.approx(s["speed_rms"], rel=1e-9)
    assert o["anisotropy"] == pytest.approx(s["anisotropy"], abs=1e-9)
    assert o["gyration"].shape == (2, 2)
    # R_t is the root of the gyration tensor's trace, by definition.
    assert o["radius_rms"] == pytest.approx(np.sqrt(np.trace(o["gyration"])))


def test_distributions_are_normalised(small_sim):
    snap = small_sim.snapshot()
    for h in (gs.radial_distribution(snap, bins=20), gs.speed_distribution(snap)):
        assert np.sum(h["values"] * np.diff(h["edges"])) == pytest.approx(1)
        assert h["samples"] == len(snap)
    scaled = gs.scaled_radial_distribution(snap, 1 / 3)
    assert np.sum(scaled["values"] * np.diff(scaled["edges"])) == pytest.approx(1)


def test_profile_counts_every_active_particle(small_sim):
    snap = small_sim.snapshot()
    p = gs.radial_profile(snap, bins=25)
    assert p["edges"].shape == (26,) and int(p["count"].sum()) == len(snap)


def test_band_packing_is_a_fraction(small_sim):
    b = gs.band_packing(small_sim.snapshot(active_only=False))
    assert 0 < b["typical"] < 1 and len(b["fraction"]) == len(b["active"]) > 0
    assert gs.inner_edge_speed(small_sim.snapshot())["ratio"] > 0


def test_ensemble_means_do_not_depend_on_threads():
    kw = dict(realisations=3, particles=1500, restitution=0.5, t_max=300, resamples=20)
    one = gs.ensemble(threads=1, **kw)
    two = gs.ensemble(threads=2, **kw)
    assert one["realisations"] == 3
    ts = one["timeseries"]
    assert ts["t"][-1] == pytest.approx(300) and len(ts["t"]) == len(ts["R_t"] if "R_t" in ts else ts["t"])
    for name, values in ts.items():
        np.testing.assert_array_equal(values, two["timeseries"][name])
    assert "R_t" in one["fits"] and one["alpha_theory"] == pytest.approx(1 / 3)


def test_ensemble_refuses_bad_input():
    with pytest.raises(ValueError, match="--realisations"):
        gs.ensemble(realisations=0, particles=500)
    with pytest.raises(TypeError, match="colour"):
        gs.ensemble(particles=500, colour=1)
