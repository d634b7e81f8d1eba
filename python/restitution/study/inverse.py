"""The inverse map: which impacts produce a measured restitution coefficient?

Given a sweep and a measured value (say e_T = 0.9 +- 0.01), :func:`find` returns every impact
configuration in the sweep that produces it: along each curve (one per combination of the
non-theta axes, e.g. per (mu, omega_in)) the sampled values are joined linearly in theta, every
crossing of the measured value is located between grid points, and the theta interval in which
the curve stays within the tolerance is reported with it. Curves that come within the tolerance
without crossing give a "near" row. This is the study's point made quantitative: one e_T or e_kin
maps onto many (theta, mu, omega_in).

Examples
--------
>>> import numpy as np, polars as pl
>>> from restitution import inverse
>>> th = np.arange(4.0, 90.0)
>>> df = pl.DataFrame({"theta_deg": th, "e_n": 0.9, "e_t": 1.0 - th / 100})  # a toy sweep frame
>>> sol = inverse.find(df, "e_t", 0.9, tol=0.01)
>>> sol.select("theta_deg", "theta_lo", "theta_hi", "kind").rows()
[(10.0, 9.0, 11.0, 'crossing')]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import polars as pl

from .analysis import _curves, group_columns

#: Record columns interpolated to each solution when present.
_CARRIED = ("e_n", "e_t", "e_kin", "omega_out", "beta")


def _band(theta: np.ndarray, d: np.ndarray, tol: float) -> list[list[float]]:
    """Merged theta intervals in which the piecewise-linear d(theta) satisfies |d| <= tol."""
    out: list[list[float]] = []
    for j in range(len(theta) - 1):
        d0, d1 = d[j], d[j + 1]
        delta = d1 - d0
        if delta == 0.0:
            if abs(d0) > tol:
                continue
            t0, t1 = 0.0, 1.0
        else:
            a, b = sorted(((-tol - d0) / delta, (tol - d0) / delta))
            t0, t1 = max(a, 0.0), min(b, 1.0)
            if t0 > t1:
                continue
        lo = theta[j] + t0 * (theta[j + 1] - theta[j])
        hi = theta[j] + t1 * (theta[j + 1] - theta[j])
        if out and lo <= out[-1][1] + 1e-12 * max(1.0, abs(lo)):
            out[-1][1] = max(out[-1][1], hi)
        else:
            out.append([lo, hi])
    if len(theta) == 1 and abs(d[0]) <= tol:
        out.append([theta[0], theta[0]])
    return out


def _crossings(theta: np.ndarray, d: np.ndarray) -> list[tuple[float, int, float]]:
    """(theta*, segment index, fraction) where d changes sign or is exactly zero at a grid point."""
    out = []
    n = len(theta)
    for j in range(n):
        if d[j] == 0.0:
            # A zero on the grid counts once, and only where the curve actually reaches it.
            out.append((float(theta[j]), min(j, n - 2), 0.0 if j < n - 1 else 1.0))
        if j < n - 1 and d[j] * d[j + 1] < 0.0:
            f = d[j] / (d[j] - d[j + 1])
            out.append((float(theta[j] + f * (theta[j + 1] - theta[j])), j, f))
    return out


def find(df: pl.DataFrame, quantity: str, value: float, tol: float = 0.0) -> pl.DataFrame:
    """Every (theta, other axes) in a sweep at which ``quantity`` equals ``value`` (within ``tol``).

    Parameters
    ----------
    df : polars.DataFrame
        A sweep frame (:func:`restitution.sweep`): axis columns, then the record's.
    quantity : str
        The measured column, e.g. ``"e_t"``, ``"e_kin"``, ``"e_n"``, ``"omega_out"``.
    value : float
        The measured value.
    tol : float
        Its tolerance (>= 0): rows also give the theta interval in which the curve stays within
        ``value +- tol`` (piecewise linear between grid points), and curves that come that close
        without crossing give a row of kind "near".

    Returns
    -------
    polars.DataFrame
        One row per solution: the curve's axes, ``theta_deg`` (the interpolated crossing, or for
        "near" the closest approach), ``theta_lo`` and ``theta_hi`` (the band around it),
        ``kind`` ("crossing" or "near"), ``slope`` (d quantity / d theta per degree), and the
        record columns e_n, e_t, e_kin, omega_out, beta interpolated there. Sorted like the
        sweep's curves, then by theta.
    """
    _check_find_args(df, quantity, value, tol)
    keys = group_columns(df)
    carried = [c for c in _CARRIED if c in df.columns]
    rows: list[dict[str, Any]] = []
    for key, part in _curves(df):
        curve = _Curve.of(part, quantity, value, carried)
        if curve is not None:
            rows.extend(_curve_solutions(key, curve, tol))
    return _solutions_frame(rows, df, keys, carried)


def _check_find_args(df: pl.DataFrame, quantity: str, value: float, tol: float) -> None:
    """Refuses bad arguments up front, before any curve is looked at."""
    if quantity not in df.columns:
        raise ValueError(f"`quantity` {quantity!r} is not a column of the frame (columns: {', '.join(df.columns)})")
    if not np.isfinite(value):
        raise ValueError(f"require `value` finite (found {value})")
    if not (tol >= 0.0 and np.isfinite(tol)):
        raise ValueError(f"require `tol` finite and >= 0 (found {tol})")


@dataclass(frozen=True)
class _Curve:
    """One curve of the sweep (fixed non-theta axes) with its unusable samples dropped.

    ``d`` is the measured quantity minus the sought value, so solutions are the zeros of the
    piecewise-linear d(theta); ``cols`` are the record columns carried to each solution.
    """

    th: np.ndarray
    y: np.ndarray
    d: np.ndarray
    cols: dict[str, np.ndarray]

    @staticmethod
    def of(part: pl.DataFrame, quantity: str, value: float, carried: list[str]) -> _Curve | None:
        """The curve of one group's rows, or None when no row has the quantity (null everywhere)."""
        part = part.filter(pl.col(quantity).is_not_null())
        if part.height == 0:
            return None
        th = part["theta_deg"].to_numpy().astype(float)
        y = part[quantity].to_numpy().astype(float)
        keep = np.isfinite(y)
        th, y = th[keep], y[keep]
        cols = {c: part[c].to_numpy()[keep].astype(float) for c in carried}
        return _Curve(th, y, y - value, cols)

    def interp(self, j: int, f: float) -> dict[str, float]:
        """The carried columns at fraction ``f`` of segment ``j`` (the one sample if there is one)."""
        out = {}
        for c, arr in self.cols.items():
            out[c] = float(arr[j] + f * (arr[j + 1] - arr[j])) if len(arr) > 1 else float(arr[0])
        return out

    def slope(self, j: int) -> float:
        """d quantity / d theta on segment ``j`` (NaN for a one-sample curve)."""
        th, y = self.th, self.y
        return float((y[j + 1] - y[j]) / (th[j + 1] - th[j])) if len(th) > 1 else float("nan")


def _curve_solutions(key: dict[str, Any], curve: _Curve, tol: float) -> list[dict[str, Any]]:
    """The rows of one curve: each crossing with the band that holds it, then each band that
    holds no crossing as a "near" row at its closest approach."""
    bands = _band(curve.th, curve.d, tol) if tol > 0 else []
    rows = []
    used = set()
    for t, j, f in _crossings(curve.th, curve.d):
        lo = hi = t
        for b, (blo, bhi) in enumerate(bands):
            if blo - 1e-12 <= t <= bhi + 1e-12:
                lo, hi = blo, bhi
                used.add(b)
                break
        rows.append({**key, "theta_deg": t, "theta_lo": lo, "theta_hi": hi, "kind": "crossing",
                     "slope": curve.slope(j), **curve.interp(j, f)})
    for b, (blo, bhi) in enumerate(bands):
        if b in used:
            continue
        t, j, f = _closest_approach(curve, blo, bhi)
        rows.append({**key, "theta_deg": t, "theta_lo": blo, "theta_hi": bhi, "kind": "near",
                     "slope": curve.slope(j), **curve.interp(j, f)})
    return rows


def _closest_approach(curve: _Curve, blo: float, bhi: float) -> tuple[float, int, float]:
    """(theta, segment index, fraction) where |d| is smallest within the band [blo, bhi].

    |d| is piecewise linear, so the minimum is at a band end or at a grid point inside.
    """
    th = curve.th
    cand = [blo, bhi] + [float(t) for t in th if blo <= t <= bhi]
    dd = np.interp(cand, th, curve.d)
    t = cand[int(np.argmin(np.abs(dd)))]
    j = int(np.clip(np.searchsorted(th, t, side="right") - 1, 0, max(len(th) - 2, 0)))
    f = float((t - th[j]) / (th[j + 1] - th[j])) if len(th) > 1 else 0.0
    return t, j, f


def _solutions_frame(rows: list[dict[str, Any]], df: pl.DataFrame, keys: list[str],
                     carried: list[str]) -> pl.DataFrame:
    """The rows as a frame with a fixed schema (also when empty), sorted by curve, then theta."""
    schema: dict[str, Any] = {k: df.schema[k] for k in keys}
    schema.update({"theta_deg": pl.Float64, "theta_lo": pl.Float64, "theta_hi": pl.Float64, "kind": pl.Utf8,
                   "slope": pl.Float64})
    schema.update({c: pl.Float64 for c in carried})
    out = pl.DataFrame(rows, schema=schema) if rows else pl.DataFrame(schema=schema)
    return out.sort([*keys, "theta_deg"], maintain_order=True) if keys else out.sort("theta_deg")


def plot(solutions: pl.DataFrame, df: pl.DataFrame | None = None, *, quantity: str = "e_t", value: float | None = None,
         tol: float = 0.0, path: Any = None, title: str | None = None, **kwargs: Any):
    """Draws an inverse-map result: the curves of ``df`` (when given) with the band value +- tol
    and the solutions marked, and the solutions in the (theta, omega_in) plane (or theta alone).
    Returns the matplotlib figure; saves it when ``path`` is given. Other keywords (``r``, ``v``
    for the theory curves, ``reference``) go to :func:`restitution.figures.inverse_figure`."""
    from . import figures

    return figures.inverse_figure(solutions, df, quantity=quantity, value=value, tol=tol, path=path, title=title,
                                  **kwargs)


__all__ = ["find", "plot"]
