"""Robot files: where example-robot-data keeps its URDFs, and joint limits read from a URDF."""

from __future__ import annotations

import importlib.metadata
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np


def example_robot_data_dir() -> Path:
    """The robots/ folder of the example-robot-data package (it ships no Python module)."""
    try:
        dist = importlib.metadata.distribution("example-robot-data")
    except importlib.metadata.PackageNotFoundError as e:
        raise FileNotFoundError("example-robot-data is not installed: pip install example-robot-data "
                                "(or pathpace[examples])") from e
    return Path(str(dist.locate_file("cmeel.prefix/share/example-robot-data/robots")))


def example_robot_urdf(relative: str) -> Path:
    """e.g. example_robot_urdf("panda_description/urdf/panda.urdf")."""
    path = example_robot_data_dir() / relative
    if not path.is_file():
        raise FileNotFoundError(f"{relative} is not in example-robot-data ({path})")
    return path


def urdf_joint_limits(urdf: str | Path, joints: list[str] | None = None) -> dict[str, np.ndarray]:
    """Position, velocity and effort limits of the movable joints, in file order (or in `joints` order).

    Returns a dict with "names", "lower", "upper", "velocity", "effort" (absent limits are ±inf; continuous
    joints have no position limits).
    """
    root = ET.parse(str(urdf)).getroot()
    found = {}
    for j in root.iter("joint"):
        kind = j.get("type")
        if kind not in ("revolute", "continuous", "prismatic"):
            continue
        lim = j.find("limit")
        get = lambda key, default: float(lim.get(key)) if lim is not None and lim.get(key) is not None else default  # noqa: E731
        lower, upper = (-np.inf, np.inf) if kind == "continuous" else (get("lower", -np.inf), get("upper", np.inf))
        found[j.get("name")] = (lower, upper, get("velocity", np.inf), get("effort", np.inf))
    names = list(found) if joints is None else list(joints)
    missing = [n for n in names if n not in found]
    if missing:
        from ._core import InvalidInputError

        raise InvalidInputError(f"joints {missing} are not movable joints of {urdf}")
    table = np.array([found[n] for n in names], dtype=float).reshape(len(names), 4)
    return {"names": names, "lower": table[:, 0], "upper": table[:, 1], "velocity": table[:, 2], "effort": table[:, 3]}
