"""The rod of the paper's sec. IV.E (fig. 3): a rod of mass 1 and length 2 stands on a frictional point
contact (μ = 0.5) and turns about it with |τ| <= 2; its centre sits on the circle of radius 1 around
the contact. The path is the lean angle θ; the feasible (ṡ², s̈) sets at several θ come from projecting
the polytope of eq. (18) (pathpace's recursive expansion), and match the analytic constraints of
eqs. (20)-(23).

    .venv/bin/python examples/rod_contact.py [--plot]

Observations of the paper, reproduced here: accelerations are available only near the vertical; above
about ṡ = √7 the set is bounded by the friction diagonals; beyond ṡ² = g no speed is feasible.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import pathpace as pp

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
G, MU = 9.81, 0.5


def rod_path(thetas: np.ndarray) -> pp.SampledPath:
    """q = (x, z, angle) of the rod's centre with its lower end on the origin: x = -sin θ, z = cos θ,
    angle = -θ; p' and p'' in closed form (θ'(s) = 1)."""
    th = np.asarray(thetas, dtype=float)
    q = np.column_stack([-np.sin(th), np.cos(th), -th])
    dq = np.column_stack([-np.cos(th), -np.sin(th), -np.ones_like(th)])
    ddq = np.column_stack([np.sin(th), -np.cos(th), np.zeros_like(th)])
    return pp.SampledPath(th, q, dq, ddq)


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--plot", action="store_true", help="write examples/output/rod_feasible_sets.png")
    args = ap.parse_args(argv)
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    thetas = np.round(np.linspace(-0.4, 0.4, 9), 12)
    prob = pp.TimeScalingProblem(rod_path(thetas), grid=thetas)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=MU)], cone_edges=4)
    sets = {}
    print(f"{'θ (rad)':>8s} {'edges':>5s} {'max ṡ²':>8s} {'s̈ range at ṡ = 0':>22s}")
    for k, th in enumerate(thetas):
        fs = prob.feasible_set(k)
        sets[th] = fs
        if fs.empty:
            print(f"{th:8.2f}  empty")
            continue
        at_rest = [fs.contains(0.0, u) for u in np.linspace(-20, 20, 4001)]
        us = np.linspace(-20, 20, 4001)[np.array(at_rest)]
        rng = f"[{us.min():6.2f}, {us.max():6.2f}]" if len(us) else "none"
        print(f"{th:8.2f} {fs.halfplanes.shape[0]:5d} {np.max(fs.vertices[:, 0]):8.3f} {rng:>22s}")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 5))
        for th, fs in sets.items():
            if fs.empty or th < 0:  # the set is mirrored in θ -> -θ, s̈ -> -s̈
                continue
            v = np.vstack([fs.vertices, fs.vertices[:1]])  # a closed polygon in (ṡ², s̈)
            line, = ax.plot(v[:, 0], v[:, 1], marker=".", label=f"θ = {th:.1f}")
            ax.fill(v[:, 0], v[:, 1], color=line.get_color(), alpha=0.08)
        ax.axvline(7.0, color="grey", ls=":", lw=0.8)
        ax.axvline(G, color="k", ls="--", lw=0.8)
        ax.text(7.05, -1.9, "ṡ = √7", fontsize=8)
        ax.text(G - 0.9, -1.9, "ṡ² = g", fontsize=8)
        ax.set_xlabel("ṡ² (rad²/s²)")
        ax.set_ylabel("s̈ (rad/s²)")
        ax.set_xlim(0, 10.5)
        ax.set_title("Rod on a frictional point contact: feasible (ṡ², s̈) sets (cf. paper fig. 3)")
        ax.legend()
        out = Path(__file__).resolve().parent / "output"
        out.mkdir(exist_ok=True)
        fig.tight_layout()
        fig.savefig(out / "rod_feasible_sets.png", dpi=110)
        print(f"plot: {out / 'rod_feasible_sets.png'}")
    return sets


if __name__ == "__main__":
    main()
