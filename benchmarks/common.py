"""Shared helpers of the benchmark run scripts (see doc/benchmarks.md).

Each benchmark runs the mpm executable of an existing build (MPM_BUILD, or
build/ at the top of the repository), times every run in the same process
that measures its error, writes results.csv and PNG plots next to its run
script, and ends its printed table with a line 'SUMMARY key=value ...'.
"""
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def ensure_matplotlib():
    """Import matplotlib (Agg); install Debian's package if it is missing."""
    try:
        import matplotlib
    except ImportError:
        if os.geteuid() != 0:
            sys.exit("benchmark: needs python3-matplotlib "
                     "(apt-get install python3-matplotlib)")
        subprocess.run(["apt-get", "install", "-y", "-qq",
                        "python3-matplotlib"], check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
        import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def mpm_executable():
    build = os.environ.get("MPM_BUILD", os.path.join(ROOT, "build"))
    exe = os.path.join(build, "mpm")
    if not os.access(exe, os.X_OK):
        sys.exit("benchmark: no mpm executable in %s; build first "
                 "(bash .ci/build) or set MPM_BUILD" % build)
    return exe


class RunFailed(Exception):
    """mpm stopped with an error; the message is its last words."""


def run_mpm(prm, settings, directory, ranks=1):
    """Run one scene; return (wall seconds, stdout, time series columns).

    The wall time is that of the whole process, measured here."""
    command = [mpm_executable()]
    for key, value in settings.items():
        command += ["--set", "%s=%s" % (key, value)]
    command += ["--set", "Output/Directory=%s" % directory, prm]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        raise RunFailed(result.stderr.strip().splitlines()[-1]
                        if result.stderr.strip() else "exit code %d"
                        % result.returncode)
    return wall, result.stdout, read_csv(os.path.join(directory,
                                                      "time_series.csv"))


def read_csv(filename):
    with open(filename) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def write_results(directory, rows):
    """rows: list of dicts with the same keys."""
    path = os.path.join(directory, "results.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    return path


def print_table(rows):
    keys = list(rows[0].keys())
    widths = [max(len(k), *(len(fmt(r[k])) for r in rows)) for k in keys]
    print("  ".join(k.ljust(w) for k, w in zip(keys, widths)))
    for r in rows:
        print("  ".join(fmt(r[k]).ljust(w) for k, w in zip(keys, widths)))


def fmt(value):
    if isinstance(value, float):
        return "%.4g" % value
    return str(value)


def summary(**pairs):
    print("SUMMARY " + " ".join("%s=%s" % (k, fmt(v))
                                for k, v in pairs.items()))


def timer_sections(stdout):
    """Wall seconds per TimerOutput section (max over ranks)."""
    sections = {}
    for line in stdout.splitlines():
        m = re.match(r"\|\s*([A-Za-z0-9 ]+?)\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s"
                     r"\s*\d+\s*\|\s*([0-9.e+-]+)s\s*\|\s*([0-9.e+-]+)s", line)
        if m:
            sections[m.group(1)] = float(m.group(5))
    return sections
