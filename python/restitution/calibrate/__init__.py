"""From measurements to contact parameters.

- :mod:`.roots`: one parameter from one coefficient by root finding (:func:`gamma_for_e_n`,
  :func:`mu_for_e_t`).
- :mod:`.sobol`: which parameter moves which quantity at which angle, by Sobol' indices
  (:func:`sensitivity`, :func:`plot_sensitivity`).
- :mod:`.experiment`: which impacts to measure next (:func:`design`).

The statistical methods need the ``calibrate`` extra (``pip install "restitution[calibrate]"``).
"""

from .roots import Calibration, gamma_for_e_n, mu_for_e_t
from .experiment import design
from .sobol import plot_sensitivity, sensitivity

__all__ = ["Calibration", "design", "gamma_for_e_n", "mu_for_e_t", "plot_sensitivity", "sensitivity"]
