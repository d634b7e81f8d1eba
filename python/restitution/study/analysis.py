"""From a sweep to the study's numbers: theta_c, e_kin,min, exponential fits, micro-slip, Eq. 2.

All functions take a sweep frame (:func:`restitution.sweep`: axis columns first, then the record's)
and group it by every axis except ``theta_deg``, so a sweep over ``mu`` and ``omega_in`` gives one
result per (mu, omega_in).

Examples
--------
>>> import numpy as np, restitution as rs
>>> from restitution import analysis
>>> df = rs.sweep(rs.Scene(), theta_deg=np.arange(4.0, 89.5, 0.5), mu=[0.5, 1.0])
>>> crit = analysis.critical_angles(df)
>>> [(mu, round(t, 1)) for mu, t in crit.select("mu", "theta_c").rows()]
[(0.5, 19.4), (1.0, 9.9)]
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from numpy.typing import ArrayLike

import numpy as np
import polars as pl

from . import theory

#: The record's first column: every column before it in a sweep frame is an axis.
_FIRST_RECORD_COLUMN = "e_n"


def axis_columns(df: pl.DataFrame) -> list[str]:
    """The axis columns of a sweep frame (those before the record's ``e_n``)."""
    if _FIRST_RECORD_COLUMN not in df.columns or "theta_deg" not in df.columns:
        raise ValueError("expected a sweep frame with `theta_deg` and the record's columns (e_n, e_t, ...)")
    return df.columns[: df.columns.index(_FIRST_RECORD_COLUMN)]


def group_columns(df: pl.DataFrame) -> list[str]:
    """Axes other than theta_deg: one curve y(theta) per distinct combination."""
    return [c for c in axis_columns(df) if c != "theta_deg"]


def _curves(df: pl.DataFrame):
    """Yields (key dict, part sorted by theta) per curve, in the order of first appearance."""
    keys = group_columns(df)
    if not keys:
        yield {}, df.sort("theta_deg")
        return
    for key, part in df.group_by(keys, maintain_order=True):
        yield dict(zip(keys, key)), part.sort("theta_deg")


# --------------------------------------------------------------------------------------------
# Extrema with sub-grid refinement
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Extremum:
    """A located extremum: position, value, the model that located it ("kink-left", "kink-right",
    "parabola", "grid" or "edge") and the grid index nearest to it."""

    x: float
    y: float
    method: str
    index: int


def _line(x0: float, y0: float, x1: float, y1: float) -> tuple[float, float]:
    s = (y1 - y0) / (x1 - x0)
    return s, y0 - s * x0


def locate_min(x: ArrayLike, y: ArrayLike, method: str = "auto") -> Extremum:
    """The minimum of the sampled curve ``y(x)`` between grid points.

    A kink (the corner where the sliding and rolling branches meet) and a smooth minimum need
    different models. Three are tried around the grid minimum i, each fitted on four of the five
    points i-2 .. i+2 (three for the parabola) and judged by how well it predicts the others:

    - ``kink-left``: the corner lies in [x_{i-1}, x_i]; lines through (i-2, i-1) and (i, i+1)
      are intersected, and the right line must predict y_{i+2};
    - ``kink-right``: the mirror image, corner in [x_i, x_{i+1}];
    - ``parabola``: through i-1, i, i+1, which must predict y_{i-2} and y_{i+2}.

    ``method="auto"`` keeps the model with the smallest prediction error whose extremum lies in
    its interval; ``"kink"`` or ``"parabola"`` force a family. Near the ends of the grid it falls
    back to the parabola (``"grid"`` if even that is impossible); a minimum at the first or last
    point is returned with method ``"edge"`` (no interior minimum on this grid).

    >>> x = np.arange(0.0, 10.0, 1.0)
    >>> e = locate_min(x, np.abs(x - 4.3))
    >>> round(e.x, 12), round(e.y, 12), e.method
    (4.3, 0.0, 'kink-right')
    >>> e = locate_min(x, (x - 4.3) ** 2)
    >>> round(e.x, 12), e.method
    (4.3, 'parabola')
    """
    if method not in ("auto", "kink", "parabola"):
        raise ValueError(f'require `method` one of "auto", "kink", "parabola" (found {method!r})')
    xa = np.asarray(x, dtype=float)
    ya = np.asarray(y, dtype=float)
    if xa.shape != ya.shape or xa.ndim != 1 or len(xa) < 3:
        raise ValueError("require `x` and `y` 1-D of equal length >= 3")
    ok = np.isfinite(ya)
    if not ok.all():
        xa, ya = xa[ok], ya[ok]
        if len(xa) < 3:
            raise ValueError("require at least 3 finite values in `y`")
    if np.any(np.diff(xa) <= 0):
        raise ValueError("require `x` strictly increasing")
    i = int(np.argmin(ya))
    n = len(xa)
    if i == 0 or i == n - 1:
        return Extremum(float(xa[i]), float(ya[i]), "edge", i)
    cands: list[tuple[float, float, float, str]] = []  # (check error, x, y, name)
    if method in ("auto", "kink") and 2 <= i <= n - 3:
        # Corner left of x_i: left branch (i-2, i-1), right branch (i, i+1), check i+2.
        for name, left, right, check, lo, hi in (
            ("kink-left", (i - 2, i - 1), (i, i + 1), i + 2, xa[i - 1], xa[i]),
            ("kink-right", (i - 1, i), (i + 1, i + 2), i - 2, xa[i], xa[i + 1]),
        ):
            s1, b1 = _line(xa[left[0]], ya[left[0]], xa[left[1]], ya[left[1]])
            s2, b2 = _line(xa[right[0]], ya[right[0]], xa[right[1]], ya[right[1]])
            if not s1 < s2:
                continue
            xs = (b2 - b1) / (s1 - s2)
            if not lo <= xs <= hi:
                continue
            pred = (s2 * xa[check] + b2) if name == "kink-left" else (s1 * xa[check] + b1)
            cands.append((abs(pred - ya[check]), xs, s1 * xs + b1, name))
    if method in ("auto", "parabola"):
        x0, x1, x2 = xa[i - 1], xa[i], xa[i + 1]
        coef = np.polyfit([x0, x1, x2], [ya[i - 1], ya[i], ya[i + 1]], 2)
        if coef[0] > 0:
            xs = -coef[1] / (2 * coef[0])
            if x0 <= xs <= x2:
                checks = [j for j in (i - 2, i + 2) if 0 <= j < n]
                err = max((abs(np.polyval(coef, xa[j]) - ya[j]) for j in checks), default=np.inf)
                if method == "parabola":
                    err = -1.0
                cands.append((err, xs, float(np.polyval(coef, xs)), "parabola"))
    if not cands:
        return Extremum(float(xa[i]), float(ya[i]), "grid", i)
    err, xs, ys, name = min(cands, key=lambda c: c[0])
    # Sub-grid refinement may not raise the minimum above the sampled one.
    return Extremum(float(xs), float(min(ys, ya[i])), name, i)


def locate_max(x: ArrayLike, y: ArrayLike, method: str = "auto") -> Extremum:
    """The maximum of ``y(x)``, as :func:`locate_min` of ``-y``."""
    e = locate_min(x, -np.asarray(y, dtype=float), method)
    return Extremum(e.x, -e.y, e.method, e.index)


def critical_angles(df: pl.DataFrame, *, method: str = "auto", r: float | None = None, v: float | None = None,
                    kappa: float | str = theory.DISC) -> pl.DataFrame:
    """theta_c, the largest |omega_out| and e_kin,min of every curve of a sweep, refined between grid points.

    theta_c is where |omega_out| peaks: the kink at which the sliding branch (|omega| growing like
    sin theta) meets the rolling one (falling like cos theta), for every mu > 0. e_kin,min is
    located separately: at large mu it sits at the same kink; at small mu the sliding branch turns
    up before theta_c and the minimum is smooth and lies below theta_c (the study treats the two
    as one angle; we report both).

    Returns one row per curve: the group's axes, ``theta_c``, ``omega_out_max`` (signed value at
    the peak of |omega_out|), ``theta_e_kin_min``, ``e_kin_min``, ``e_n_at_theta_c`` (interpolated),
    ``theta_c_theory`` (rigid body with that e_N and the curve's omega_in), and the locating
    methods. Curves whose extremum is at the end of the grid, and mu = 0, give nulls.
    """
    rows = []
    for key, part in _curves(df):
        th = part["theta_deg"].to_numpy().astype(float)
        w = part["omega_out"].to_numpy().astype(float)
        ek = part["e_kin"].to_numpy().astype(float)
        en = part["e_n"].to_numpy().astype(float)
        row: dict[str, Any] = dict(key)
        if len(th) < 3:
            raise ValueError(f"require at least 3 theta values per curve (found {len(th)} for {key})")
        wmax = locate_max(th, np.abs(w), method)
        emin = locate_min(th, ek, method)
        mu = float(key.get("mu", np.nan))
        # Without friction there is no rolling regime: a polygon's tiny corner-induced spin has
        # peaks, but none of them is theta_c.
        interior_w = wmax.method != "edge" and wmax.y > 0.0 and mu != 0.0
        row["theta_c"] = wmax.x if interior_w else None
        row["omega_out_max"] = float(np.sign(w[wmax.index]) * wmax.y) if interior_w else None
        row["theta_c_method"] = wmax.method
        row["theta_e_kin_min"] = emin.x if emin.method != "edge" else None
        row["e_kin_min"] = emin.y if emin.method != "edge" else None
        row["e_kin_min_method"] = emin.method
        en_c = float(np.interp(wmax.x, th, en)) if interior_w else None
        row["e_n_at_theta_c"] = en_c
        if interior_w and np.isfinite(mu):
            rr = float(key.get("r", r if r is not None else theory.R_PAPER))
            vv = float(key.get("v", v if v is not None else theory.V_PAPER))
            om = float(key.get("omega_in", 0.0))
            row["theta_c_theory"] = float(theory.theta_c(mu, en_c, om, r=rr, v=vv, kappa=kappa))
        else:
            row["theta_c_theory"] = None
        rows.append(row)
    return pl.DataFrame(rows, infer_schema_length=None)


# --------------------------------------------------------------------------------------------
# a exp(-b x) + c with uncertainties (numpy only)
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ExpFit:
    """Least-squares fit of ``a exp(-b x) + c``.

    ``errors`` are standard errors (sqrt of the covariance diagonal). With ``sigma`` given and
    ``absolute_sigma=True`` they follow from the data errors alone; otherwise the covariance is
    scaled by chi2 / dof (as when the scatter about the fit is the only estimate of the noise,
    which is how a fit to a curve that is "not strictly exponential" gets its error bars).
    """

    a: float
    b: float
    c: float
    errors: tuple[float, float, float]
    cov: np.ndarray = field(repr=False)
    chi2: float
    dof: int
    n: int
    x_range: tuple[float, float] = (float("-inf"), float("inf"))
    """Smallest and largest x fitted (outside it the curve is an extrapolation)."""

    @property
    def params(self) -> tuple[float, float, float]:
        return (self.a, self.b, self.c)

    def __call__(self, x: Any) -> np.ndarray:
        return self.a * np.exp(-self.b * np.asarray(x, dtype=float)) + self.c

    def as_dict(self) -> dict[str, float]:
        ea, eb, ec = self.errors
        return {"a": self.a, "a_err": ea, "b": self.b, "b_err": eb, "c": self.c, "c_err": ec,
                "chi2": self.chi2, "dof": float(self.dof)}


def _exp_jac(p: np.ndarray, x: np.ndarray) -> np.ndarray:
    e = np.exp(-p[1] * x)
    return np.column_stack([e, -p[0] * x * e, np.ones_like(x)])


def _scan_b(bs: np.ndarray, x: np.ndarray, y: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, float]:
    """Variable projection: for each b, a and c enter linearly; solves the 2x2 weighted normal
    equations for all b at once and returns ([a, b, c], chi2) of the best b.

    The basis is exp(-b (x - x_ref)) with x_ref the end of the data where it is largest (1), so
    it never overflows; a is converted back at the end."""
    x_ref = np.where(bs >= 0, x.min(), x.max())
    E = np.exp(-bs[:, None] * (x[None, :] - x_ref[:, None])) * w[None, :]
    W = w[None, :]
    yw = (y * w)[None, :]
    s_ee, s_ew, s_ww = (E * E).sum(1), (E * W).sum(1), float((W * W).sum())
    s_ey, s_wy, s_yy = (E * yw).sum(1), float((W * yw).sum()), float((yw * yw).sum())
    det = s_ee * s_ww - s_ew**2
    ok = det > 1e-12 * s_ee * s_ww  # b -> 0 makes the two basis functions collinear
    with np.errstate(divide="ignore", invalid="ignore"):
        a_ = (s_ww * s_ey - s_ew * s_wy) / det
        c_ = (s_ee * s_wy - s_ew * s_ey) / det
        chi2 = s_yy - a_ * s_ey - c_ * s_wy
    chi2 = np.where(ok & np.isfinite(chi2), chi2, np.inf)
    k = int(np.argmin(chi2))
    with np.errstate(over="ignore"):
        a = a_[k] * np.exp(bs[k] * x_ref[k])
    return np.array([a, bs[k], c_[k]]), float(chi2[k])


def fit_exp(x: Any, y: Any, sigma: Any = None, *, absolute_sigma: bool | None = None) -> ExpFit:
    """Fits ``y = a exp(-b x) + c`` by least squares (weights 1/sigma^2) and returns values,
    standard errors and covariance.

    The model is linear in a and c, so b is first found by scanning the reduced problem
    (variable projection) on a log grid of ``|b| (max x - min x)`` from 1e-3 to 60 (both signs:
    a rising exponential is allowed), then all three are polished by
    Levenberg-Marquardt; the covariance is ``(J^T W J)^-1`` at the optimum, scaled by
    chi2 / dof unless ``absolute_sigma`` (default: True when ``sigma`` is given).

    Examples
    --------
    >>> x = np.linspace(0.1, 1.0, 10)
    >>> f = fit_exp(x, 73.45 * np.exp(-5.44 * x) + 16.26)
    >>> [round(p, 6) for p in f.params]
    [73.45, 5.44, 16.26]
    """
    xa = np.asarray(x, dtype=float).ravel()
    ya = np.asarray(y, dtype=float).ravel()
    if xa.shape != ya.shape:
        raise ValueError(f"require `x` and `y` of equal length (found {xa.size} and {ya.size})")
    if xa.size < 4:
        raise ValueError(f"require at least 4 points for 3 parameters and an error estimate (found {xa.size})")
    if not (np.all(np.isfinite(xa)) and np.all(np.isfinite(ya))):
        raise ValueError("require `x` and `y` finite")
    if sigma is None:
        sa = np.ones_like(xa)
        absolute = False if absolute_sigma is None else bool(absolute_sigma)
        if absolute:
            raise ValueError("`absolute_sigma=True` needs `sigma`")
    else:
        sa = np.broadcast_to(np.asarray(sigma, dtype=float), xa.shape).copy()
        if not np.all(sa > 0) or not np.all(np.isfinite(sa)):
            raise ValueError("require `sigma` finite and > 0")
        absolute = True if absolute_sigma is None else bool(absolute_sigma)
    w = 1.0 / sa
    span = float(xa.max() - xa.min())
    if span <= 0.0:
        raise ValueError("require at least two distinct `x` values")
    grid = np.geomspace(1e-3, 60.0, 300) / span
    p, chi2 = _scan_b(np.concatenate([-grid[::-1], grid]), xa, ya, w)
    p, chi2 = _levenberg_marquardt(p, xa, ya, w)
    J = _exp_jac(p, xa) * w[:, None]
    dof = xa.size - 3
    try:
        cov = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((3, 3), np.inf)
    if not absolute:
        cov = cov * (chi2 / dof)
    err = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    return ExpFit(float(p[0]), float(p[1]), float(p[2]), (float(err[0]), float(err[1]), float(err[2])), cov,
                  float(chi2), dof, int(xa.size), (float(xa.min()), float(xa.max())))


def _levenberg_marquardt(p: np.ndarray, x: np.ndarray, y: np.ndarray, w: np.ndarray,
                         max_iter: int = 200) -> tuple[np.ndarray, float]:
    def chi2_of(q: np.ndarray) -> float:
        with np.errstate(over="ignore", invalid="ignore"):
            r = (q[0] * np.exp(-q[1] * x) + q[2] - y) * w
        return float(r @ r) if np.all(np.isfinite(r)) else np.inf

    lam = 1e-3
    c2 = chi2_of(p)
    for _ in range(max_iter):
        r = (y - (p[0] * np.exp(-p[1] * x) + p[2])) * w
        J = _exp_jac(p, x) * w[:, None]
        A = J.T @ J
        g = J.T @ r
        improved = False
        for _ in range(30):
            try:
                step = np.linalg.solve(A + lam * np.diag(np.maximum(np.diag(A), 1e-300)), g)
            except np.linalg.LinAlgError:
                lam *= 10.0
                continue
            q = p + step
            c2q = chi2_of(q)
            if np.isfinite(c2q) and c2q <= c2:
                improved = True
                done = c2 - c2q <= 1e-15 * max(c2, 1e-300) or np.all(np.abs(step) <= 1e-13 * (np.abs(p) + 1e-300))
                p, c2 = q, c2q
                lam = max(lam / 10.0, 1e-12)
                break
            lam *= 10.0
        if not improved or done:
            break
    return p, c2


def compare(ours: tuple[float, float], theirs: tuple[float, float], n_sigma: float = 2.0) -> tuple[float, bool]:
    """Distance between two values with standard errors, in combined sigmas, and whether it
    exceeds ``n_sigma``.

    >>> compare((1.0, 0.1), (1.5, 0.2))[1]
    True
    """
    s = float(np.hypot(ours[1], theirs[1]))
    d = abs(ours[0] - theirs[0]) / s if s > 0 else (np.inf if ours[0] != theirs[0] else 0.0)
    return d, bool(d > n_sigma)


# --------------------------------------------------------------------------------------------
# Rolling regime: micro-slip oscillations; sliding regime: the study's Eq. 2
# --------------------------------------------------------------------------------------------


def _theory_columns(df: pl.DataFrame, r: float | None, v: float | None, kappa: float | str) -> dict[str, np.ndarray]:
    n = df.height
    col = lambda name, default: (df[name].to_numpy().astype(float) if name in df.columns  # noqa: E731
                                 else np.full(n, default, dtype=float))
    return {
        "theta": col("theta_deg", np.nan), "mu": col("mu", np.nan), "e_n": df["e_n"].to_numpy().astype(float),
        "omega_in": col("omega_in", 0.0),
        "r": col("r", r if r is not None else theory.R_PAPER), "v": col("v", v if v is not None else theory.V_PAPER),
    }


def _rowwise(fn, t: dict[str, np.ndarray], kappa: float | str, **extra) -> np.ndarray:
    """Applies a theory function row by row where r and v differ between rows (they are scalars there)."""
    out = np.empty(len(t["theta"]))
    for (rr, vv) in {(a, b) for a, b in zip(t["r"], t["v"])}:
        m = (t["r"] == rr) & (t["v"] == vv)
        out[m] = fn(t["theta"][m], r=rr, v=vv, kappa=kappa, m=m, **extra)
    return out


def with_theory(df: pl.DataFrame, *, r: float | None = None, v: float | None = None,
                kappa: float | str = theory.DISC) -> pl.DataFrame:
    """The frame with rigid-body columns added, each computed with the row's measured e_N:
    ``e_t_theory``, ``e_kin_theory``, ``omega_out_theory``, ``theta_c_theory`` and ``sliding``
    (the theory's regime). ``mu``, ``omega_in``, ``r`` and ``v`` come from the frame's columns
    where present, else from the arguments (default: the paper preset)."""
    if "mu" not in df.columns:
        raise ValueError("`with_theory` needs a `mu` column (sweep over mu, even a single value)")
    t = _theory_columns(df, r, v, kappa)
    res = {}
    for name, fn in (("e_t_theory", theory.e_t), ("e_kin_theory", theory.e_kin),
                     ("omega_out_theory", theory.omega_out), ("sliding", theory.slides)):
        res[name] = _rowwise(lambda th, r, v, kappa, m, fn=fn: fn(th, t["mu"][m], t["e_n"][m], t["omega_in"][m],
                                                                  r=r, v=v, kappa=kappa), t, kappa)
    res["theta_c_theory"] = _rowwise(lambda th, r, v, kappa, m: theory.theta_c(t["mu"][m], t["e_n"][m], t["omega_in"][m],
                                                                               r=r, v=v, kappa=kappa), t, kappa)
    e_t_theory = np.where(np.isfinite(res["e_t_theory"]), res["e_t_theory"], np.nan)
    return df.with_columns(
        pl.Series("e_t_theory", e_t_theory).fill_nan(None),
        pl.Series("e_kin_theory", res["e_kin_theory"]),
        pl.Series("omega_out_theory", res["omega_out_theory"]),
        pl.Series("theta_c_theory", res["theta_c_theory"]).fill_nan(None),
        pl.Series("sliding", res["sliding"].astype(bool)),
    )


def sondergaard_residuals(df: pl.DataFrame, *, r: float | None = None, v: float | None = None) -> pl.DataFrame:
    """The frame with ``e_t_sondergaard`` = 1 - s mu (1 + e_N) tan(theta) (the study's Eq. 2 with
    the row's measured e_N; s = sign(v_T + r omega_in), so it also holds with spin),
    ``e_t_residual`` = e_t - e_t_sondergaard, and ``sliding`` (rigid-body regime).

    Eq. 2 is meant for the sliding regime; in the rolling regime the residual grows without
    bound as the formula falls to very low and negative values (the study's remark).
    """
    if "mu" not in df.columns:
        raise ValueError("`sondergaard_residuals` needs a `mu` column")
    t = _theory_columns(df, r, v, theory.DISC)
    es = _rowwise(lambda th, r, v, kappa, m: theory.e_t_sliding(th, t["mu"][m], t["e_n"][m], t["omega_in"][m], r=r, v=v),
                  t, theory.DISC)
    sl = _rowwise(lambda th, r, v, kappa, m: theory.slides(th, t["mu"][m], t["e_n"][m], t["omega_in"][m], r=r, v=v,
                                                           kappa=kappa), t, theory.DISC)
    es_s = pl.Series("e_t_sondergaard", es).fill_nan(None)
    return df.with_columns(es_s, pl.Series("sliding", sl.astype(bool))).with_columns(
        (pl.col("e_t") - pl.col("e_t_sondergaard")).alias("e_t_residual"))


def micro_slip(df: pl.DataFrame, *, margin_deg: float = 3.0, theta_max: float = 89.0, r: float | None = None,
               v: float | None = None, kappa: float | str = theory.DISC) -> pl.DataFrame:
    """Micro-slip oscillation of e_T in the rolling regime, per curve.

    Rows with theta >= theta_c(theory) + ``margin_deg`` and theta <= ``theta_max`` are compared
    with the rigid-body rolling value e_R = 1/(1+kappa) - kappa r omega_in / ((1+kappa) v_T)
    (2/3 without spin). Returns per curve: ``n``, ``e_t_mean``, ``rel_min`` and ``rel_max``
    (smallest and largest e_t / e_R - 1), ``amplitude`` = (rel_max - rel_min) / 2 and
    ``rel_std`` (standard deviation of e_t / e_R - 1). The margin skips the rounded corner at
    theta_c, where a soft contact is still partly sliding.
    """
    wt = with_theory(df, r=r, v=v, kappa=kappa)
    t = _theory_columns(df, r, v, kappa)
    e_roll = _rowwise(lambda th, r, v, kappa, m: theory.e_t_rolling(th, t["omega_in"][m], r=r, v=v, kappa=kappa),
                      t, kappa)
    wt = wt.with_columns(pl.Series("_e_roll", e_roll))
    sel = wt.filter(pl.col("theta_c_theory").is_not_null()
                    & (pl.col("theta_deg") >= pl.col("theta_c_theory") + margin_deg)
                    & (pl.col("theta_deg") <= theta_max) & pl.col("e_t").is_not_null())
    keys = group_columns(df)
    rel = (pl.col("e_t") / pl.col("_e_roll") - 1.0)
    aggs = [pl.len().alias("n"), pl.col("e_t").mean().alias("e_t_mean"), rel.min().alias("rel_min"),
            rel.max().alias("rel_max"), rel.std().alias("rel_std")]
    out = (sel.group_by(keys, maintain_order=True).agg(aggs) if keys else sel.select(aggs))
    return out.with_columns(((pl.col("rel_max") - pl.col("rel_min")) / 2).alias("amplitude"))


__all__ = ["ExpFit", "Extremum", "axis_columns", "compare", "critical_angles", "fit_exp", "group_columns",
           "locate_max", "locate_min", "micro_slip", "sondergaard_residuals", "with_theory"]
