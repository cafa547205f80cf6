#!/usr/bin/python3
"""Pages of `grainshock view` in headless Chromium (software WebGL2, SwiftShader): the time to
load a page and the time per frame switch, at 1e4 and 1e5 particles a frame.

    /usr/bin/python3 bench/view_browser_bench.py [--binary build/apps/grainshock] [--repeat 20]

Each size: a 2D band of N active discs in 5 frames (written as extended XYZ, then `grainshock
view`); load = navigation start to the first frame drawn (the page's script has run and drawn);
switch = setFrame(k) to a finished draw (gl.finish): to a frame not shown before (its base64
decoded, uploaded, drawn) and to one shown before (uploaded, drawn), medians. Nothing here
is a test (Debian's chromium, chromium-driver and python3-selenium needed).
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from selenium import webdriver
from selenium.webdriver.chrome.service import Service


def write_band(path, n, t, seed):
    rng = random.Random(seed)
    lines = [str(n), f'Properties=species:S:1:pos:R:2:velo:R:2 Time={t} Dim=2']
    r_in, r_out = math.sqrt(n) * 0.6, math.sqrt(n) * 0.9
    for _ in range(n):
        a, u = rng.uniform(0, 2 * math.pi), rng.random()
        r = math.sqrt(r_in ** 2 + (r_out ** 2 - r_in ** 2) * u)
        lines.append(f"A {r * math.cos(a):.4f} {r * math.sin(a):.4f} {math.cos(a) * u:.4f} "
                     f"{math.sin(a) * u:.4f}")
    path.write_text("\n".join(lines) + "\n")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--binary", default="build/apps/grainshock")
    p.add_argument("--repeat", type=int, default=20)
    a = p.parse_args()
    o = webdriver.ChromeOptions()
    for arg in ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader",
                "--use-angle=swiftshader", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--no-first-run",
                "--window-size=1280,1000", "--user-data-dir=" + tempfile.mkdtemp()]:
        o.add_argument(arg)
    o.binary_location = "/usr/bin/chromium"
    d = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)
    out = {}
    for n in (10000, 100000):
        folder = Path(tempfile.mkdtemp())
        for k in range(5):
            write_band(folder / f"f{k}.xyz", n, 10 * (k + 1), k)
        page = folder / "page.html"
        subprocess.run([a.binary, "view", str(folder), "--out", str(page), "--quiet"], check=True)
        d.get(page.as_uri())
        load = d.execute_script(
            "const e = performance.getEntriesByType('navigation')[0];"
            "return e.loadEventEnd - e.startTime;")
        switch = """
              const t0 = performance.now();
              window.gsView.setFrame(arguments[0]);
              window.gsView.state.gl.finish();
              return performance.now() - t0;"""
        # Frames 0-3 not yet shown: base64 decoded, uploaded, drawn; then again, decoded already.
        first = [d.execute_script(switch, k) for k in range(4)]
        again = [d.execute_script(switch, r % 5) for r in range(a.repeat)]
        out[n] = {"page_mb": page.stat().st_size / 1e6, "load_ms": load,
                  "first_switch_ms_median": statistics.median(first),
                  "switch_ms_median": statistics.median(again)}
        print(f"{n:>7} particles: page {out[n]['page_mb']:.2f} MB, load {load:.0f} ms, "
              f"frame switch {out[n]['first_switch_ms_median']:.1f} ms to a frame not shown "
              f"before, {out[n]['switch_ms_median']:.1f} ms again (medians)")
    d.quit()
    print(json.dumps(out))


if __name__ == "__main__":
    main()
