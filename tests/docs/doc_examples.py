#!/usr/bin/python3
"""Runs every ```sh and ```python block of the README and docs/, so that the docs cannot drift.

Usage: doc_examples.py SOURCE_DIR BUILD_DIR [FILE.md ...]

The blocks of one file run in order in one scratch folder, which holds links to the source's
assets/, examples/ and scripts/ and to the build (as build/). A block fails when a command
exits non-zero or a file named on its `# leaves:` line is missing. Sizes are made small by the
substitution CONTRIBUTING.md describes ("The documentation is tested"); it is done here, in
`substitute`, and nowhere else.

GRAINSHOCK_DOC_BREAK=1 adds an unknown flag to the first grainshock command, for the test that
a broken example fails.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SMALL_PARTICLES = 20000
SMALL_T_MAX = 2000.0
SMALL_REALISATIONS = 2


def blocks(md_text):
    """(language, code, first line number) of every fenced block."""
    out, lines, i = [], md_text.split("\n"), 0
    while i < len(lines):
        m = re.match(r"^```(\w+)\s*$", lines[i])
        if m:
            start, body = i + 1, []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            out.append((m.group(1), "\n".join(body), start + 1))
        i += 1
    return out


def leaves(code):
    """The files a block promises, their times (tsim_<t>) scaled as its commands' times are."""
    factors = [time_factor(c) for c in re.sub(r"\\\n\s*", " ", code).split("\n")]
    f = min(factors + [1.0])
    files = []
    for line in code.split("\n"):
        m = re.match(r"^\s*#\s*leaves:\s*(.*)$", line)
        if m:
            files += [re.sub(r"tsim_(\d+(?:\.\d+)?)(?=\.[a-z])",
                             lambda t: "tsim_" + format(float(t.group(1)) * f, "g"), name)
                      for name in m.group(1).split()]
    return files


def cap(flag, limit, as_int):
    def repl(m):
        v = float(m.group(2))
        v = min(v, limit)
        return m.group(1) + (str(int(v)) if as_int else format(v, "g"))
    return (re.compile(r"(" + re.escape(flag) + r"[ =])([0-9.eE+]+)"), repl)


RULES = [
    cap("--particles", SMALL_PARTICLES, True),
    cap("--realisations", SMALL_REALISATIONS, True),
    cap("--width", 640, True),
    cap("--height", 480, True),
]


def time_factor(cmd):
    """What the times of a command are multiplied by: --t-max at most SMALL_T_MAX."""
    m = re.search(r"--t-max[ =]([0-9.eE+]+)", cmd)
    return min(1.0, SMALL_T_MAX / float(m.group(1))) if m else 1.0


def scale_times(cmd, f):
    """--t-max, --snapshot-times and --sample-every times f."""
    def times(m):
        return m.group(1) + ",".join(format(float(x) * f, "g") for x in m.group(2).split(","))
    return re.sub(r"(--(?:t-max|snapshot-times|sample-every)[ =])([0-9.eE+,]+)", times, cmd)


def substitute_command(cmd, has_mpi):
    """One logical command line (continuations joined) made small."""
    cmd = cmd.replace("bash scripts/bootstrap.sh run", "grainshock run")
    cmd = scale_times(cmd, time_factor(cmd))
    for pattern, repl in RULES:
        cmd = pattern.sub(repl, cmd)
    cmd = re.sub(r"--threads[ =](\$\w+|\d+)", "--threads 1", cmd)
    cmd = re.sub(r"(\bfigures\b.*?)--(quick|full)\b", r"\1--tiny", cmd)
    if has_mpi:
        cmd = re.sub(r"\bmpirun -n \d+", "mpirun --oversubscribe -n 2", cmd)
    else:
        cmd = re.sub(r"\bmpirun -n \d+ ", "", cmd)
    # A run, movie or ensemble that simulates gets a small gas (stored-snapshot movies take
    # files, and --config files keep their own).
    m = re.search(r"\bgrainshock (run|movie|ensemble)\b", cmd)
    if m and "--config" not in cmd:
        rest = cmd[m.end():]
        stored = m.group(1) == "movie" and re.search(r"\.(xyz|gsd|lammpstrj)\b", rest)
        if not stored:
            extra = "" if "--particles" in cmd else " --particles %d" % SMALL_PARTICLES
            if m.group(1) == "movie":  # a simulated movie: fewer, smaller frames
                for flag, value in (("--frames", 24), ("--width", 640), ("--height", 360)):
                    if flag not in cmd:
                        extra += " %s %d" % (flag, value)
            # A run without --t-max is the Fig. 1 job, which keeps its times.
            if m.group(1) != "run" and "--t-max" not in cmd:
                extra += " --t-max %g" % SMALL_T_MAX
            cmd = cmd[:m.end()] + extra + rest
    return cmd


def substitute(code, has_mpi):
    """The shell block as the test runs it."""
    # `bootstrap.sh test` is the whole suite, which CI runs: its line is left out.
    code = "\n".join(l for l in code.split("\n") if "bash scripts/bootstrap.sh test" not in l)
    joined = re.sub(r"\\\n\s*", " ", code)
    # A shell variable given to --realisations (a SLURM script's M=8) is capped where it is set.
    for name in re.findall(r"--realisations[ =]\$(\w+)", joined):
        joined = re.sub(r"^(\s*%s=)(\d+)" % name,
                        lambda m: m.group(1) + str(min(int(m.group(2)), SMALL_REALISATIONS)),
                        joined, flags=re.M)
    out = []
    for line in joined.split("\n"):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            out.append(line)
            continue
        out.append(substitute_command(line, has_mpi))
    return "\n".join(out)


def break_first(code):
    return re.sub(r"\bgrainshock (\w+)", r"grainshock \1 --no-such-flag", code, count=1)


def scratch(source, build):
    d = tempfile.mkdtemp(prefix="grainshock-docs-")
    for name in ("assets", "examples", "scripts"):
        os.symlink(os.path.join(source, name), os.path.join(d, name))
    os.symlink(build, os.path.join(d, "build"))
    bindir = os.path.join(d, ".bin")
    os.mkdir(bindir)
    os.symlink(os.path.join(build, "apps", "grainshock"), os.path.join(bindir, "grainshock"))
    return d, bindir


def run_file(path, source, build, has_mpi, has_python, env_base):
    """Failures of one Markdown file, as messages."""
    text = open(path, encoding="utf-8").read()
    d, bindir = scratch(source, build)
    env = dict(env_base)
    env["PATH"] = bindir + os.pathsep + env["PATH"]
    env["PYTHONPATH"] = os.path.join(build, "python")
    env["MPLBACKEND"] = "Agg"
    env["SLURM_ARRAY_TASK_ID"] = "0"
    env["SLURM_CPUS_PER_TASK"] = "1"
    if os.geteuid() == 0:  # Open MPI refuses root unless told (containers, CI)
        env["OMPI_ALLOW_RUN_AS_ROOT"] = env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    failures, broken = [], os.environ.get("GRAINSHOCK_DOC_BREAK") == "1"
    rel = os.path.relpath(path, source)
    try:
        for lang, code, line in blocks(text):
            where = "%s:%d" % (rel, line)
            if lang == "sh":
                script = substitute(code, has_mpi)
                if broken:
                    script, broken = break_first(script), False
                argv = ["bash", "-e", "-o", "pipefail", "-c", script]
            elif lang == "python":
                if not has_python:
                    print("%s: skipped: the grainshock Python module was not built" % where)
                    continue
                argv, script = ["/usr/bin/python3", "-c", code], code
            else:
                continue
            print("%s: %s" % (where, script.strip().split("\n")[0]))
            r = subprocess.run(argv, cwd=d, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, timeout=600)
            if r.returncode != 0:
                failures.append("%s: exit %d\n%s\n--- output:\n%s" %
                                (where, r.returncode, script, r.stdout[-3000:]))
                if os.environ.get("GRAINSHOCK_DOC_BREAK") == "1":
                    break  # the broken example failed, as it must: no need to run the rest
                continue
            for f in leaves(code):
                if not os.path.exists(os.path.join(d, f)):
                    failures.append("%s: promised file '%s' is missing" % (where, f))
    finally:
        shutil.rmtree(d, ignore_errors=True)
    return failures


def main():
    source, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    files = sys.argv[3:] or ["README.md"] + sorted(
        os.path.join("docs", f) for f in os.listdir(os.path.join(source, "docs"))
        if f.endswith(".md"))
    has_python = os.path.isdir(os.path.join(build, "python", "grainshock"))
    has_mpi = False
    if shutil.which("mpirun"):
        cache = open(os.path.join(build, "CMakeCache.txt")).read()
        has_mpi = re.search(r"^GRAINSHOCK_MPI:BOOL=ON$", cache, re.M) is not None
    failures = []
    for f in files:
        failures += run_file(os.path.join(source, f), source, build, has_mpi, has_python,
                             os.environ)
    for f in failures:
        print("FAILED " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
