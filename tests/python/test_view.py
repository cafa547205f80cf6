"""view: the page of `grainshock view` from Python, for notebooks (_repr_html_) and files."""
import html
import json
import re

import pytest

import grainshock as gs
from conftest import run_command


def header(page_html):
    """The page's JSON header (the data of every frame)."""
    m = re.search(r'<script type="application/json" id="gs-header">(.*?)</script>', page_html, re.S)
    return json.loads(m.group(1))


def test_view_of_a_simulation_and_snapshots(small_sim, out_dir):
    page = gs.view(small_sim)
    h = header(page.html)
    assert len(h["frames"]) == 1 and h["dim"] == 2
    assert h["frames"][0]["count"] == int(small_sim.snapshot().active.sum())
    early = small_sim.snapshot()
    small_sim.run_until(120)
    page = gs.view([small_sim.snapshot(), early])
    h = header(page.html)
    # In time order whatever order they were given in.
    assert [f["t"] for f in h["frames"]] == [60, 120]
    page.save(out_dir / "p.html")
    assert (out_dir / "p.html").read_text() == page.html


def test_repr_html_is_an_iframe_holding_the_page(small_sim):
    r = gs.view(small_sim)._repr_html_()
    assert r.startswith("<iframe") and 'srcdoc="' in r
    srcdoc = r.split('srcdoc="', 1)[1].rsplit('"', 1)[0]
    assert "<" not in srcdoc and '"' not in srcdoc  # escaped: the attribute cannot end early
    assert html.unescape(srcdoc) == gs.view(small_sim).html


def test_view_of_a_run_folder_is_the_command_page(out_dir):
    run = out_dir / "r"
    cli = run_command("run", "--dim", "2", "--particles", 3000, "--t-max", 100, "--snapshot-times",
                      50, 100, "--out", run, "--quiet")
    assert cli.returncode == 0, cli.stderr
    page = gs.view(run)
    h = header(page.html)
    assert h["kind"] == "run" and len(h["frames"]) == 2 and h["timeseries"].startswith("t,")
    own = header((run / "index.html").read_text())["frames"]
    # The folder's own page names its files relative to itself; all else is the same.
    assert [f.pop("source") for f in own] == ["snapshots/tsim_50.xyz", "snapshots/tsim_100.xyz"]
    assert [f.pop("source") for f in h["frames"]] == [
        str(run / "snapshots" / "tsim_50.xyz"), str(run / "snapshots" / "tsim_100.xyz")]
    assert own == h["frames"]


def test_view_refuses_other_things():
    with pytest.raises(TypeError):
        gs.view(42)
    with pytest.raises(ValueError, match="neither a snapshot file nor a folder"):
        gs.view("/no/such/place")


def test_ensemble_leaves_its_page_unless_told(out_dir):
    for name, flags in (("e", []), ("quiet", ["--no-page"])):
        cli = run_command("ensemble", "--dim", 2, "--particles", 2000, "--t-max", 100,
                          "--realisations", 2, "--threads", 1, "--out", out_dir / name,
                          "--quiet", *flags)
        assert cli.returncode == 0, cli.stderr
    h = header((out_dir / "e" / "index.html").read_text())
    # The means with their errors, and the slopes of the paper's alpha = 1/(d+1) in 2D.
    assert h["kind"] == "ensemble" and h["mean"] and "active_sem" in h["timeseries"].split("\n")[0]
    assert h["dim"] == 2 and h["alpha"] == pytest.approx(1 / 3)
    assert not (out_dir / "quiet" / "index.html").exists()
