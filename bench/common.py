"""Shared pieces of the pathpace-vs-toppra benchmarks: the Panda problem, an independent spline, independent
constraint checks, interleaved timing, machine description.

Nothing here uses pathpace: the problem data come from the URDF (pinocchio, cross-checked against the XML),
and the checks are plain numpy on an independently built cubic spline, so that neither library checks itself.
"""

from __future__ import annotations

import os

# One thread everywhere (set before numpy is imported anywhere): the machine is shared and both libraries
# are meant to be compared single-threaded.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
             "VECLIB_MAXIMUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ[_var] = "1"

import importlib.metadata  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import xml.etree.ElementTree as ET  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

PANDA_URDF = "panda_description/urdf/panda.urdf"
PANDA_JOINTS = [f"panda_joint{i}" for i in range(1, 8)]


# ----------------------------------------------------------------------------------------------- problem
def robots_dir() -> Path:
    dist = importlib.metadata.distribution("example-robot-data")
    return Path(str(dist.locate_file("cmeel.prefix/share/example-robot-data/robots")))


def panda_limits() -> dict[str, np.ndarray]:
    """Position and velocity limits of the 7 arm joints, from pinocchio's URDF parser (fingers ignored),
    cross-checked against the URDF's XML."""
    import pinocchio as pin

    urdf = robots_dir() / PANDA_URDF
    model = pin.buildModelFromUrdf(str(urdf))
    lower, upper, vel = [], [], []
    for name in PANDA_JOINTS:
        joint = model.joints[model.getJointId(name)]
        assert joint.nq == 1 and joint.nv == 1, name
        lower.append(model.lowerPositionLimit[joint.idx_q])
        upper.append(model.upperPositionLimit[joint.idx_q])
        vel.append(model.velocityLimit[joint.idx_v])
    lim = {"lower": np.array(lower), "upper": np.array(upper), "velocity": np.array(vel)}
    xml = {j.get("name"): j.find("limit") for j in ET.parse(str(urdf)).getroot().iter("joint")}
    for key, attr in (("lower", "lower"), ("upper", "upper"), ("velocity", "velocity")):
        from_xml = np.array([float(xml[n].get(attr)) for n in PANDA_JOINTS])
        assert np.array_equal(from_xml, lim[key]), f"pinocchio and the URDF XML disagree on {key}"
    assert np.all(lim["velocity"] > 0) and np.all(np.isfinite(lim["velocity"]))
    return lim


def panda_problem(seed: int = 0, n_waypoints: int = 5):
    """Seeded waypoints strictly inside the position limits (10 %..90 % of each range), velocity limits from
    the URDF, acceleration limits 2x the velocity limits."""
    lim = panda_limits()
    rng = np.random.default_rng(seed)
    lo, hi = lim["lower"], lim["upper"]
    waypoints = lo + (hi - lo) * rng.uniform(0.1, 0.9, (n_waypoints, len(PANDA_JOINTS)))
    v = lim["velocity"]
    return waypoints, v, 2.0 * v


def import_example(name: str):
    """examples/<name>.py as a module (talos_sway, humanoid_steps, ...), with examples/ first on sys.path: the
    examples import each other by name, and bench/humanoid_steps.py must not find itself under its example's
    name. Importing it through here also means a bench script has imported common, so its one-thread BLAS
    pinning came before numpy."""
    examples = str(Path(__file__).resolve().parents[1] / "examples")
    if not sys.path or sys.path[0] != examples:
        sys.path.insert(0, examples)
    return importlib.import_module(name)


# ------------------------------------------------------------------------------- independent reference
class NotAKnotSpline:
    """Cubic spline through (knots, waypoints) with not-a-knot ends, by second-derivative moments (own code:
    the reference both libraries' paths are compared with and judged on)."""

    def __init__(self, knots, waypoints):
        x = np.asarray(knots, float)
        y = np.asarray(waypoints, float)
        K = len(x)
        assert K >= 4, "not-a-knot with distinct end conditions needs 4 points"
        h = np.diff(x)
        A = np.zeros((K, K))
        rhs = np.zeros((K, y.shape[1]))
        for i in range(1, K - 1):
            A[i, i - 1:i + 2] = h[i - 1], 2 * (h[i - 1] + h[i]), h[i]
            rhs[i] = 6 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1])
        # S''' continuous at x_1 and x_{K-2}: (M1-M0)/h0 = (M2-M1)/h1, same at the other end
        A[0, :3] = 1 / h[0], -1 / h[0] - 1 / h[1], 1 / h[1]
        A[-1, -3:] = 1 / h[-2], -1 / h[-2] - 1 / h[-1], 1 / h[-1]
        self.x, self.y, self.h = x, y, h
        self.M = np.linalg.solve(A, rhs)

    def __call__(self, s, order=0):
        s = np.asarray(s, float)
        i = np.clip(np.searchsorted(self.x, s, side="right") - 1, 0, len(self.x) - 2)
        t = (s - self.x[i])[:, None]
        h = self.h[i][:, None]
        y0, y1, M0, M1 = self.y[i], self.y[i + 1], self.M[i], self.M[i + 1]
        b = (y1 - y0) / h - h * (2 * M0 + M1) / 6
        d = (M1 - M0) / (6 * h)
        if order == 0:
            return y0 + t * (b + t * (M0 / 2 + t * d))
        if order == 1:
            return b + t * (M0 + 3 * t * d)
        if order == 2:
            return M0 + 6 * t * d
        raise ValueError(order)


def times_from_sdot(s, sdot):
    """Grid times of a constant-s̈-per-interval profile: Δt_k = 2Δs_k / (ṡ_k + ṡ_{k+1})."""
    return np.concatenate([[0.0], np.cumsum(2 * np.diff(s) / (sdot[:-1] + sdot[1:]))])


def grid_excess(ref, s, sdot, v, a):
    """Per grid point, the largest relative excess max_j (|q̇_j| - v_j)/v_j, (|q̈_j| - a_j)/a_j, clipped at 0:
    rows (velocity, acceleration with the interval after, acceleration with the interval before), ṡ at the
    point and s̈ of the interval on EACH side of it (s̈_k = (ṡ_{k+1}² - ṡ_k²)/(2Δs_k), eq. 26)."""
    dq, ddq = ref(s, 1), ref(s, 2)
    x = sdot**2
    u = (x[1:] - x[:-1]) / (2 * np.diff(s))
    rows = np.full((3, len(s)), -np.inf)
    rows[0] = (np.abs(dq * sdot[:, None]) / v - 1).max(axis=1)
    rows[1, :-1] = (np.abs(ddq[:-1] * x[:-1, None] + dq[:-1] * u[:, None]) / a - 1).max(axis=1)
    rows[2, 1:] = (np.abs(ddq[1:] * x[1:, None] + dq[1:] * u[:, None]) / a - 1).max(axis=1)
    return np.maximum(rows, 0.0)


def grid_violation(ref, s, sdot, v, a):
    """grid_excess's largest values: (overall, velocity, acceleration with the interval after, acceleration
    with the interval before)."""
    vel, fwd, bwd = (float(r.max()) for r in grid_excess(ref, s, sdot, v, a))
    return max(vel, fwd, bwd), vel, fwd, bwd


def dense_times(s, sdot, per_interval=20):
    """`per_interval` times strictly inside each interval (at (j + 1/2)/per_interval of it), from the
    independently computed grid times, so no sample sits on a grid point where s̈ is two-valued."""
    t = times_from_sdot(s, sdot)
    frac = (np.arange(per_interval) + 0.5) / per_interval
    return (t[:-1, None] + np.diff(t)[:, None] * frac[None, :]).ravel()


def reconstruct(ref, s, sdot, t):
    """q̇, q̈ at times t of the constant-s̈-per-interval profile through (s, ṡ), by own code."""
    tk = times_from_sdot(s, sdot)
    k = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(s) - 2)
    u = (sdot[1:] ** 2 - sdot[:-1] ** 2) / (2 * np.diff(s))
    tau = t - tk[k]
    sd = sdot[k] + u[k] * tau
    ss = s[k] + sdot[k] * tau + 0.5 * u[k] * tau**2
    dq, ddq = ref(ss, 1), ref(ss, 2)
    return dq * sd[:, None], ddq * sd[:, None] ** 2 + dq * u[k][:, None]


def dense_violation(qd, qdd, v, a):
    return max(0.0, (np.abs(qd) / v - 1).max(), (np.abs(qdd) / a - 1).max())


# ----------------------------------------------------------------------------------------------- timing
def interleaved_timing(fns: dict, rounds: int, block: int, warmup: int = 1):
    """Block-interleaved timing. Each round runs, for every function in a rotating order (so load drift
    hits all alike), 1 + `block` consecutive calls: the first ("cold": it follows another library's calls,
    whose memory traffic has evicted this one's caches and pages) is kept apart, the other `block` ("warm",
    steady state of repeated solves) are the headline samples. The garbage collector is left at its
    defaults. Returns {name: {"wall"|"cpu": {"warm"|"cold": [[s per call] per round]}}} and the last
    return value of every function."""
    names = list(fns)
    out = {n: {"wall": {"warm": [], "cold": []}, "cpu": {"warm": [], "cold": []}} for n in names}
    last = {}
    for _ in range(warmup):
        for n in names:
            last[n] = fns[n]()
    for r in range(rounds):
        for i in range(len(names)):
            n = names[(r + i) % len(names)]
            wall, cpu = [], []
            for _ in range(1 + block):
                c0, w0 = time.thread_time(), time.perf_counter()
                last[n] = fns[n]()
                w1, c1 = time.perf_counter(), time.thread_time()
                wall.append(w1 - w0)
                cpu.append(c1 - c0)
            out[n]["wall"]["cold"].append([wall[0]])
            out[n]["wall"]["warm"].append(wall[1:])
            out[n]["cpu"]["cold"].append([cpu[0]])
            out[n]["cpu"]["warm"].append(cpu[1:])
    return out, last


def summary(samples):
    q = np.percentile(samples, [25, 50, 75])
    return {"median": float(statistics.median(samples)), "q25": float(q[0]), "q75": float(q[2]),
            "min": float(min(samples)), "n": len(samples)}


# ---------------------------------------------------------------------------------------------- machine
def build_info() -> dict:
    """Which build was measured: the repository's commit (read only) and the installed extension's mtime."""
    info = {}
    root = Path(__file__).resolve().parent.parent
    try:
        info["commit"] = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True,
                                        text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.split("\n")
        info["modified_files"] = [d[3:] for d in dirty if d.strip()]
    except (OSError, subprocess.CalledProcessError):
        pass
    try:
        import pathpace._core as core

        info["extension_mtime"] = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(os.path.getmtime(core.__file__)))
    except (ImportError, OSError):
        pass
    return info


def machine() -> dict:
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        env = {k: v for k, v in os.environ.items() if k not in ("OMP_NUM_THREADS", "OMP_THREAD_LIMIT")}
        nproc = int(subprocess.run(["nproc"], capture_output=True, text=True, check=True, env=env).stdout)  # honours OMP_*
    except (OSError, subprocess.CalledProcessError, ValueError):
        nproc = os.cpu_count()

    def version(dist):
        try:
            return importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            return "?"

    return {"cpu": cpu, "nproc": nproc, "os": platform.platform(), "python": platform.python_version(),
            "pathpace": version("pathpace"), "toppra": version("toppra"), "numpy": version("numpy"),
            "scipy": version("scipy"), "pin": version("pin"),
            "copp": version("copp-py")}


def write_generated_section(section: str, begin: str, end: str, heading: str, path: Path | None = None) -> None:
    """Put `section` (which starts with `begin` and ends with `end`) into `path` (bench/README.md) in place of
    the block between those markers; without them, right under `heading` (a markdown heading line) if the
    README has that line, else appended under a new one."""
    path = path or Path(__file__).resolve().parent / "README.md"
    text = path.read_text() if path.exists() else "# Benchmarks\n"
    if begin in text and end in text:
        text = text[:text.index(begin)] + section + text[text.index(end) + len(end):]
    else:
        lines = text.splitlines(keepends=True)
        at = next((i for i, line in enumerate(lines) if line.rstrip("\n") == heading), None)
        if at is None:
            text = text.rstrip("\n") + "\n\n" + heading + "\n\n" + section + "\n"
        else:  # the heading is there (its markers were removed by hand): not a second one
            head = "".join(lines[:at + 1])
            text = head + ("" if head.endswith("\n") else "\n") + "\n" + section + "\n" + "".join(lines[at + 1:])
    path.write_text(text)
