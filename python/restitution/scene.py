"""The scene: everything that defines an impact except its angle and spin."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

from ._validation import check_choice, check_non_negative, check_positive, check_real
from .shapes import ConvexPolygon, Disc, RegularPolygon, Shape

INTEGRATORS = ("gear5", "verlet", "reference")
NORMAL_LAWS = ("area", "linear")
INERTIAS = ("shape", "sphere")
#: Overlap paths: what the shape requires (closed form / half-plane clip), or the general
#: convex-convex intersection through parry (polygons only), to compare the two.
OVERLAPS = ("auto", "halfplane", "parry")



@dataclass(frozen=True, kw_only=True)
class Scene:
    """An impact scene: particle, material, contact law and numerics (SI units, per unit depth).

    ``Scene()`` is the study's preset on an exact disc; :meth:`Scene.paper` is the preset on
    the study's 120-gon. Every field is validated: bad values raise ``ValueError`` naming the
    parameter and its allowed range.

    Examples
    --------
    >>> import restitution as rs
    >>> scene = rs.Scene(mu=0.1)
    >>> scene.replace(mu=1.0).mu
    1.0
    """

    shape: Shape = field(default_factory=lambda: Disc(r=0.01))
    """Particle shape: ``Disc``, ``RegularPolygon`` or ``ConvexPolygon``."""
    rho: float = 2500.0
    """Density (kg/m^3)."""
    E: float = 1e7
    """Young's modulus of the area law (Pa); sets t_ref = sqrt(m / E)."""
    gamma: float = 0.33
    """Normal damping of the area law (dimensionless; calibrated to e_N = 0.90 head-on at v:
    ``calibrate.gamma_for_e_n`` gives 0.33249 on the 120-gon, 0.33299 on the exact disc)."""
    gamma_t: float = 0.5
    """Tangential damping ratio: c_t = gamma_t sqrt(k_t m_t) (0 allowed)."""
    mu: float = 0.5
    """Coulomb friction coefficient (0: no tangential force)."""
    v: float = 0.0357
    """Impact speed (m/s)."""
    integrator: str = "gear5"
    """"gear5" (the study's), "verlet" (cheap) or "reference" (adaptive Dormand-Prince 5(4) with the
    contact's switches located: accurate to about 1e-10, a few times slower than gear5 at dt_factor 1)."""
    dt_factor: float = 0.01
    """dt = dt_factor * t_ref; at most ``max_dt_factor`` (the integrator's stability bound for this scene's
    stiffness and damping: 0.0648 for gear5, 0.108 for verlet on the preset). For "reference" it is the largest
    (and first) step instead: its accuracy is set by its tolerance, so use dt_factor=1 for speed."""
    normal_law: str = "area"
    """"area" (force proportional to overlap area) or "linear" (spring-dashpot on the depth)."""
    kn: float | None = None
    """Linear law stiffness (Pa); None: equal to E."""
    cn: float | None = None
    """Linear law damping (Pa s); None: 0."""
    kt: float | None = None
    """Tangential stiffness (Pa); None: 2 E / 7 (area) or 2 kn / 7 (linear)."""
    inertia: str = "shape"
    """"shape" (exact) or "sphere" (I = 0.4 m r^2, discs only)."""
    overlap: str = "auto"
    """Overlap with the plate: "auto" (closed-form segment for a disc, half-plane clip for a
    polygon), "halfplane", or "parry" (general convex-convex intersection; polygons only)."""

    def __post_init__(self) -> None:
        if not isinstance(self.shape, (Disc, RegularPolygon, ConvexPolygon)):
            raise TypeError(f"`shape` must be Disc, RegularPolygon or ConvexPolygon (found {type(self.shape).__name__})")
        for name in ("rho", "E", "v"):
            check_positive(name, getattr(self, name))
        for name in ("gamma", "gamma_t", "mu"):
            check_non_negative(name, getattr(self, name))
        check_choice("integrator", self.integrator, INTEGRATORS)
        check_choice("normal_law", self.normal_law, NORMAL_LAWS)
        check_choice("inertia", self.inertia, INERTIAS)
        if self.kn is not None:
            check_positive("kn", self.kn)
        if self.cn is not None:
            check_non_negative("cn", self.cn)
        if self.kt is not None:
            check_positive("kt", self.kt)
        if self.inertia == "sphere" and not isinstance(self.shape, Disc):
            raise ValueError('require `inertia` "shape" for polygons ("sphere" applies to discs only)')
        check_choice("overlap", self.overlap, OVERLAPS)
        if self.overlap == "parry" and isinstance(self.shape, Disc):
            raise ValueError(
                'require `overlap` "auto" or "halfplane" for a Disc (found "parry": the parry path '
                "intersects polygons; use a RegularPolygon with large n to compare)"
            )
        # Last: the bound depends on every other field (the scene's stiffness and damping).
        dtf = check_real("dt_factor", self.dt_factor)
        bound = self.max_dt_factor
        if not (math.isfinite(dtf) and 0.0 < dtf <= bound):  # one message, with the bound, for NaN too
            why = _dt_bounds(self, explain=True)[1][0]
            raise ValueError(f"require `dt_factor` in (0, {bound}] for the {self.integrator} integrator ({why}; found {dtf})")

    @classmethod
    def paper(cls, shape: Shape | None = None, **changes: Any) -> Scene:
        """The study's preset (MODEL.md): a 120-gon of circumradius 0.01 m unless ``shape`` is given."""
        return cls(shape=shape if shape is not None else RegularPolygon(r=0.01, n=120, phi0_deg=0.0), **changes)

    def replace(self, **changes: Any) -> Scene:
        """A validated copy with some fields changed."""
        return dataclasses.replace(self, **changes)

    @property
    def max_dt_factor(self) -> float:
        """Largest ``dt_factor`` this scene accepts: its integrator's stability bound for its
        stiffness and damping (E, kn, kt, gamma, cn, gamma_t, mu, shape), with a margin of 2.
        It holds for any v, theta and spin. Computed by the engine (one formula; see the
        documentation of ``restitution_core::stability``)."""
        return float(_dt_bounds(self)[0][0])

    @property
    def r(self) -> float:
        """Circumradius of the particle (m)."""
        return float(self.shape.r)


def _dt_bounds(scene: Scene, explain: bool = False) -> tuple[Any, list[str] | None]:
    """The engine's bound (and, with ``explain``, what sets it) for a scene, as one case."""
    from . import _core
    from ._columns import build_columns, template_vertices

    cols = build_columns(scene, {}, 1)
    return _core.max_dt_factor_for(cols, template_vertices(scene), scene.normal_law, scene.inertia, explain)


#: Largest accepted ``dt_factor`` per integrator for the study's preset on the exact disc,
#: ``Scene()``; ``Scene.paper()`` (the 120-gon) is within 0.2 %. Another scene's own bound,
#: which depends on its stiffness and damping, is ``scene.max_dt_factor``.
MAX_DT_FACTOR = {name: Scene(integrator=name).max_dt_factor for name in INTEGRATORS}
