"""From measurements to contact parameters.

- :mod:`.roots`: one parameter from one coefficient by root finding (:func:`gamma_for_e_n`,
  :func:`mu_for_e_t`).
- :func:`fit`: a Bayesian posterior over any scene fields from measured impacts
  (:class:`Posterior`: samples, summary, predictive check, plots); :func:`compare` ranks contact
  models on the same data by WAIC (docs/model.md, "Calibration").
- :mod:`.sobol`: which parameter moves which quantity at which angle, by Sobol' indices
  (:func:`sensitivity`, :func:`plot_sensitivity`).
- :mod:`.experiment`: which impacts to measure next (:func:`design`).

The statistical methods need the ``calibrate`` extra (``pip install "restitution[calibrate]"``).
"""

from .compare import compare
from .experiment import design
from .posterior import Posterior
from .roots import Calibration, gamma_for_e_n, mu_for_e_t
from .sampler import fit
from .sobol import plot_sensitivity, sensitivity

__all__ = [
    "Calibration",
    "Posterior",
    "compare",
    "design",
    "fit",
    "gamma_for_e_n",
    "mu_for_e_t",
    "plot_sensitivity",
    "sensitivity",
]
