"""Shared helpers of the benchmark run scripts (see doc/benchmarks.md).

Each benchmark runs the mpm executable of an existing build (MPM_BUILD, or
build/ at the top of the repository), times every run in the same process
that measures its error, writes results.csv and PNG plots next to its run
script, and ends its printed table with a line 'SUMMARY key=value ...'.

With --quick a benchmark runs its scenes on coarse grids for short times,
writes under <MPM_BUILD>/benchmarks/<name>/ (output_dir), checks its key
figures against plausible ranges (quick_check) and exits with status 1 if
one is out of range or an mpm run failed (finish_quick).
"""
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
# The script's start, for the wall time a quick mode prints.
START = time.perf_counter()


def quick():
    """Whether the benchmark runs in its quick mode (--quick): its scenes
    through the same code paths on coarse grids and short times, with
    plausibility checks (quick_check) that fail the run (finish_quick)."""
    return "--quick" in sys.argv[1:]


def build_directory():
    return os.path.abspath(os.environ.get("MPM_BUILD",
                                          os.path.join(ROOT, "build")))


def output_dir(here):
    """Where a benchmark writes its results, figures and run directories:
    its own folder (here), or under --quick <MPM_BUILD>/benchmarks/<name>/
    (created), so that a quick run leaves the records and figures of the
    full runs alone."""
    if not quick():
        return here
    path = os.path.join(build_directory(), "benchmarks",
                        os.path.basename(os.path.normpath(here)))
    os.makedirs(path, exist_ok=True)
    return path


# The quick mode's checks: (name, passed), in order.
QUICK_CHECKS = []


def quick_check(name, value, lo, hi):
    """One plausibility check of a quick mode: prints
    'QUICK CHECK name: value in [lo, hi]: ok|FAILED' and records it for
    finish_quick. A NaN (or None) value fails."""
    try:
        number = float(value)
        passed = lo <= number <= hi
    except (TypeError, ValueError):
        number, passed = float("nan"), False
    QUICK_CHECKS.append((name, passed))
    print("QUICK CHECK %s: %.6g in [%.6g, %.6g]: %s"
          % (name, number, lo, hi, "ok" if passed else "FAILED"), flush=True)
    return passed


def finish_quick():
    """End of a quick mode: exit with status 1 if a check failed or an mpm
    run exited non-zero (run_mpm records that as a failed check). Nothing
    outside the quick mode."""
    if not quick():
        return
    failed = [name for name, passed in QUICK_CHECKS if not passed]
    if failed:
        sys.stderr.write("quick mode FAILED (%d of %d checks): %s\n"
                         % (len(failed), len(QUICK_CHECKS),
                            "; ".join(failed)))
        sys.exit(1)


DEBIAN_PYTHON_PACKAGES = "/usr/lib/python3/dist-packages"


def import_matplotlib():
    """Import matplotlib, also from Debian's python3 packages, which a
    python3 of the same version that is not Debian's (pyenv's, say) does
    not search."""
    try:
        import matplotlib
    except ImportError:
        import importlib
        importlib.invalidate_caches()
        if os.path.isdir(DEBIAN_PYTHON_PACKAGES) and \
                DEBIAN_PYTHON_PACKAGES not in sys.path:
            sys.path.append(DEBIAN_PYTHON_PACKAGES)
        import matplotlib
    return matplotlib


def ensure_matplotlib():
    """Import matplotlib (Agg); install Debian's package if it is missing."""
    try:
        matplotlib = import_matplotlib()
    except ImportError:
        if os.geteuid() != 0:
            sys.exit("benchmark: needs python3-matplotlib "
                     "(apt-get install python3-matplotlib)")
        subprocess.run(["apt-get", "install", "-y", "-qq",
                        "python3-matplotlib"], check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
        matplotlib = import_matplotlib()
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def scene_options():
    """The options --shape-functions=NAME, --dilatation-rate=NAME,
    --velocity-projection=NAME and --geometry=NAME of a benchmark's command
    line: the settings they stand
    for, and a suffix for the names of its output, empty without them."""
    entries = {"--shape-functions=": "Grid/Shape functions",
               "--dilatation-rate=": "Time stepping/Dilatation rate",
               "--velocity-projection=": "Time stepping/Velocity projection",
               "--geometry=": "Grid/Geometry"}
    settings, suffix = {}, ""
    for argument in sys.argv[1:]:
        for option, entry in entries.items():
            if argument.startswith(option):
                value = argument[len(option):]
                settings[entry] = value
                suffix += "_" + value.replace(" ", "_")
    return settings, suffix


def mpm_executable():
    build = os.environ.get("MPM_BUILD", os.path.join(ROOT, "build"))
    exe = os.path.join(build, "mpm")
    if not os.access(exe, os.X_OK):
        sys.exit("benchmark: no mpm executable in %s; build first "
                 "(bash .ci/build) or set MPM_BUILD" % build)
    return exe


class RunFailed(Exception):
    """mpm stopped with an error; the message is its last words, stdout
    what it printed."""

    def __init__(self, message, stdout=""):
        super().__init__(message)
        self.stdout = stdout


# The bases of the runs of this process, for the SUMMARY line.
BASES_USED = set()


def basis_of(prm, settings):
    """The basis a run uses: the meshfree Method (GMM-MLS, GMM-LME), or
    MPM's Grid/Shape functions, each from the settings, else the prm
    file, else the default."""
    with open(prm) as f:
        text = f.read()

    def entry(path, name, default):
        if path in settings:
            return str(settings[path])
        found = re.search(r"^\s*set\s+%s\s*=\s*([^#\n]*?)\s*(#.*)?$" % name,
                          text, re.MULTILINE)
        return found.group(1) if found else default

    method = entry("Method", "Method", "MPM")
    return method if method != "MPM" else entry(
        "Grid/Shape functions", "Shape functions", "linear")


def run_mpm(prm, settings, directory, ranks=1, restart=False):
    """Run one scene; return (wall seconds, stdout, time series columns).
    With restart, the run continues from the checkpoint in directory.

    The wall time is that of the whole process, measured here."""
    BASES_USED.add(basis_of(prm, settings))
    command = [mpm_executable()] + (["--restart"] if restart else [])
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
        last_words = result.stderr.strip().splitlines()[-1] \
            if result.stderr.strip() else "exit code %d" % result.returncode
        if quick():
            quick_check("mpm exit status of %s (%s)" % (os.path.basename(
                os.path.normpath(directory)), last_words),
                result.returncode, 0, 0)
        raise RunFailed(last_words, result.stdout)
    return wall, result.stdout, read_csv(os.path.join(directory,
                                                      "time_series.csv"))


def without_shortened_last_step(series):
    """The series without its last row if that step was shortened to land
    on End time: a wall's or obstacle's force in a step is the impulse of
    that step over its dt, so a node that joins the obstacle in a short
    step gives a force far above the mean (at 1/50 of a step, a hundred
    times the pressure)."""
    dt = series["dt"]
    if len(dt) > 2 and dt[-1] < 0.99 * dt[-2]:
        return {key: values[:-1] for key, values in series.items()}
    return series


def read_csv(filename):
    with open(filename) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def write_results(directory, rows):
    """rows: list of dicts with the same keys."""
    return write_results_as(directory, "results.csv", rows)


def write_results_as(directory, name, rows):
    """write_results under another file name (benchmarks in parts)."""
    path = os.path.join(directory, name)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    return path


def number_or_text(value):
    """A value read back from a results file, as the int, float or text it
    was written from."""
    try:
        number = float(value)
    except ValueError:
        return value
    return int(number) if value.lstrip("-").isdigit() else number


def read_results(directory, name):
    """The rows that write_results_as wrote, each value as it was written."""
    with open(os.path.join(directory, name)) as f:
        return [{k: number_or_text(v) for k, v in r.items()}
                for r in csv.DictReader(f)]


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


def bases_text(bases):
    """Bases for a SUMMARY value: sorted, joined by +, with no spaces."""
    return "+".join(sorted(b.replace(" ", "_") for b in bases))


def summary(**pairs):
    """The SUMMARY line. It says which bases the runs used (joined by +)
    unless the benchmark says so itself."""
    if "shape_functions" not in pairs and BASES_USED:
        pairs = dict(shape_functions=bases_text(BASES_USED), **pairs)
    if quick():
        pairs = dict(pairs, quick=1)
        print_quick_wall_time()
    print("SUMMARY " + " ".join("%s=%s" % (k, fmt(v))
                                for k, v in pairs.items()))


def print_quick_wall_time():
    """The quick mode's wall time so far and its checks, printed before
    its SUMMARY line."""
    print("QUICK wall time %.1f s, %d checks, %d failed"
          % (time.perf_counter() - START, len(QUICK_CHECKS),
             sum(1 for _, passed in QUICK_CHECKS if not passed)), flush=True)


def newton_counts(stdout):
    """Newton's work in a Newmark run's screen output: step attempts (the
    "time step" lines, cut steps counted again), out-of-balance
    evaluations (iteration 0 included), corrections per attempt, and cut
    steps."""
    lines = stdout.splitlines()
    attempts = sum(1 for l in lines if l.lstrip().startswith("time step"))
    evaluations = sum(1 for l in lines if "out-of-balance ratio" in l)
    return {"step_attempts": attempts,
            "newton_evaluations": evaluations,
            "corrections_per_attempt":
                (evaluations - attempts) / attempts if attempts else
                float("nan"),
            "cut_steps": sum(1 for l in lines if "Cutting" in l)}


def timer_sections(stdout):
    """Wall seconds per TimerOutput section (max over ranks), summed over
    the tables in stdout (a run continued from checkpoints prints one per
    part)."""
    sections = {}
    for line in stdout.splitlines():
        m = re.match(r"\|\s*([A-Za-z0-9 ]+?)\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s"
                     r"\s*\d+\s*\|\s*([0-9.e+-]+)s\s*\|\s*([0-9.e+-]+)s", line)
        if m:
            sections[m.group(1)] = sections.get(m.group(1), 0.) + \
                float(m.group(5))
    return sections


def read_vtu(filename):
    """Points and point data of one VTU piece written by deal.II (base64
    binary, zlib-compressed or not, or ascii): {'points': [(x, y, z)],
    name: [values]}; a vector field gives tuples. An empty piece gives
    empty lists."""
    import base64
    import struct
    import zlib
    with open(filename) as f:
        text = f.read()
    compressed = "vtkZLibDataCompressor" in text

    def decode(payload, kind):
        payload = "".join(payload.split())
        if compressed:
            head = base64.b64decode(payload[:8])
            n_blocks = struct.unpack("<I", head[:4])[0]
            header_chars = 4 * ((4 * (3 + n_blocks) + 2) // 3)
            header = struct.unpack("<%dI" % (3 + n_blocks),
                                   base64.b64decode(payload[:header_chars]))
            data = base64.b64decode(payload[header_chars:])
            raw, start = b"", 0
            for size in header[3:]:
                raw += zlib.decompress(data[start:start + size])
                start += size
        else:
            raw = base64.b64decode(payload)[4:]
        code = {"Float32": "f", "Float64": "d", "Int32": "i",
                "UInt8": "B", "Int64": "q"}[kind]
        return struct.unpack("<%d%s" % (len(raw) // struct.calcsize(code),
                                        code), raw)

    result = {}
    for attributes, payload in re.findall(
            r"<DataArray([^>]*)>(.*?)</DataArray>", text, re.S):
        kind = re.search(r'type="(\w+)"', attributes).group(1)
        name = re.search(r'Name="([^"]+)"', attributes)
        components = re.search(r'NumberOfComponents="(\d+)"', attributes)
        if 'format="ascii"' in attributes:
            values = tuple(float(v) for v in payload.split())
        elif not payload.strip():
            values = ()
        else:
            values = decode(payload, kind)
        n = int(components.group(1)) if components else 1
        if n > 1:
            values = [tuple(values[i:i + n])
                      for i in range(0, len(values), n)]
        if name is None:
            if "points" not in result:
                result["points"] = values
        else:
            result[name.group(1)] = values
    return result


def snapshots(directory, name="points"):
    """(time, piece files) of each snapshot listed in name.pvd."""
    with open(os.path.join(directory, name + ".pvd")) as f:
        entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"',
                             f.read())
    result = []
    for time_value, pvtu in entries:
        with open(os.path.join(directory, pvtu)) as f:
            pieces = re.findall(r'Source="([^"]+)"', f.read())
        result.append((float(time_value),
                       [os.path.join(directory, p) for p in pieces]))
    return result


def read_snapshot(files):
    """The pieces of one snapshot merged: {'points': [...], name: [...]}."""
    merged = {}
    for f in files:
        for key, values in read_vtu(f).items():
            merged.setdefault(key, []).extend(values)
    return merged


def surface_profile(points, h):
    """Height of the material in columns of width h: the top of the highest
    point (its centre plus a quarter cell, for 2 x 2 points per cell) in
    each column."""
    columns = {}
    for x, y, _ in points:
        k = int(x // h)
        columns[k] = max(columns.get(k, 0.0), y + h / 4)
    return [((k + 0.5) * h, columns[k]) for k in sorted(columns)]


def profile_crossing(profile, depth):
    """Where the surface, walking out from the wall, first falls below
    `depth`: interpolated between the column centres, so that the measure
    does not change with the columns' width."""
    previous = None
    for x, height in profile:
        if height < depth:
            if previous is None:
                return x
            x0, h0 = previous
            return x0 + (x - x0) * (h0 - depth) / (h0 - height)
        previous = (x, height)
    return previous[0]


def profile_toe(profile, h):
    """The run-out: the right edge of the last column, walking out from the
    wall, of the connected material at least one cell deep (stray points
    ahead of the front do not count)."""
    toe = 0.0
    previous = None
    for x, height in profile:
        if previous is not None and x - previous > 1.5 * h:
            break
        if height >= h:
            toe = x + h / 2
        previous = x
    return toe
