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
from .study import analysis, calibrate, inverse, theory  # rs.theory, rs.analysis, ...: the study's numbers

__all__ = [
    "ConvexPolygon",
    "Disc",
    "MAX_DT_FACTOR",
    "Record",
    "RegularPolygon",
    "RestitutionError",
    "Scene",
    "Sphere",
    "__version__",
    "analysis",
    "calibrate",
    "inverse",
    "read_dataset",
    "simulate",
    "sweep",
    "sweep_to_dataset",
    "theory",
]
