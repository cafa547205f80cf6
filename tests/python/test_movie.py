"""Movie: the encoder of `grainshock movie`, whole or absent."""
import pytest

import grainshock as gs


def test_movie_of_snapshots_and_images(tmp_path):
    sim = gs.Simulation(particles=3000, restitution=0.5, seed=3)
    path = tmp_path / "m.mp4"
    with gs.Movie(path, fps=10, width=320, height=240) as m:
        for t in (10, 20, 30):
            sim.run_until(t)
            m.add(sim.snapshot())
        m.add(gs.render(sim.snapshot(), width=320, height=240))
        assert m.frames == 4
    assert path.stat().st_size > 1000


def test_a_failed_block_leaves_no_movie(tmp_path):
    path = tmp_path / "m.mp4"
    with pytest.raises(ZeroDivisionError):
        with gs.Movie(path, width=320, height=240) as m:
            m.add(gs.Image.from_array(__import__("numpy").zeros((240, 320, 3), "uint8")))
            1 / 0
    assert not path.exists()
    assert list(tmp_path.iterdir()) == []


def test_a_frame_of_another_size_is_refused(tmp_path):
    import numpy as np
    with pytest.raises(ValueError):
        with gs.Movie(tmp_path / "m.mp4", width=320, height=240) as m:
            m.add(gs.Image.from_array(np.zeros((100, 100, 3), "uint8")))


def test_encoder_options_not_given_are_the_movie_commands(tmp_path):
    # Given ones reach the encoder: a CRF out of 0..51 is refused naming it.
    with pytest.raises(ValueError, match="crf"):
        gs.Movie(tmp_path / "bad.mp4", width=320, height=240, crf=99)
    with gs.Movie(tmp_path / "m.mp4", width=320, height=240) as m:
        m.add(gs.Image.from_array(__import__("numpy").zeros((240, 320, 3), "uint8")))
    assert (tmp_path / "m.mp4").stat().st_size > 0
    assert not (tmp_path / "bad.mp4").exists()
