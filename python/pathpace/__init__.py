"""pathpace: time-optimal timing of robot paths under velocity, acceleration, torque and contact limits."""

from importlib.metadata import PackageNotFoundError, version as _version

from . import _core
from ._core import (
    AccelerationLimits,
    Constraint,
    ConstraintRows,
    Contact,
    ContactConstraint,
    ContactForces,
    ContactWrenches,
    CubicSplinePath,
    Error,
    FeasibleSet,
    FrameLimits,
    InvalidInputError,
    LinearConstraint,
    Path,
    PathSamples,
    PiecewisePolynomialPath,
    Result,
    RobotModel,
    SampledPath,
    SecondOrderConstraint,
    Status,
    TimeScalingProblem,
    TorqueLimits,
    Trajectory,
    VelocityLimits,
    auto_grid,
    contact_phase_of_s,
)

from .batch import solve_many
from .paths import as_path

try:
    __version__ = _version("pathpace")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.0.0"

__all__ = [
    "as_path",
    "auto_grid",
    "contact_phase_of_s",
    "AccelerationLimits",
    "Constraint",
    "ConstraintRows",
    "Contact",
    "ContactConstraint",
    "ContactForces",
    "ContactWrenches",
    "CubicSplinePath",
    "Error",
    "FeasibleSet",
    "FrameLimits",
    "InvalidInputError",
    "LinearConstraint",
    "Path",
    "PathSamples",
    "PiecewisePolynomialPath",
    "Result",
    "RobotModel",
    "SampledPath",
    "SecondOrderConstraint",
    "Status",
    "TimeScalingProblem",
    "TorqueLimits",
    "Trajectory",
    "VelocityLimits",
    "__version__",
    "solve_many",
]
