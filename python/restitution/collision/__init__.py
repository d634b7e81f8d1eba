"""Collision operators: the engine's outcome tabulated for event-driven and rockfall codes, and
the reduced models (Walton's, constant coefficients) fitted to it with their error."""

from .operator import CollisionOperator
from .reduced import ReducedModel, fit_constant, fit_walton

__all__ = ["CollisionOperator", "ReducedModel", "fit_constant", "fit_walton"]
