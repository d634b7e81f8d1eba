"""From measurements to contact parameters.

- :mod:`.roots`: one parameter from one coefficient by root finding (:func:`gamma_for_e_n`,
  :func:`mu_for_e_t`).
"""

from .roots import Calibration, gamma_for_e_n, mu_for_e_t

__all__ = ["Calibration", "gamma_for_e_n", "mu_for_e_t"]
