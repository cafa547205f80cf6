"""render: the pixels of `grainshock render`; Image; compare with the golden-image rule."""
import numpy as np
import pytest

import grainshock as gs
from conftest import run_command


@pytest.fixture(scope="module")
def snapshot_file(tmp_path_factory):
    out = tmp_path_factory.mktemp("render") / "r"
    # A box: --framing box is among the cases (an unbounded run's snapshot has no box to frame).
    cli = run_command("run", "--medium", "box", "--particles", 6000, "--restitution", 0.3,
                      "--seed", 9, "--t-max", 150, "--snapshot-times", 150, "--out", out, "--quiet")
    assert cli.returncode == 0, cli.stderr
    return next((out / "snapshots").iterdir())


@pytest.mark.parametrize("flags,kwargs", [
    ([], {}),
    (["--color-by", "first-collision", "--no-inset", "--background", "dark"],
     {"color_by": "first-collision", "inset": False, "background": "dark"}),
    (["--color-by", "speed", "--framing", "box", "--show-inactive", "--no-colorbar"],
     {"color_by": "speed", "framing": "box", "show_inactive": True, "colorbar": False}),
])
def test_render_is_byte_identical_to_the_command(snapshot_file, tmp_path, flags, kwargs):
    png = tmp_path / "cli.png"
    cli = run_command("render", snapshot_file, "--out", png, "--width", 480, "--height", 320,
                      *flags)
    assert cli.returncode == 0, cli.stderr
    image = gs.render(gs.read(snapshot_file), width=480, height=320, **kwargs)
    expected = gs.Image.load(png)
    assert image.array.shape == (320, 480, 3) and image.array.dtype == np.uint8
    np.testing.assert_array_equal(image.rgba, expected.rgba)
    assert dict(image.text) == dict(expected.text)


def test_render_refuses_what_the_command_refuses(snapshot_file, tmp_path):
    snap = gs.read(snapshot_file)
    cli = run_command("render", snapshot_file, "--out", tmp_path / "x.png", "--color-by", "mass")
    assert cli.returncode == 2  # a --color-by the snapshot lacks: a usage error (README exit codes)
    with pytest.raises(ValueError) as e:
        gs.render(snap, color_by="mass")
    # The same sentence, naming the file there and "the snapshot" here.
    said = str(e.value).replace("'the snapshot'", "'" + str(snapshot_file) + "'")
    assert said in cli.stderr
    with pytest.raises(ValueError, match="--framing"):
        gs.render(snap, framing="wide")
    with pytest.raises(ValueError, match="--zoom"):
        gs.render(snap, zoom=0)


def test_image_save_load_and_notebook_display(snapshot_file, tmp_path):
    image = gs.render(gs.read(snapshot_file), width=200, height=150)
    png = image._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    image.save(tmp_path / "a.png")
    assert (tmp_path / "a.png").read_bytes() == png
    np.testing.assert_array_equal(gs.Image.load(tmp_path / "a.png").array, image.array)


def test_compare_tells_alike_from_different(snapshot_file):
    snap = gs.read(snapshot_file)
    a = gs.render(snap, width=320, height=240)
    same = gs.compare(a, gs.Image.from_array(a.array))
    assert same.alike and same.fraction == 0 and same.psnr == float("inf") and same.ssim == 1
    changed = a.array.copy()
    changed[100:110, 100:110] = [255, 0, 0]  # a 10 x 10 red square
    diff = gs.compare(a, changed)
    assert not diff.alike and diff.fraction > 0 and diff.psnr < 60
    assert diff.diff.array.shape == a.array.shape
    other = gs.render(snap, width=320, height=240, color_by="first-collision")
    assert not gs.compare(a, other).alike


def test_render_takes_a_path_or_says_what_it_takes(snapshot_file):
    by_path = gs.render(snapshot_file, width=320, height=240)
    by_str = gs.render([str(snapshot_file)], width=320, height=240)
    by_snapshot = gs.render(gs.read(snapshot_file), width=320, height=240)
    np.testing.assert_array_equal(by_path.rgba, by_snapshot.rgba)
    np.testing.assert_array_equal(by_str.rgba, by_snapshot.rgba)
    with pytest.raises(TypeError, match="a Snapshot, a path"):
        gs.render(42)


def test_compare_of_different_sizes_is_a_value_error(snapshot_file):
    # As `grainshock compare`, which exits 2: no verdict on pictures of different sizes.
    a = gs.render(gs.read(snapshot_file), width=320, height=240)
    b = gs.render(gs.read(snapshot_file), width=240, height=320)
    with pytest.raises(ValueError, match="different sizes"):
        gs.compare(a, b)
