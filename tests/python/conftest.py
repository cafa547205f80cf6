"""Shared fixtures: the built command, a scratch folder per test, a small kicked gas."""
import os
import pathlib
import subprocess

import pytest

import grainshock as gs

BINARY = os.environ.get("GRAINSHOCK_BINARY", "grainshock")


def run_command(*args):
    """Runs the grainshock command; returns the CompletedProcess (text)."""
    return subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True)


@pytest.fixture
def small_sim():
    sim = gs.Simulation(dim=2, particles=4000, restitution=0.5, seed=7, medium="box")
    sim.run_until(60)
    return sim


@pytest.fixture
def out_dir(tmp_path):
    return pathlib.Path(tmp_path)
