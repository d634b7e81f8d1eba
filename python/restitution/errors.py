"""The package's one error type for invalid parameters.

Every rule a scene, an impact or a sweep case must meet is checked once, by the engine; a
violation raises :class:`RestitutionError` carrying what the user needs to fix it, so that no
caller ever parses a message:

>>> import restitution as rs
>>> try:
...     rs.Scene(mu=-1.0)
... except rs.RestitutionError as err:
...     print(err.parameter, err.value, "|", err)
mu -1.0 | require `mu` finite and >= 0 (found -1.0)
"""

from __future__ import annotations

from typing import Any


class RestitutionError(ValueError):
    """An invalid parameter: which one, its value, what is allowed and, in sweeps, which case.

    It is a ``ValueError``, so ``except ValueError`` keeps working.

    Attributes
    ----------
    parameter : str
        The parameter's public name (``"mu"``, ``"dt_factor"``, ``"theta_deg"`` ...).
    value : Any
        The offending value (a float where it is a number).
    expected : str
        The allowed range, in words (``"finite and >= 0"``).
    case : int or None
        The row of a sweep (in case order) or of a cases table; None outside sweeps.
    """

    def __init__(self, parameter: str, value: Any, expected: str, case: int | None = None) -> None:
        self.parameter = parameter
        self.value = value
        self.expected = expected
        self.case = case
        super().__init__(str(self))

    def __str__(self) -> str:
        where = f"case {self.case}: " if self.case is not None else ""
        return f"{where}require `{self.parameter}` {self.expected} (found {self.value})"

    def __reduce__(self) -> tuple[Any, ...]:
        # Crosses process boundaries (Dask workers) with its fields, not only its message.
        return (type(self), (self.parameter, self.value, self.expected, self.case))

    def at_case(self, case: int | None) -> RestitutionError:
        """The same error for ``case`` (e.g. a chunk's row made an index in the whole sweep)."""
        return type(self)(self.parameter, self.value, self.expected, case)


class RestitutionTypeError(RestitutionError, TypeError):
    """A value of the wrong kind (a bool or a string where a number is expected, a number where
    a name is): a :class:`RestitutionError` with the same attributes (``.case`` in a cases
    table), and a ``TypeError``, so ``except TypeError`` keeps working."""


class RestitutionFileError(RestitutionError):
    """A file this package wrote (a dataset's manifest, part or cases table, a collision table)
    that is unreadable, truncated, foreign or edited: ``.parameter`` is ``"path"``, ``.value``
    the file, ``.expected`` what is wrong with it and how to fix it. Shown as ``FILE: WHAT; FIX``."""

    def __str__(self) -> str:
        return f"{self.value}: {self.expected}"


__all__ = ["RestitutionError", "RestitutionFileError", "RestitutionTypeError"]
