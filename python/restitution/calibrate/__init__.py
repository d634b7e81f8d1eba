"""From measurements to contact parameters.

- :mod:`.roots`: one parameter from one coefficient by root finding (:func:`gamma_for_e_n`,
  :func:`mu_for_e_t`).
- :func:`fit`: a Bayesian posterior over any scene fields from measured impacts
  (:class:`Posterior`: samples, summary, predictive check, plots); :func:`compare` ranks contact
  models on the same data by WAIC (docs/model.md, "Calibration").
"""

from .compare import compare
from .sampler import fit
from .posterior import Posterior
from .roots import Calibration, gamma_for_e_n, mu_for_e_t

__all__ = ["Calibration", "Posterior", "compare", "fit", "gamma_for_e_n", "mu_for_e_t"]
