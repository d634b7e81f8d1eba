"""Scenes and axes to the flat per-case columns the compiled engine takes, and back."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import polars as pl

from .scene import INERTIAS, INTEGRATORS, NORMAL_LAWS, Scene
from .shapes import ConvexPolygon, Disc

#: Float columns, in the engine's order.
FLOAT_COLUMNS = ("theta_deg", "omega_in", "v", "mu", "gamma", "gamma_t", "E", "rho", "r", "phi0_deg",
                 "dt_factor", "kn", "cn", "kt")

#: Record columns, in output order (MODEL.md names).
RECORD_COLUMNS = ("e_n", "e_t", "e_kin", "omega_out", "beta", "rebound_angle_deg", "vx_out", "vy_out",
                  "contact_time", "steps", "contacts", "max_depth", "max_area", "slip_events", "energy_in",
                  "energy_out", "work_normal", "work_friction", "energy_residual", "separated", "timed_out")

#: Axes whose values are names; the engine gets their index in these tuples. ``integrator``
#: is a per-case engine column; ``normal_law`` and ``inertia`` are per call, so a sweep over
#: them runs one engine call per value group (see :func:`restitution.sweep.run_per_case`).
CHOICE_AXES = {"integrator": INTEGRATORS, "normal_law": NORMAL_LAWS, "inertia": INERTIAS}

#: Names accepted as sweep axes (``n``: the shape, 0 for an exact disc, >= 3 for a regular n-gon).
AXES = FLOAT_COLUMNS + ("n",) + tuple(CHOICE_AXES)


def scene_defaults(scene: Scene) -> dict[str, Any]:
    """The scene's value of every engine column."""
    kn = scene.E if scene.kn is None else scene.kn
    return {
        "theta_deg": np.nan, "omega_in": 0.0, "v": scene.v, "mu": scene.mu, "gamma": scene.gamma,
        "gamma_t": scene.gamma_t, "E": scene.E, "rho": scene.rho, "r": scene.r,
        "phi0_deg": float(getattr(scene.shape, "phi0_deg", 0.0)), "dt_factor": scene.dt_factor,
        "kn": kn, "cn": 0.0 if scene.cn is None else scene.cn,
        "kt": np.nan if scene.kt is None else scene.kt,
        "n": 0 if isinstance(scene.shape, Disc) else int(scene.shape.n),
        "integrator": INTEGRATORS.index(scene.integrator),
        "normal_law": NORMAL_LAWS.index(scene.normal_law),
        "inertia": INERTIAS.index(scene.inertia),
    }


def _as_float_array(name: str, values: Any) -> np.ndarray:
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"`{name}` must be a number or a 1-D array of numbers (found {values!r:.80})") from None
    if a.ndim > 1:
        raise ValueError(f"require `{name}` a scalar or 1-D array (found shape {a.shape})")
    return np.atleast_1d(a)


def validate_axis(name: str, values: Any, scene: Scene) -> np.ndarray:
    """Checks one axis' values with the same rules as the scalar fields; returns a 1-D array."""
    if name in CHOICE_AXES:
        names = CHOICE_AXES[name]
        vals = [values] if isinstance(values, str) else list(np.atleast_1d(np.asarray(values, dtype=object)))
        if not vals:
            raise ValueError(f"require `{name}` non-empty")
        for v in vals:
            if v not in names:
                choices = ", ".join(f'"{c}"' for c in names)
                raise ValueError(f"require `{name}` values in {choices} (found {v!r})")
        table = INTEGRATORS if name == "integrator" else names
        return np.array([table.index(v) for v in vals], dtype=np.int64)
    if name == "n":
        a = np.atleast_1d(np.asarray(values))
        if a.ndim != 1 or not np.issubdtype(a.dtype, np.integer):
            raise TypeError(f"`n` must be an integer or a 1-D array of integers (found {values!r:.80})")
        if isinstance(scene.shape, ConvexPolygon):
            raise ValueError("`n` is not a sweep axis for a ConvexPolygon scene (its vertices are fixed)")
        if a.size == 0:
            raise ValueError("require `n` non-empty")
        if np.any((a < 3) & (a != 0)):
            raise ValueError(f"require `n` >= 3, or 0 for an exact disc (found {a[(a < 3) & (a != 0)][0]})")
        return a.astype(np.int64)
    if name not in FLOAT_COLUMNS:
        allowed = ", ".join(AXES)
        raise ValueError(f"`{name}` is not a sweep axis; allowed axes: {allowed}")
    a = _as_float_array(name, values)
    if a.size == 0:
        raise ValueError(f"require `{name}` non-empty")
    bad = ~np.isfinite(a)
    if np.any(bad):
        raise ValueError(f"require `{name}` finite (found {a[bad][0]})")
    if name == "theta_deg":
        bad = (a <= 0.0) | (a > 90.0)
        rule = "in (0, 90] degrees, measured from the plate"
    elif name in ("v", "E", "rho", "r", "kn", "kt"):
        bad = a <= 0.0
        rule = "> 0"
    elif name in ("mu", "gamma", "gamma_t", "cn"):
        bad = a < 0.0
        rule = ">= 0"
    elif name == "dt_factor":
        # The bound per integrator is checked with the integrator axis in check_combinations.
        bad = a <= 0.0
        rule = "> 0"
    else:  # omega_in, phi0_deg: any finite value
        bad = np.zeros(a.shape, dtype=bool)
        rule = ""
    if np.any(bad):
        raise ValueError(f"require `{name}` {rule} (found {a[bad][0]})")
    return a


def check_combinations(scene: Scene, validated: Mapping[str, np.ndarray], *, rows: bool) -> None:
    """Rules that tie two parameters: dt_factor against each case's stability bound, and
    sphere inertia only for discs. ``rows``: the arrays are per-case columns (a cases table),
    else independent axes of a Cartesian product (every combination occurs)."""
    base = scene_defaults(scene)
    def col(name: str) -> np.ndarray:
        return validated[name] if name in validated else np.array([base[name]])
    _check_dt_bound(scene, validated, rows=rows)
    sphere = col("inertia") == INERTIAS.index("sphere")
    polygon = col("n") != 0 if not isinstance(scene.shape, ConvexPolygon) else np.array([True])
    clash = (sphere & polygon) if rows else np.array([sphere.any() and polygon.any()])
    if np.any(clash):
        where = f"case {int(np.argmax(clash))}: " if rows else ""
        raise ValueError(f'{where}require `inertia` "shape" for polygons ("sphere" applies to discs, n = 0, only)')


#: Axes the stability bound does not depend on: it holds for any speed, angle, spin and orientation.
_BOUND_FREE = ("theta_deg", "omega_in", "v", "phi0_deg", "dt_factor")

#: Largest number of cases (or combinations of the bound's axes) checked here; beyond it the
#: engine still refuses each case, naming it and its bound.
_BOUND_CHECK_MAX = 200_000


def dt_bounds(scene: Scene, cols: Mapping[str, np.ndarray], n: int, explain: bool = False) -> tuple[np.ndarray, list[str]]:
    """Each case's largest ``dt_factor`` (one formula, in the engine) and, with ``explain``, what sets it."""
    from . import _core

    laws = cols.get("normal_law", np.full(n, NORMAL_LAWS.index(scene.normal_law)))
    inertias = cols.get("inertia", np.full(n, INERTIAS.index(scene.inertia)))
    full = build_columns(scene, {k: v for k, v in cols.items() if k not in ("normal_law", "inertia")}, n)
    bounds, reasons = np.empty(n), [""] * n
    for law in np.unique(laws):
        for inertia in np.unique(inertias):
            sel = np.flatnonzero((laws == law) & (inertias == inertia))
            if sel.size:
                sub = {k: np.ascontiguousarray(v[sel]) for k, v in full.items()}
                b, why = _core.max_dt_factor_for(sub, template_vertices(scene), NORMAL_LAWS[law], INERTIAS[inertia], explain)
                bounds[sel] = b
                for i, w in zip(sel, why or ()):
                    reasons[i] = w
    return bounds, reasons


def _check_dt_bound(scene: Scene, validated: Mapping[str, np.ndarray], *, rows: bool) -> None:
    """dt_factor against the stability bound of every case (or combination of axes)."""
    base = scene_defaults(scene)
    dt = validated.get("dt_factor", np.array([base["dt_factor"]]))
    relevant = {k: v for k, v in validated.items() if k not in _BOUND_FREE}
    if rows:
        n = max([len(v) for v in validated.values()] + [1])
        if n > _BOUND_CHECK_MAX:
            return
        cols = {k: np.broadcast_to(v, n) for k, v in relevant.items()}
        bounds, _ = dt_bounds(scene, cols, n)
        bad = np.broadcast_to(dt, n) > bounds
        if np.any(bad):
            i = int(np.argmax(bad))
            _, why = dt_bounds(scene, {k: v[i:i + 1] for k, v in cols.items()}, 1, explain=True)
            integ = INTEGRATORS[int(np.broadcast_to(validated.get("integrator", base["integrator"]), n)[i])]
            raise ValueError(f"case {i}: require `dt_factor` in (0, {bounds[i]}] for the {integ} integrator "
                             f"({why[0]}; found {np.broadcast_to(dt, n)[i]})")
        return
    sizes = [len(v) for v in relevant.values()]
    n = int(np.prod(sizes)) if sizes else 1
    if n > _BOUND_CHECK_MAX:
        return
    grids = np.meshgrid(*relevant.values(), indexing="ij") if relevant else []
    cols = {k: g.ravel() for k, g in zip(relevant, grids)}
    bounds, _ = dt_bounds(scene, cols, n)
    i = int(np.argmin(bounds))
    if dt.max() > bounds[i]:
        one = {k: v[i:i + 1] for k, v in cols.items()}
        _, why = dt_bounds(scene, one, 1, explain=True)
        integ = INTEGRATORS[int(one["integrator"][0]) if "integrator" in one else base["integrator"]]
        where = ", ".join(f"{k} = {CHOICE_AXES[k][int(v[0])] if k in CHOICE_AXES else v[0]}" for k, v in one.items())
        at = f" at {where}" if where else ""
        raise ValueError(f"require `dt_factor` in (0, {bounds[i]}] for the {integ} integrator{at} "
                         f"({why[0]}; found {dt.max()})")


def build_columns(scene: Scene, per_case: Mapping[str, np.ndarray], n_cases: int) -> dict[str, np.ndarray]:
    """Engine columns of length ``n_cases``: per-case arrays where given, the scene's value elsewhere."""
    base = scene_defaults(scene)
    cols: dict[str, np.ndarray] = {}
    for name in FLOAT_COLUMNS:
        v = per_case.get(name)
        cols[name] = np.ascontiguousarray(v, dtype=np.float64) if v is not None else np.full(n_cases, base[name], dtype=np.float64)
    for name in ("n", "integrator"):
        v = per_case.get(name)
        cols[name] = np.ascontiguousarray(v, dtype=np.int64) if v is not None else np.full(n_cases, base[name], dtype=np.int64)
    if scene.kn is None and "E" in per_case:
        cols["kn"] = cols["E"].copy()  # kn defaults to E case by case
    return cols


def template_vertices(scene: Scene) -> np.ndarray | None:
    """Unit-circumradius vertices of a ConvexPolygon scene (the engine scales them by r)."""
    if isinstance(scene.shape, ConvexPolygon):
        return scene.shape._template
    return None


def records_frame(raw: Mapping[str, np.ndarray]) -> pl.DataFrame:
    """Record columns as a polars frame; e_t and beta are null (never NaN) where undefined."""
    frame = pl.DataFrame({name: raw[name] for name in RECORD_COLUMNS + ("e_t_valid", "beta_valid")})
    return frame.with_columns(
        pl.when(pl.col("e_t_valid")).then(pl.col("e_t")).otherwise(None).alias("e_t"),
        pl.when(pl.col("beta_valid")).then(pl.col("beta")).otherwise(None).alias("beta"),
    ).drop("e_t_valid", "beta_valid")
