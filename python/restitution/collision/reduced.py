"""Reduced collision models fitted to an operator's table, with what they cost.

Both act on a body of mass m, moment of inertia I = kappa m r^2 (kappa of the scene's shape),
whose contact point lies a distance r below its centre, through an impulse at that point
(docs/model.md, section 16.4). With u = v_t + r omega the contact point's slip:

**Walton's three-parameter model** (e, mu, beta_0):

    v_n' = -e v_n,
    u'   = -beta u,   beta = min(beta_0, -1 + mu (1 + e) (1 + 1/kappa) |v_n| / |u|),
    v_t' = v_t + D,   omega' = omega + D / (kappa r),   D = -(1 + beta) u / (1 + 1/kappa):

the contact point rebounds with tangential restitution beta_0 unless that needs more than
Coulomb's impulse mu (1 + e) m |v_n|, in which case it slides throughout.

**Constant coefficients** (e_N, e_T): v_n' = -e_N v_n, v_t' = e_T v_t and, from the same impulse
at the contact point, omega' = omega + (e_T - 1) v_t / (kappa r).

The fit: least squares on the operator's three dimensionless outputs (v_n' / |v|, v_t' / |v|,
omega' r / |v|), at unit speed, at points spread uniformly over the table's domain (theta,
spin, log v; not its nodes, which refinement crowds where the outcome bends). ``e`` (or e_N)
fits v_n' / |v| = e sin theta (linear); the tangential parameters minimise the other two outputs' squared errors
(mu, beta_0: a grid search then Levenberg-Marquardt; e_T: linear). Their standard errors
come from the fit's covariance scaled by chi^2 / dof, the misfit treated as noise: they say how
well the table fixes the parameters, not how good the model is; the ``error`` table (largest
and rms difference from the operator, per output) says that.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import polars as pl

from ..scene import Scene
from ..shapes import ConvexPolygon, Disc, RegularPolygon
from .table import AXES, OUTPUTS

#: Points per axis of the uniform fitting grid (theta, spin, v).
FIT_POINTS = (46, 31, 5)


def kappa_of(scene: Scene) -> float:
    """I / (m r^2) of the scene's particle, r its circumradius."""
    shape = scene.shape
    if isinstance(shape, RegularPolygon):
        return (1.0 + 2.0 * np.cos(np.pi / shape.n) ** 2) / 6.0
    if isinstance(shape, ConvexPolygon):
        v = shape._template  # unit circumradius about the centroid
        x, y = v[:, 0], v[:, 1]
        x1, y1 = np.roll(x, -1), np.roll(y, -1)
        cross = x * y1 - x1 * y
        area = cross.sum() / 2.0
        return float((cross * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)).sum() / 12.0 / area)
    if isinstance(shape, Disc) and scene.inertia == "shape":
        return 0.5
    return 0.4  # a sphere, or a disc with sphere inertia


@dataclass(frozen=True)
class ReducedModel:
    """A fitted reduced model: its parameters with standard errors, and its error against the
    operator it was fitted to. Callable like the operator, on SI arrays."""

    name: str
    """``"walton"`` or ``"constant"``."""
    params: dict[str, float]
    errors: dict[str, float | None]
    """Standard errors of the parameters (None where the table does not fix one)."""
    kappa: float
    r: float
    error: pl.DataFrame = field(repr=False)
    """Per output: largest and rms absolute difference from the operator's mean over the fitting
    points, beside the operator's own stated error."""

    def __call__(self, v_n: Any, v_t: Any, omega: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Post-collision (v_n', v_t', omega') (SI, the plate's convention, v_n < 0 approaching)."""
        vn, vt, om = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (v_n, v_t, omega)))
        if self.name == "walton":
            return _walton(self.params, vn, vt, om, self.kappa, self.r)
        return _constant(self.params, vn, vt, om, self.kappa, self.r)

    def summary(self) -> str:
        """One line: the parameters with their errors."""
        return ", ".join(f"{k} = {v:.4g}" + (f" +- {self.errors[k]:.2g}" if self.errors[k] is not None else "")
                         for k, v in self.params.items())


def _walton(p: dict[str, float], vn: np.ndarray, vt: np.ndarray, om: np.ndarray, kappa: float,
            r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    e, mu, beta0 = p["e"], p["mu"], p["beta_0"]
    u = vt + r * om
    with np.errstate(divide="ignore", invalid="ignore"):
        slide = -1.0 + mu * (1.0 + e) * (1.0 + 1.0 / kappa) * np.abs(vn) / np.abs(u)
    beta = np.where(u != 0.0, np.minimum(beta0, slide), beta0)
    d = -(1.0 + beta) * u / (1.0 + 1.0 / kappa)
    return -e * vn, vt + d, om + d / (kappa * r)


def _constant(p: dict[str, float], vn: np.ndarray, vt: np.ndarray, om: np.ndarray, kappa: float,
              r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    d = (p["e_t"] - 1.0) * vt
    return -p["e_n"] * vn, vt + d, om + d / (kappa * r)


def _fit_points(op: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Unit-speed states (v_n, v_t, omega r) over the domain and the operator's mean outputs there."""
    t = op.table
    axes = []
    for a, k in zip(AXES, FIT_POINTS):
        nodes = getattr(t, a)
        lo, hi = nodes[0], nodes[-1]
        axes.append(np.geomspace(lo, hi, k) if a == "v" and hi > lo else np.linspace(lo, hi, k) if hi > lo
                    else np.array([lo]))
    th, sp, v = (m.ravel() for m in np.meshgrid(*axes, indexing="ij"))
    target = t.mean_at(th, sp, v)
    rad = np.radians(th)
    return -np.sin(rad), np.where(th == 90.0, 0.0, np.cos(rad)), sp, target


def _outputs(model: ReducedModel, vn: np.ndarray, vt: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The model's dimensionless outputs at unit speed (r = 1: omega is omega r / |v|)."""
    m = ReducedModel(model.name, model.params, model.errors, model.kappa, 1.0, model.error)
    return np.column_stack(m(vn, vt, w))


def _error_table(op: Any, model: ReducedModel, pts: tuple[np.ndarray, ...]) -> pl.DataFrame:
    vn, vt, w, target = pts
    diff = np.abs(_outputs(model, vn, vt, w) - target)
    stated = dict(zip(op.error["output"].to_list(), op.error["max_abs"].to_list()))
    return pl.DataFrame({"output": list(OUTPUTS), "max_abs": diff.max(axis=0), "rms": np.sqrt((diff**2).mean(axis=0)),
                         "operator_max_abs": [stated.get(o) for o in OUTPUTS]})


def _e_fit(vn: np.ndarray, target: np.ndarray) -> tuple[float, float | None]:
    """Least squares of v_n' / |v| = e sin theta (sin theta = -v_n at unit speed), its standard error."""
    s, y = -vn, target[:, 0]
    e = float(s @ y / (s @ s))
    chi2 = float(((e * s - y) ** 2).sum())
    return e, float(np.sqrt(chi2 / (s.size - 1) / (s @ s))) if s.size > 1 else None


def fit_constant(op: Any) -> ReducedModel:
    """Constant (e_N, e_T) fitted to ``op``'s table (see the module doc)."""
    kappa, pts = kappa_of(op.scene), _fit_points(op)
    vn, vt, w, target = pts
    e_n, e_n_err = _e_fit(vn, target)
    a = np.concatenate([vt, vt / kappa])
    b = np.concatenate([target[:, 1], target[:, 2] - w + vt / kappa])
    saa = float(a @ a)
    e_t = float(a @ b) / saa if saa > 0 else 1.0
    chi2 = float(((a * e_t - b) ** 2).sum())
    e_t_err = float(np.sqrt(chi2 / max(a.size - 1, 1) / saa)) if saa > 0 else None
    model = ReducedModel("constant", {"e_n": e_n, "e_t": e_t}, {"e_n": e_n_err, "e_t": e_t_err}, kappa, op.scene.r,
                         pl.DataFrame())
    return ReducedModel(**{**model.__dict__, "error": _error_table(op, model, pts)})


def fit_walton(op: Any) -> ReducedModel:
    """Walton's (e, mu, beta_0) fitted to ``op``'s table (see the module doc)."""
    kappa, pts = kappa_of(op.scene), _fit_points(op)
    vn, vt, w, target = pts
    e, e_err = _e_fit(vn, target)

    def residuals(q: np.ndarray) -> np.ndarray:
        m = ReducedModel("walton", {"e": e, "mu": q[0], "beta_0": q[1]}, {}, kappa, 1.0, pl.DataFrame())
        return (_outputs(m, vn, vt, w)[:, 1:] - target[:, 1:]).ravel()

    grid = [(mu, b0) for mu in np.linspace(0.0, 2.0, 26) for b0 in np.linspace(-1.0, 1.0, 26)]
    q = np.array(min(grid, key=lambda g: float(np.sum(residuals(np.array(g)) ** 2))))
    q, chi2, jac = _levenberg_marquardt(residuals, q)
    errs: list[float | None] = [None, None]
    try:
        cov = np.linalg.inv(jac.T @ jac) * chi2 / max(jac.shape[0] - 2, 1)
        errs = [float(np.sqrt(c)) if np.isfinite(c) and c >= 0 else None for c in np.diag(cov)]
    except np.linalg.LinAlgError:
        pass  # e.g. mu = 0: no tangential impulse, beta_0 does not enter
    model = ReducedModel("walton", {"e": e, "mu": float(q[0]), "beta_0": float(q[1])},
                         {"e": e_err, "mu": errs[0], "beta_0": errs[1]}, kappa, op.scene.r, pl.DataFrame())
    return ReducedModel(**{**model.__dict__, "error": _error_table(op, model, pts)})


def _levenberg_marquardt(residuals: Any, q: np.ndarray, max_iter: int = 100) -> tuple[np.ndarray, float, np.ndarray]:
    """Minimises |residuals(q)|^2 over mu >= 0, beta_0 in [-1, 1]; (q, chi2, Jacobian at q)."""
    lo, hi = np.array([0.0, -1.0]), np.array([np.inf, 1.0])

    def jacobian(q: np.ndarray) -> np.ndarray:
        cols = []
        for k in range(2):
            h = 1e-6 * max(1.0, abs(q[k]))
            qp, qm = q.copy(), q.copy()
            qp[k], qm[k] = min(q[k] + h, hi[k]), max(q[k] - h, lo[k])
            cols.append((residuals(qp) - residuals(qm)) / (qp[k] - qm[k]))
        return np.column_stack(cols)

    lam, r = 1e-3, residuals(q)
    chi2 = float(r @ r)
    for _ in range(max_iter):
        jac = jacobian(q)
        a, g = jac.T @ jac, jac.T @ r
        step = np.linalg.lstsq(a + lam * np.diag(np.diag(a) + 1e-12), -g, rcond=None)[0]
        trial = np.clip(q + step, lo, hi)
        r_trial = residuals(trial)
        c_trial = float(r_trial @ r_trial)
        if c_trial < chi2:
            converged = chi2 - c_trial <= 1e-12 * chi2
            q, r, chi2, lam = trial, r_trial, c_trial, lam / 3.0
            if converged:
                break
        else:
            lam *= 4.0
            if lam > 1e10:
                break
    return q, chi2, jacobian(q)


__all__ = ["ReducedModel", "fit_constant", "fit_walton", "kappa_of"]
