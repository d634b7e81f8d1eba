"""Calibration configs: a TOML file to a checked fit problem and its options.

Layout (``examples/calibrate_kharaz.toml`` is a documented example)::

    [scene]                  # as in a sweep config: a preset, any Scene field, [scene.shape], [scene.partner]
    normal_law = "hertz"
    [scene.shape]
    kind = "sphere"
    r = 0.0025
    [data]
    file = "measurements.csv"    # CSV or Parquet (theta_deg, omega_in, quantity, value, sigma), relative
                                 # to this file; or builtin = "kharaz2001"
    [free]                   # scene field -> prior, as an ensemble's distributions
    mu = { dist = "uniform", lo = 0.0, hi = 0.3 }
    [fit]                    # rs.calibrate.fit's options, all optional
    seed = 1
    likelihood = "gaussian"  # or "student-t" (with df)

Every error is a ``ValueError`` of one line naming the key.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import polars as pl

from .. import datasets
from ..runs.config import ConfigError, _check_keys, _scene, _table, failer
from ..runs.distributions import from_dict
from .problem import Problem
from .sampler import make_problem

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

TOP_KEYS = ("scene", "data", "free", "fit")
DATA_KEYS = ("file", "builtin")
#: [fit] keys: the problem's (likelihood, df, tol), then the sampler's.
FIT_KEYS = ("likelihood", "df", "tol", "seed", "walkers", "max_iter", "min_ess", "rhat_max")
BUILTIN = {"kharaz2001": datasets.kharaz2001}


def load(path: str | Path) -> tuple[Problem, dict[str, Any]]:
    """Reads a calibration config: (the checked problem, the sampler's options)."""
    path = Path(path)
    fail = failer(str(path))
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as err:
        raise ConfigError(f"{path}: cannot read the config ({err.strerror})") from None
    except tomllib.TOMLDecodeError as err:
        raise ConfigError(f"{path}: invalid TOML: {' '.join(str(err).split())}") from None
    _check_keys(data, TOP_KEYS, "", fail)
    scene = _scene(_table(data, "scene", fail), fail)
    measurements = _data(_table(data, "data", fail), path.parent, fail)
    free = {name: from_dict(d, f"{path}: free.{name}") for name, d in _table(data, "free", fail).items()}
    if not free:
        raise fail("free", "require at least one free scene field, e.g. mu = { dist = \"uniform\", lo = 0, hi = 1 }")
    options = _table(data, "fit", fail)
    _check_keys(options, FIT_KEYS, "fit", fail)
    try:
        problem = make_problem(scene, measurements, free, options.get("likelihood", "gaussian"),
                               options.get("df", 4.0), options.get("tol"))
    except (ValueError, TypeError) as err:
        raise fail("", str(err)) from None
    return problem, {k: v for k, v in options.items() if k not in ("likelihood", "df", "tol")}


def _data(table: dict[str, Any], base: Path, fail: Any) -> pl.DataFrame:
    _check_keys(table, DATA_KEYS, "data", fail)
    if ("file" in table) == ("builtin" in table):
        raise fail("data", "require exactly one of `file` (CSV or Parquet) and `builtin` ("
                   + ", ".join(map(repr, BUILTIN)) + ")")
    if "builtin" in table:
        if table["builtin"] not in BUILTIN:
            raise fail("data.builtin", f"require one of {', '.join(map(repr, BUILTIN))} (found {table['builtin']!r})")
        return BUILTIN[table["builtin"]]()
    file = base / str(table["file"])
    try:
        frame = pl.read_parquet(file) if file.suffix == ".parquet" else pl.read_csv(file)
    except (OSError, pl.exceptions.PolarsError) as err:
        raise fail("data.file", f"cannot read {file} ({' '.join(str(err).split())[:200]})") from None
    try:
        return datasets.check_measurements(frame)
    except ValueError as err:
        raise fail("data.file", f"{file}: {err}") from None


__all__ = ["load"]
