"""Ensemble distributions: each draws its own law (Kolmogorov-Smirnov against the analytic CDF,
moments of the truncated normal in closed form), exactly within its truncation, and the same
draw j whatever is drawn with it; bad parameters are refused naming them."""

from __future__ import annotations

import math

import numpy as np
import pytest

import restitution as rs
from restitution.runs.distributions import BLOCK, from_dict, normal_ppf, stratified

N = 20_000
#: Kolmogorov-Smirnov: P(sqrt(n) D > 1.95) = 0.001 for a sample of the law itself.
KS_CRITICAL = 1.95 / math.sqrt(N)


def ks_statistic(x: np.ndarray, cdf) -> float:
    x = np.sort(x)
    f = np.asarray(cdf(x), dtype=float)
    i = np.arange(1, x.size + 1)
    return float(max(np.max(i / x.size - f), np.max(f - (i - 1) / x.size)))


def phi(z: float) -> float:
    return 0.5 * math.erfc(-z / math.sqrt(2.0))


def pdf(z: float) -> float:
    return math.exp(-z * z / 2.0) / math.sqrt(2.0 * math.pi)


@pytest.mark.parametrize("dist", [
    rs.Uniform(-2.0, 3.0),
    rs.Normal(0.5, 0.2),
    rs.Normal(0.5, 0.2, lo=0.4),
    rs.Normal(0.0, 1.0, lo=-0.5, hi=2.0),
    rs.Normal(0.0, 1.0, lo=6.0),                       # far in the upper tail: drawn from its mirror image
    rs.LogNormal(math.log(0.5), 0.8),
    rs.LogNormal(0.0, 1.0, lo=0.3, hi=4.0),
], ids=repr)
def test_draws_follow_the_law(dist) -> None:
    x = dist.draw(seed=11, name="mu", start=0, stop=N)
    assert ks_statistic(x, dist.cdf) < KS_CRITICAL
    lo = getattr(dist, "lo", None)
    hi = getattr(dist, "hi", None)
    assert (lo is None or x.min() >= lo) and (hi is None or x.max() <= hi)


def test_the_truncated_normal_has_its_closed_form_moments() -> None:
    # mean = m + s (phi(a) - phi(b)) / Z, var = s^2 [1 + (a phi(a) - b phi(b)) / Z - ((phi(a) - phi(b)) / Z)^2]
    m, s, lo, hi = 0.3, 0.2, 0.1, 0.9
    a, b = (lo - m) / s, (hi - m) / s
    z = phi(b) - phi(a)
    mean = m + s * (pdf(a) - pdf(b)) / z
    var = s * s * (1.0 + (a * pdf(a) - b * pdf(b)) / z - ((pdf(a) - pdf(b)) / z) ** 2)
    x = rs.Normal(m, s, lo=lo, hi=hi).draw(seed=5, name="mu", start=0, stop=200_000)
    se = math.sqrt(var / x.size)
    assert abs(x.mean() - mean) < 4.0 * se, (x.mean(), mean, se)
    assert abs(x.var() / var - 1.0) < 4.0 * math.sqrt(2.0 / x.size)


def test_choice_frequencies_and_names() -> None:
    d = rs.Choice([3, 4, 6], p=[0.2, 0.3, 0.5])
    x = d.draw(seed=2, name="n", start=0, stop=N)
    counts = np.array([(x == k).sum() for k in (3, 4, 6)])
    expected = N * np.array([0.2, 0.3, 0.5])
    chi2 = float(((counts - expected) ** 2 / expected).sum())
    assert chi2 < 13.8  # chi^2 with 2 degrees of freedom: P(> 13.8) = 0.001
    names = rs.Choice(["gear5", "adaptive"]).draw(seed=2, name="integrator", start=0, stop=100)
    assert set(names.tolist()) == {"gear5", "adaptive"}


def test_a_draw_depends_on_seed_name_and_index_only() -> None:
    d = rs.LogNormal(0.0, 1.5)
    whole = d.draw(seed=7, name="v", start=0, stop=3 * BLOCK)
    j = np.array([5, BLOCK + 3, 2 * BLOCK + 1, 5, 0])
    assert np.array_equal(d.draw_at(7, "v", j), whole[j])  # bit for bit, across blocks, any order
    for start, stop in ((0, 1), (BLOCK - 2, BLOCK + 2), (17, 4000)):
        assert np.array_equal(d.draw(7, "v", start, stop), whole[start:stop])
    assert not np.array_equal(d.draw(8, "v", 0, 10), whole[:10])
    assert not np.array_equal(d.draw(7, "mu", 0, 10), whole[:10])


def test_the_inverse_normal_cdf_is_as241() -> None:
    from statistics import NormalDist

    u = np.array([1e-300, 1e-20, 1e-5, 0.02, 0.3, 0.5, 0.9, 0.975, 1.0 - 1e-12])
    assert np.array_equal(normal_ppf(u), [NormalDist().inv_cdf(float(p)) for p in u])


@pytest.mark.parametrize("make, parameter", [
    (lambda: rs.Uniform(1.0, 1.0), "Uniform.hi"),
    (lambda: rs.Normal(0.0, 0.0), "Normal.sd"),
    (lambda: rs.Normal(0.0, 1.0, lo=2.0, hi=1.0), "Normal.hi"),
    (lambda: rs.Normal(0.0, 1.0, lo=40.0, hi=41.0), "Normal.lo"),   # no probability left in [lo, hi]
    (lambda: rs.Normal(float("nan"), 1.0), "Normal.mean"),
    (lambda: rs.LogNormal(0.0, 1.0, lo=-1.0), "LogNormal.lo"),
    (lambda: rs.LogNormal(0.0, -1.0), "LogNormal.sd_log"),
    (lambda: rs.Choice([1, 2], p=[0.5, 0.6]), "Choice.p"),
    (lambda: rs.Choice([]), "Choice.values"),
    (lambda: rs.Choice([1, "a"]), "Choice.values"),
], ids=lambda x: x if isinstance(x, str) else "")
def test_bad_parameters_are_refused_by_name(make, parameter: str) -> None:
    with pytest.raises(rs.RestitutionError) as err:
        make()
    assert err.value.parameter == parameter


@pytest.mark.parametrize("make, parameter, value, quoted", [
    (lambda: rs.Normal(0.5, 0.1, lo=1, hi=0), "Normal.hi", 0.0, ["lo = 1.0", "mean=0.5", "sd=0.1"]),
    (lambda: rs.Normal(0.5, 0.1, lo=50, hi=60), "Normal.lo", 50.0, ["[50.0, 60.0]", "mean=0.5", "sd=0.1"]),
    (lambda: rs.Normal(0.5, 0.1, hi=-60), "Normal.lo", None, ["[None, -60.0]", "mean=0.5", "sd=0.1"]),
    (lambda: rs.LogNormal(0.0, 1.0, lo=5, hi=2), "LogNormal.hi", 2.0, ["lo = 5.0", "mean_log=0.0", "sd_log=1.0"]),
    (lambda: rs.LogNormal(0.0, 0.01, lo=1e30, hi=1e31), "LogNormal.lo", 1e30,
     ["[1e+30, 1e+31]", "mean_log=0.0", "sd_log=0.01"]),
], ids=["normal-empty", "normal-far", "normal-far-below", "lognormal-empty", "lognormal-far"])
def test_truncation_errors_quote_the_users_numbers(make, parameter: str, value: float | None,
                                                     quoted: list[str]) -> None:
    """Issue 42: the check runs on z-scores (logs for LogNormal), but the message must quote
    what the user wrote: ``Normal(0.5, 0.1, lo=1, hi=0)`` said "lo = 5.0 (found -5.0)"."""
    with pytest.raises(rs.RestitutionError) as err:
        make()
    assert err.value.parameter == parameter
    assert err.value.value == value
    for text in quoted:
        assert text in str(err.value), (text, str(err.value))


def test_dict_form_round_trips_and_names_bad_keys() -> None:
    for d in (rs.Uniform(0.0, 60.0), rs.Normal(0.5, 0.1, lo=0.0), rs.LogNormal(0.0, 0.5, hi=3.0),
              rs.Choice([3, 4], p=[0.25, 0.75])):
        assert from_dict(d.to_dict()) == d
    with pytest.raises(ValueError, match="vary.mu: unknown key `sigma`"):
        from_dict({"dist": "normal", "mean": 0.5, "sigma": 0.1}, "vary.mu")
    with pytest.raises(ValueError, match="`dist` one of"):
        from_dict({"dist": "beta"}, "vary.mu")


def test_stratified_draws_fill_every_stratum_and_their_mean_converges_faster() -> None:
    # Each of the n strata holds one draw, the marginal stays uniform (the draws of many seeds
    # pass Kolmogorov-Smirnov), and the mean of a smooth function over n stratified draws varies
    # across seeds far less than over independent ones (O(n^-3/2) against O(n^-1/2) in sd).
    n = 64
    u = stratified(3, "phi0_deg", n)
    assert sorted(np.floor(u * n).astype(int).tolist()) == list(range(n))
    pooled = np.concatenate([stratified(s, "phi0_deg", n) for s in range(300)])
    assert ks_statistic(pooled, lambda x: x) < 1.95 / math.sqrt(pooled.size)  # strata only make it more uniform
    d = rs.Normal(0.5, 0.2)
    strat = [d.draw_at(s, "mu", np.arange(n), strata=n).mean() for s in range(200)]
    iid = [d.draw_at(s, "mu", np.arange(n)).mean() for s in range(200)]
    assert np.std(strat) < 0.2 * np.std(iid), (np.std(strat), np.std(iid))
    assert np.array_equal(d.draw_at(3, "mu", np.array([5, 7]), strata=n), d.draw_at(3, "mu", np.arange(n), strata=n)[[5, 7]])
