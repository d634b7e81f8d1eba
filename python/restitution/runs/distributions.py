"""Distributions of what a scene leaves open, drawn reproducibly from a seed.

Each distribution is drawn by its inverse CDF from one uniform number per draw, and the
uniforms of draw ``j`` of parameter ``name`` depend only on ``(seed, name, j)``: they come
from fixed blocks of :data:`BLOCK` draws, block ``b`` seeded by ``SeedSequence(seed,
spawn_key=(crc32(name), b))``. So a draw's value does not depend on the chunk size, the thread
count, the machine, which other parameters vary, or the order in which the draws are made; and
a truncated distribution is exact (the uniform is mapped into ``[F(lo), F(hi)]``), never
rejection-sampled.

Examples
--------
>>> import restitution as rs
>>> d = rs.Normal(0.5, 0.1, lo=0.0)
>>> x = d.draw(seed=1, name="mu", start=0, stop=5)
>>> bool((x >= 0.0).all()), x.shape
(True, (5,))
>>> bool((d.draw(1, "mu", 3, 5) == x[3:]).all())     # draw j is the same whatever is drawn with it
True
"""

from __future__ import annotations

import abc
import functools
import math
import numbers
import zlib
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..errors import RestitutionError

#: Draws per seeded block of uniforms (a constant of the format: changing it changes every draw).
BLOCK = 4096
_TWO53 = float(2**53)


def uniforms(seed: int, name: str, start: int, stop: int) -> np.ndarray:
    """Uniform numbers in (0, 1) for draws ``start:stop`` of parameter ``name`` (53 random bits
    each, offset by half a unit so that neither end is reached: every inverse CDF is finite)."""
    return uniforms_at(seed, name, np.arange(start, stop, dtype=np.int64))


def uniforms_at(seed: int, name: str, j: np.ndarray) -> np.ndarray:
    """Uniform numbers in (0, 1) for the draws ``j`` (any order, repeats allowed)."""
    return _by_block(np.asarray(j, dtype=np.int64), lambda b: _block(seed, name, b))


def _block(seed: int, name: str, b: int) -> np.ndarray:
    """The uniforms of block ``b``: draws ``b * BLOCK`` to ``(b + 1) * BLOCK`` of ``name``."""
    key = zlib.crc32(name.encode())
    gen = np.random.Generator(np.random.Philox(np.random.SeedSequence(seed, spawn_key=(key, b))))
    return (gen.integers(0, 2**53, size=BLOCK, dtype=np.int64) + 0.5) / _TWO53


def _by_block(j: np.ndarray, block: Any) -> np.ndarray:
    """Values of the draws ``j``, computed a whole block at a time by ``block(b)``.

    Whole blocks, always: numpy's vectorised exp and log may round the last bit differently
    at different positions of an array (SIMD body or tail), so a draw computed inside a chunk
    of another size could differ by an ulp. Computed in its block, a draw's bits depend on the
    seed, the name and j alone.
    """
    if j.size and j.min() < 0:
        raise ValueError(f"require draw numbers >= 0 (found {j.min()})")
    blocks, which = np.unique(j // BLOCK, return_inverse=True)
    table = np.stack([block(int(b)) for b in blocks]) if blocks.size else np.empty((0, BLOCK))
    return table[which.reshape(j.shape), j % BLOCK]


@functools.lru_cache(maxsize=32)
def _permutation(seed: int, name: str, n: int) -> np.ndarray:
    """The strata of draws 0 ... n - 1 of ``name``: a permutation of 0 ... n - 1 (read-only)."""
    gen = np.random.Generator(np.random.Philox(np.random.SeedSequence(seed, spawn_key=(zlib.crc32(name.encode()),
                                                                                       2**32 - 1, n))))
    perm = gen.permutation(n)
    perm.flags.writeable = False
    return perm


def stratified(seed: int, name: str, n: int) -> np.ndarray:
    """The uniforms of ``n`` stratified draws (Latin hypercube across parameters): draw j's
    uniform is (k_j + u_j) / n, with k a seeded permutation of 0 ... n - 1 and u_j the draw's
    own uniform, so each of the n equal strata of (0, 1) holds exactly one draw of each
    parameter. Each draw is still uniform; a mean over the n draws errs as O(1 / n) for a smooth
    function of one parameter (O(1 / sqrt(n)) for independent draws).

    Examples
    --------
    >>> u = stratified(1, "phi0_deg", 8)
    >>> sorted((u * 8).astype(int).tolist())
    [0, 1, 2, 3, 4, 5, 6, 7]
    """
    return Uniform(0.0, 1.0).draw_at(seed, name, np.arange(n), strata=n)


def check_seed(seed: Any) -> int:
    """A seed: an integer in [0, 2^63)."""
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= int(seed) < 2**63:
        raise RestitutionError("seed", repr(seed), "an integer in [0, 2^63)")
    return int(seed)


def normal_ppf(p: np.ndarray) -> np.ndarray:
    """The standard normal's inverse CDF, vectorised: Wichura's AS241 (PPND16, relative error
    about 1e-16), the algorithm of Python's ``statistics.NormalDist.inv_cdf``."""
    p = np.asarray(p, dtype=np.float64)
    q = p - 0.5
    out = np.empty_like(p)
    central = np.abs(q) <= 0.425
    qc = q[central]
    r = 0.180625 - qc * qc
    num = (((((((2.5090809287301226727e3 * r + 3.3430575583588128105e4) * r + 6.7265770927008700853e4) * r
                + 4.5921953931549871457e4) * r + 1.3731693765509461125e4) * r + 1.9715909503065514427e3) * r
            + 1.3314166789178437745e2) * r + 3.3871328727963666080e0) * qc
    den = (((((((5.2264952788528545610e3 * r + 2.8729085735721942674e4) * r + 3.9307895800092710610e4) * r
                + 2.1213794301586595867e4) * r + 5.3941960214247511077e3) * r + 6.8718700749205790830e2) * r
            + 4.2313330701600911252e1) * r + 1.0)
    out[central] = num / den
    tail = ~central
    qt = q[tail]
    r = np.sqrt(-np.log(np.where(qt <= 0.0, p[tail], 1.0 - p[tail])))
    near = r <= 5.0
    a = r - 1.6
    num1 = (((((((7.74545014278341407640e-4 * a + 2.27238449892691845833e-2) * a + 2.41780725177450611770e-1) * a
                 + 1.27045825245236838258e0) * a + 3.64784832476320460504e0) * a + 5.76949722146069140550e0) * a
             + 4.63033784615654529590e0) * a + 1.42343711074968357734e0)
    den1 = (((((((1.05075007164441684324e-9 * a + 5.47593808499534494600e-4) * a + 1.51986665636164571966e-2) * a
                 + 1.48103976427480074590e-1) * a + 6.89767334985100004550e-1) * a + 1.67638483018380384940e0) * a
             + 2.05319162663775882187e0) * a + 1.0)
    b = r - 5.0
    num2 = (((((((2.01033439929228813265e-7 * b + 2.71155556874348757815e-5) * b + 1.24266094738807843860e-3) * b
                 + 2.65321895265761230930e-2) * b + 2.96560571828504891230e-1) * b + 1.78482653991729133580e0) * b
             + 5.46378491116411436990e0) * b + 6.65790464350110377720e0)
    den2 = (((((((2.04426310338993978564e-15 * b + 1.42151175831644588870e-7) * b + 1.84631831751005468180e-5) * b
                 + 7.86869131145613259100e-4) * b + 1.48753612908506148525e-2) * b + 1.36929880922735805310e-1) * b
             + 5.99832206555887937690e-1) * b + 1.0)
    x = np.where(near, num1 / den1, num2 / den2)
    out[tail] = np.where(qt < 0.0, -x, x)
    return out


def normal_cdf(x: float) -> float:
    """The standard normal's CDF at one point, accurate in the lower tail (through erfc)."""
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def _finite(owner: str, name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(float(value)):
        raise RestitutionError(f"{owner}.{name}", repr(value), "a finite number")
    return float(value)


def _bound(owner: str, name: str, value: Any) -> float | None:
    return None if value is None else _finite(owner, name, value)


class Distribution(abc.ABC):
    """What every distribution offers: draws from a seed, its CDF and inverse CDF, a dict form."""

    kind: ClassVar[str]

    @abc.abstractmethod
    def ppf(self, u: np.ndarray) -> np.ndarray:
        """The inverse CDF at ``u`` in (0, 1) (truncation included)."""

    @abc.abstractmethod
    def cdf(self, x: np.ndarray) -> np.ndarray:
        """The CDF at ``x`` (truncation included)."""

    def logpdf(self, x: np.ndarray) -> np.ndarray:
        """The log density at ``x`` (truncation included; -inf outside the support): the prior
        of a calibration (:func:`restitution.calibrate.fit`)."""
        raise RestitutionError("prior", self.kind, "a continuous distribution (Uniform, Normal or LogNormal)")

    def draw(self, seed: int, name: str, start: int, stop: int) -> np.ndarray:
        """Draws ``start:stop`` of parameter ``name`` from ``seed`` (see the module doc)."""
        return self.draw_at(seed, name, np.arange(start, stop, dtype=np.int64))

    def draw_at(self, seed: int, name: str, j: np.ndarray, *, strata: int | None = None) -> np.ndarray:
        """The draws numbered ``j`` of parameter ``name`` from ``seed`` (bit for bit the same
        whatever else is drawn with them). With ``strata`` = n, draws 0 ... n - 1 are stratified
        (see :func:`stratified`)."""
        seed = check_seed(seed)
        perm = _permutation(seed, name, strata) if strata else None

        def block(b: int) -> np.ndarray:
            u = _block(seed, name, b)
            if perm is not None:
                k = np.arange(b * BLOCK, (b + 1) * BLOCK)
                inside = k < len(perm)
                u = np.where(inside, (perm[np.minimum(k, len(perm) - 1)] + u) / len(perm), u)
            return self.ppf(u)

        return _by_block(np.asarray(j, dtype=np.int64), block)

    def to_dict(self) -> dict[str, Any]:
        """The TOML / manifest form: ``{"dist": kind, <parameters>}`` (unset bounds left out)."""
        out: dict[str, Any] = {"dist": self.kind}
        for k, v in vars(self).items():
            if not k.startswith("_") and v is not None:
                out[k] = list(v) if isinstance(v, tuple) else v
        return out


def _normal_window(owner: str, law: str, lo: float | None, hi: float | None, a: float,
                   b: float) -> tuple[float, float, bool]:
    """(Phi(a), Phi(b), flip) of the standard normal truncated to z in [a, b], the user's
    ``[lo, hi]`` as z-scores; refuses an empty or massless truncation quoting ``lo``, ``hi`` and
    ``law`` (the user's numbers, not the z-scores or logs they become)."""
    if lo is not None and hi is not None and not lo < hi:
        raise RestitutionError(f"{owner}.hi", hi, f"> lo = {lo} of {law}")
    # Far in the upper tail Phi(a) rounds to 1: draw from the mirror image [-b, -a] there,
    # where Phi keeps its relative precision, and negate.
    flip = a > 0.0
    if flip:
        a, b = -b, -a
    f_lo, f_hi = normal_cdf(a), normal_cdf(b)
    if not f_hi - f_lo > 1e-300:
        raise RestitutionError(f"{owner}.lo", lo, f"a truncation [lo, hi] = [{lo}, {hi}] holding some "
                               f"probability of {law} (its probability under that law is below 1e-300)")
    return f_lo, f_hi, flip


@dataclass(frozen=True)
class Uniform(Distribution):
    """Uniform on ``[lo, hi)``.

    Examples
    --------
    >>> Uniform(0.0, 60.0).ppf(np.array([0.25])).tolist()
    [15.0]
    """

    lo: float
    hi: float
    kind: ClassVar[str] = "uniform"

    def __post_init__(self) -> None:
        lo, hi = _finite("Uniform", "lo", self.lo), _finite("Uniform", "hi", self.hi)
        if not lo < hi:
            raise RestitutionError("Uniform.hi", hi, f"> lo = {lo}")
        object.__setattr__(self, "lo", lo)
        object.__setattr__(self, "hi", hi)

    def ppf(self, u: np.ndarray) -> np.ndarray:
        return self.lo + np.asarray(u) * (self.hi - self.lo)

    def cdf(self, x: np.ndarray) -> np.ndarray:
        return np.clip((np.asarray(x, dtype=float) - self.lo) / (self.hi - self.lo), 0.0, 1.0)

    def logpdf(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        return np.where((x >= self.lo) & (x <= self.hi), -math.log(self.hi - self.lo), -np.inf)


@dataclass(frozen=True)
class Normal(Distribution):
    """Normal with ``mean`` and ``sd``, optionally truncated to ``[lo, hi]`` (exactly: the
    inverse CDF of the truncated law, not rejection).

    Examples
    --------
    >>> x = Normal(0.5, 0.5, lo=0.0).draw(seed=3, name="mu", start=0, stop=10000)
    >>> bool(x.min() >= 0.0), round(float(x.mean()), 3)   # the truncated law's: 0.5 + 0.5 phi(1) / Phi(1) = 0.644
    (True, 0.644)
    """

    mean: float
    sd: float
    lo: float | None = None
    hi: float | None = None
    kind: ClassVar[str] = "normal"
    _f: tuple[float, float, bool] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        mean, sd = _finite("Normal", "mean", self.mean), _finite("Normal", "sd", self.sd)
        if not sd > 0.0:
            raise RestitutionError("Normal.sd", sd, "> 0")
        lo, hi = _bound("Normal", "lo", self.lo), _bound("Normal", "hi", self.hi)
        for k, v in (("mean", mean), ("sd", sd), ("lo", lo), ("hi", hi)):
            object.__setattr__(self, k, v)
        a = -math.inf if lo is None else (lo - mean) / sd
        b = math.inf if hi is None else (hi - mean) / sd
        window = _normal_window("Normal", f"Normal(mean={mean}, sd={sd})", lo, hi, a, b)
        object.__setattr__(self, "_f", window)

    def ppf(self, u: np.ndarray) -> np.ndarray:
        f_lo, f_hi, flip = self._f
        z = normal_ppf(f_lo + np.asarray(u) * (f_hi - f_lo))
        x = self.mean + (-z if flip else z) * self.sd
        return np.clip(x, self.lo if self.lo is not None else -np.inf, self.hi if self.hi is not None else np.inf)

    def cdf(self, x: np.ndarray) -> np.ndarray:
        f_lo, f_hi, flip = self._f
        z = (np.asarray(x, dtype=float) - self.mean) / self.sd
        phi = np.vectorize(normal_cdf)(-z if flip else z)
        c = np.clip((phi - f_lo) / (f_hi - f_lo), 0.0, 1.0)
        return 1.0 - c if flip else c

    def logpdf(self, x: np.ndarray) -> np.ndarray:
        f_lo, f_hi, _ = self._f  # the mass kept by the truncation is f_hi - f_lo, mirrored or not
        x = np.asarray(x, dtype=float)
        z = (x - self.mean) / self.sd
        inside = (x >= (-np.inf if self.lo is None else self.lo)) & (x <= (np.inf if self.hi is None else self.hi))
        dens = -0.5 * z * z - math.log(self.sd) - 0.5 * math.log(2.0 * math.pi) - math.log(f_hi - f_lo)
        return np.where(inside, dens, -np.inf)


@dataclass(frozen=True)
class LogNormal(Distribution):
    """``exp(N(mean_log, sd_log))``, optionally truncated to ``[lo, hi]`` (``lo`` >= 0): the
    median is ``exp(mean_log)``.

    Examples
    --------
    >>> round(float(LogNormal(0.0, 0.5).ppf(np.array([0.5]))[0]), 12)    # the median
    1.0
    """

    mean_log: float
    sd_log: float
    lo: float | None = None
    hi: float | None = None
    kind: ClassVar[str] = "lognormal"
    _normal: Normal = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        lo, hi = _bound("LogNormal", "lo", self.lo), _bound("LogNormal", "hi", self.hi)
        if lo is not None and lo < 0.0:
            raise RestitutionError("LogNormal.lo", lo, ">= 0 (the law lives on x > 0)")
        if hi is not None and hi <= 0.0:
            raise RestitutionError("LogNormal.hi", hi, "> 0 (the law lives on x > 0)")
        mean_log, sd_log = _finite("LogNormal", "mean_log", self.mean_log), _finite("LogNormal", "sd_log", self.sd_log)
        if not sd_log > 0.0:
            raise RestitutionError("LogNormal.sd_log", sd_log, "> 0")
        law = f"LogNormal(mean_log={mean_log}, sd_log={sd_log})"
        log_lo, log_hi = None if not lo else math.log(lo), None if hi is None else math.log(hi)
        _normal_window("LogNormal", law, lo, hi, -math.inf if log_lo is None else (log_lo - mean_log) / sd_log,
                       math.inf if log_hi is None else (log_hi - mean_log) / sd_log)
        try:
            inner = Normal(mean_log, sd_log, log_lo, log_hi)
        except RestitutionError:  # lo < hi whose logs round to one number
            raise RestitutionError("LogNormal.hi", hi, f"> lo = {lo} by more than rounding, for {law}") from None
        object.__setattr__(self, "mean_log", inner.mean)
        object.__setattr__(self, "sd_log", inner.sd)
        object.__setattr__(self, "lo", lo)
        object.__setattr__(self, "hi", hi)
        object.__setattr__(self, "_normal", inner)

    def ppf(self, u: np.ndarray) -> np.ndarray:
        return np.exp(self._normal.ppf(u))

    def cdf(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return np.where(x > 0.0, self._normal.cdf(np.log(np.where(x > 0.0, x, 1.0))), 0.0)

    def logpdf(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        safe = np.where(x > 0.0, x, 1.0)
        return np.where(x > 0.0, self._normal.logpdf(np.log(safe)) - np.log(safe), -np.inf)


@dataclass(frozen=True)
class Choice(Distribution):
    """One of ``values`` with probabilities ``p`` (default: equal). Values are numbers, or the
    names of a choice parameter (``integrator``, ``normal_law``, ...).

    Examples
    --------
    >>> Choice([3, 4, 6], p=[0.5, 0.25, 0.25]).ppf(np.array([0.1, 0.6, 0.9])).tolist()
    [3, 4, 6]
    """

    values: tuple[Any, ...]
    p: tuple[float, ...] | None = None
    kind: ClassVar[str] = "choice"
    _cum: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        values = tuple(self.values.tolist() if isinstance(self.values, np.ndarray) else self.values)
        if not values:
            raise RestitutionError("Choice.values", "[]", "at least one value")
        if not (all(isinstance(v, str) for v in values)
                or all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in values)):
            raise RestitutionError("Choice.values", repr(values), "all numbers or all names")
        object.__setattr__(self, "values", tuple(v if isinstance(v, str) else v.item() if isinstance(v, np.generic)
                                                  else v for v in values))
        p = np.full(len(values), 1.0 / len(values)) if self.p is None else np.asarray(self.p, dtype=float)
        if p.shape != (len(values),) or not np.all(np.isfinite(p)) or np.any(p < 0) or abs(p.sum() - 1.0) > 1e-9:
            raise RestitutionError("Choice.p", repr(self.p), f"{len(values)} probabilities >= 0 summing to 1")
        if self.p is not None:
            object.__setattr__(self, "p", tuple(float(x) for x in p))
        cum = np.cumsum(p)
        cum[-1] = 1.0
        object.__setattr__(self, "_cum", cum)

    def index(self, u: np.ndarray) -> np.ndarray:
        """The index into ``values`` drawn by ``u``."""
        return np.minimum(np.searchsorted(self._cum, np.asarray(u), side="right"), len(self.values) - 1)

    def ppf(self, u: np.ndarray) -> np.ndarray:
        return np.asarray(self.values, dtype=object if isinstance(self.values[0], str) else None)[self.index(u)]

    def cdf(self, x: np.ndarray) -> np.ndarray:
        if isinstance(self.values[0], str):
            raise TypeError("a Choice of names has no CDF")
        x = np.asarray(x, dtype=float)
        vals = np.asarray(self.values, dtype=float)
        probs = np.diff(np.concatenate([[0.0], self._cum]))
        return (probs[None, :] * (vals[None, :] <= x.reshape(-1, 1))).sum(axis=1).reshape(x.shape)


#: The distributions by their ``dist`` name (TOML ``{ dist = "normal", mean = ..., sd = ... }``).
KINDS: dict[str, type[Distribution]] = {c.kind: c for c in (Uniform, Normal, LogNormal, Choice)}


def from_dict(d: Any, where: str = "distribution") -> Distribution:
    """A distribution from its dict form (``to_dict``); a bad key or value names ``where``."""
    if isinstance(d, Distribution):
        return d
    if not isinstance(d, dict) or d.get("dist") not in KINDS:
        raise ValueError(f"{where}: require a table with `dist` one of {', '.join(map(repr, KINDS))} (found {d!r:.80})")
    cls = KINDS[d["dist"]]
    args = {k: v for k, v in d.items() if k != "dist"}
    allowed = [f for f in cls.__dataclass_fields__ if not f.startswith("_")]  # type: ignore[attr-defined]
    unknown = [k for k in args if k not in allowed]
    if unknown:
        raise ValueError(f"{where}: unknown key `{unknown[0]}` for dist = {d['dist']!r}; allowed: {', '.join(allowed)}")
    try:
        return cls(**args)
    except TypeError as err:
        raise ValueError(f"{where}: {err}; keys of dist = {d['dist']!r}: {', '.join(allowed)}") from None


__all__ = ["BLOCK", "Choice", "Distribution", "LogNormal", "Normal", "Uniform", "from_dict", "stratified", "uniforms"]
