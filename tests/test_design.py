"""rs.calibrate.design: the chosen impacts are where the data inform the parameters, and they
beat evenly spread angles, by the criterion and in realised posteriors on synthetic data.

On the disc's sliding branch e_T = 1 - mu (1 + e_N) tan(theta): its sensitivity to mu grows
with the angle up to where rolling starts, beyond which e_T no longer depends on mu; head-on it
is undefined. So the design for mu belongs on the sliding branch, towards its end, never head-on.
"""

from __future__ import annotations


import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.calibrate import _forward

#: The linear law on the disc at the paper's step: cheap, and its e_N is 1 (no damping).
DISC = rs.Scene.paper(shape=rs.Disc(r=0.01), normal_law="linear")
MU = rs.Uniform(0.1, 0.3)
CANDIDATES = pl.DataFrame({"theta_deg": np.arange(5.0, 91.0, 5.0)})
#: k evenly spread candidate angles: 5, 35, 60 and 90 deg.
EVEN = CANDIDATES.filter(pl.col("theta_deg").is_in([5.0, 35.0, 60.0, 90.0]))
SIGMA = {"e_t": 0.02}


@pytest.fixture(scope="module")
def chosen() -> pl.DataFrame:
    return rs.calibrate.design(DISC, {"mu": MU}, CANDIDATES, k=4, quantities=["e_t"], sigma=SIGMA)



def test_mu_is_measured_on_the_sliding_branch(chosen):
    theta = chosen["theta_deg"].to_numpy()
    assert 90.0 not in theta
    # Each pick slides throughout for a good share of the prior (rigid-body theory, e_N = 1
    # here): from 1 at 25 deg to 0.34 at 45 deg and none from 60 deg on. The information there
    # is that share times (2 tan theta)^2, so the picks trade the one against the other, and
    # shun both the grazing angles (tan theta small) and the rolling branch.
    mus = np.linspace(MU.lo, MU.hi, 101)
    shares = [rs.theory.slides(np.full_like(mus, t), mus, 1.0, r=0.01, v=DISC.v).mean() for t in theta]
    assert min(shares) > 0.3 and 20.0 < theta.min() and theta.max() < 55.0, (theta, shares)
    assert chosen["pick"].to_list() == [1, 2, 3, 4]
    # Each pick narrows the expected posterior further.
    assert np.all(np.diff(chosen["sd_mu"].to_numpy()) < 0) and np.all(np.diff(chosen["eig"].to_numpy()) > 0)


def test_beats_evenly_spread_angles_as_expected_and_realised(chosen):
    even = rs.calibrate.design(DISC, {"mu": MU}, EVEN, k=4, quantities=["e_t"], sigma=SIGMA)
    assert chosen["sd_mu"][-1] < 0.8 * even["sd_mu"][-1], (chosen, even)
    # Realised: the posterior of mu on a fine grid (the prior is uniform) from synthetic data at
    # true values drawn from the prior, the same truths and noise for both designs.
    rng = np.random.default_rng(11)
    truths = MU.ppf(rng.uniform(size=24))
    grid = np.linspace(MU.lo, MU.hi, 801)
    points = pl.concat([chosen.select("theta_deg"), EVEN.select("theta_deg")])
    f_grid = _forward.predict(DISC, {"mu": grid}, points, ["e_t"])["e_t"]
    f_true = _forward.predict(DISC, {"mu": truths}, points, ["e_t"])["e_t"]
    data = f_true + SIGMA["e_t"] * rng.standard_normal(f_true.shape)
    realised = {}
    for name, cols in (("chosen", slice(0, 4)), ("even", slice(4, 8))):
        sds, covered = [], 0
        for y, truth in zip(data, truths):
            ok = np.isfinite(y[cols])
            chi2 = (((y[cols][ok] - f_grid[:, cols][:, ok]) / SIGMA["e_t"]) ** 2).sum(axis=1)
            w = np.exp(-0.5 * (chi2 - chi2.min()))
            w /= w.sum()
            mean = (w * grid).sum()
            sds.append(np.sqrt((w * (grid - mean) ** 2).sum()))
            covered += abs(truth - mean) < 3.0 * sds[-1]
        realised[name] = float(np.mean(sds))
        assert covered >= 22, (name, covered)
    print("realised posterior sd of mu", realised)
    assert realised["chosen"] < 0.8 * realised["even"], realised
    # The linear-Gaussian expectation is close to what is realised.
    assert 0.5 < realised["chosen"] / chosen["sd_mu"][-1] < 2.0, (realised, chosen)


def test_e_n_informs_cor_at_every_angle_alike():
    """A sphere's e_N is cor at any angle: measured with sd 0.01 at k points the posterior sd of
    cor is about 0.01 / sqrt(k), whatever the angles (a uniform prior of sd 0.14 barely adds)."""
    scene = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98,
                     mu=0.092, v=3.9)
    d = rs.calibrate.design(scene, {"mu": rs.Uniform(0.05, 0.3), "cor": rs.Uniform(0.5, 0.99)}, CANDIDATES, k=4,
                            quantities=["e_n", "e_t"], sigma={"e_n": 0.01, "e_t": 0.02}, draws=16)
    assert np.allclose(d["sd_cor"].to_numpy(), 0.01 / np.sqrt([1, 2, 3, 4]), rtol=0.03), d


@pytest.mark.parametrize("kwargs, name", [
    (dict(k=0), "k"),
    (dict(k=19), "k"),
    (dict(sigma={"e_t": 0.0}), "sigma.e_t"),
    (dict(sigma={}), "sigma.e_t"),
    (dict(free={"omega_in": MU}), "free"),
    (dict(free={}), "free"),
    (dict(quantities=["e_q"]), "quantities"),
    (dict(draws=1), "draws"),
])
def test_refusals_name_the_parameter(kwargs, name):
    args = {"free": {"mu": MU}, "k": 2, "quantities": ["e_t"], "sigma": SIGMA, **kwargs}
    with pytest.raises(rs.RestitutionError) as err:
        rs.calibrate.design(DISC, candidates=CANDIDATES, **args)
    assert err.value.parameter == name
