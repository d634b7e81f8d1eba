"""The scene: everything that defines an impact except its angle and spin."""

from __future__ import annotations

import dataclasses
import inspect
from dataclasses import dataclass
from typing import Any

from . import _engine
from .shapes import ConvexPolygon, Disc, RegularPolygon, Shape, Sphere

INTEGRATORS = _engine.CHOICES["integrator"]
NORMAL_LAWS = _engine.CHOICES["normal_law"]
INERTIAS = _engine.CHOICES["inertia"]
#: Overlap paths: what the shape requires (closed form / half-plane clip), or the general
#: convex-convex intersection through parry (polygons only), to compare the two.
OVERLAPS = _engine.CHOICES["overlap"]
#: Tangential laws: what the normal law implies ("mindlin" for "hertz", else "linear"), the
#: Cundall-Strack spring, or Mindlin-Deresiewicz (Hertz law only).
TANGENTIALS = _engine.CHOICES["tangential"]
#: How Mindlin's spring keeps its history (LAMMPS's names): "auto" ("mindlin/force"), as the
#: displacement ("mindlin") or the elastic force ("mindlin/force"), each also rescaled with the
#: contact radius as the contact unloads ("mindlin_rescale", "mindlin_rescale/force").
TANGENTIAL_HISTORIES = _engine.CHOICES["tangential_history"]


def _choice(name: str, value: Any) -> float:
    return float(_engine.code(name, value))


def _conversion(name: str) -> Any:
    """How a scene field becomes its engine column's value (each checks the field's type)."""
    if name in _engine.CHOICES:
        return _choice
    if name in _engine.FLAGS:
        return _engine.flag
    return _engine.optional if name in _engine.OPTIONAL else _engine.real


#: The engine columns computed from the shapes (and the impact's, set by each simulate); every
#: other column is the scene's field of that name.
_COMPUTED = ("theta_deg", "omega_in", "r", "n", "phi0_deg", "body", "partner_body", "partner_n", "partner_r",
             "partner_phi0_deg", "partner_omega_in")
_FIELDS = tuple(name for name in _engine.CASE_COLUMNS if name not in _COMPUTED)
_CONVERSIONS = tuple((name, _conversion(name)) for name in _FIELDS)
#: Each field's kind (0 real, 1 optional, 2 choice, 3 flag) beside its conversion, and the
#: choices' codes by name: what lets :func:`_field_values` take the usual values without a call.
_PLAN = tuple((name, (_engine.real, _engine.optional, _choice, _engine.flag).index(convert), convert)
              for name, convert in _CONVERSIONS)
_CODES = {name: {label: float(k) for k, label in enumerate(labels)} for name, labels in _engine.CHOICES.items()}
_NAN = float("nan")


def _field_values(fields: dict[str, Any]) -> dict[str, float]:
    """The engine value of each field of a scene's ``fields``. The usual values (a float, None
    for an optional, a known choice's name) are taken inline, the conversions' own first tests;
    anything else goes through its conversion, which checks it and names it. A call per field
    was a third of a scene's cost."""
    out: dict[str, float] = {}
    for name, kind, convert in _PLAN:
        value = fields[name]
        if type(value) is float:
            if kind <= 1 and value == value:  # a real, or a set optional (an explicit NaN is refused)
                out[name] = value
                continue
        elif value is None:
            if kind == 1:
                out[name] = _NAN
                continue
        elif kind == 2 and type(value) is str:
            code = _CODES[name].get(value)
            if code is not None:
                out[name] = code
                continue
        out[name] = convert(name, value)
    return out


#: The preset particle (shapes are frozen, so one instance serves every scene).
_PRESET_DISC = Disc(r=0.01)


@dataclass(frozen=True, kw_only=True)
class Scene:
    """An impact scene: particle, material, contact law and numerics (SI units, per unit depth;
    per particle for a ``Sphere``).

    ``Scene()`` is the study's preset on an exact disc, integrated by the adaptive path to
    ``tol = 1e-6`` (every record carries its error estimate ``err_est``); :meth:`Scene.paper` is
    the preset on the study's 120-gon with the study's own method, Gear-5 at dt = 0.01 t_ref.
    Every field is validated: bad values raise ``ValueError`` naming the parameter and its allowed
    range.

    Examples
    --------
    >>> import restitution as rs
    >>> scene = rs.Scene(mu=0.1)
    >>> scene.replace(mu=1.0).mu
    1.0
    """

    shape: Shape = _PRESET_DISC
    """Particle shape: ``Disc``, ``RegularPolygon``, ``ConvexPolygon`` (2D, per unit depth) or
    ``Sphere`` (3D, per particle; Hertz or linear law)."""
    rho: float = 2500.0
    """Density (kg/m^3)."""
    E: float = 1e7
    """Young's modulus (Pa): of the area law (t_ref = sqrt(m / E)) or the sphere's (Hertz law)."""
    gamma: float = 0.33
    """Normal damping of the area law (dimensionless; calibrated to e_N = 0.90 head-on at v:
    ``calibrate.gamma_for_e_n`` gives 0.33249 on the 120-gon, 0.33299 on the exact disc)."""
    gamma_t: float = 0.5
    """Tangential damping ratio: c_t = gamma_t sqrt(k_t m_t) (0 allowed)."""
    mu: float = 0.5
    """Coulomb friction coefficient (0: no tangential force)."""
    v: float = 0.0357
    """Impact speed (m/s)."""
    integrator: str = "adaptive"
    """"adaptive" (the default: Dormand-Prince 5(4) with the contact's switches located, to the
    accuracy ``tol``, each record estimating its error in ``err_est``; its step budget bounds any
    impact to about a second, past which it ends ``timed_out``), "gear5" (the study's fixed step,
    ``Scene.paper()``'s), "verlet" (cheap fixed step; not with the linear law on a polygon) or
    "reference" (the adaptive path at its tightest setting: accurate to about 1e-10)."""
    dt_factor: float | None = None
    """gear5 / verlet: dt = dt_factor * t_ref, at most ``max_dt_factor`` (the integrator's stability
    bound for this scene's stiffness and damping: 0.0702 for gear5, 0.105 for verlet on the preset).
    "adaptive" and "reference": the largest (and first) step in units of t_ref; the tolerance sets
    the accuracy. None: the integrator's default, 0.01 (gear5, verlet, reference) or 1 (adaptive)."""
    normal_law: str = "area"
    """"area" (force proportional to overlap area), "linear" (spring-dashpot on the depth) or
    "hertz" (a Sphere's point contact, 4/3 E* sqrt(R) delta^1.5, damped to e_N = ``cor``)."""
    kn: float | None = None
    """Linear law stiffness (Pa); None: equal to E."""
    cn: float | None = None
    """Linear law damping (Pa s); None: 0."""
    kt: float | None = None
    """Tangential stiffness (Pa); None: 2 E / 7 (area) or 2 kn / 7 (linear)."""
    inertia: str = "shape"
    """"shape" (exact; 2/5 m r^2 for a Sphere) or "sphere" (I = 0.4 m r^2, discs and spheres only)."""
    nu: float | None = None
    """Poisson's ratio of the particle (Hertz law; required there)."""
    plate_E: float | None = None
    """The plate's Young's modulus (Pa, Hertz law); None: a rigid plate."""
    plate_nu: float | None = None
    """The plate's Poisson's ratio (Hertz law; required with ``plate_E``)."""
    cor: float | None = None
    """Head-on restitution the Hertz law's damping is calibrated to, in [0.01, 1] (required there;
    independent of the speed)."""
    tangential: str = "auto"
    """"auto" ("mindlin" for the Hertz law, else "linear"), "linear" (Cundall-Strack spring ``kt``,
    damping ``gamma_t``; with the Hertz law ``kt`` in N/m is required) or "mindlin"
    (k_t = 8 G* sqrt(R delta), incremental, capped at mu F_n, damped like the normal law)."""
    tangential_history: str = "auto"
    """How Mindlin's spring keeps its history, as LAMMPS's ``pair granular`` names it (docs/model.md,
    section 14.8): "auto" (= "mindlin/force": the elastic force, incremented by -k_t v_t dt),
    "mindlin" (the displacement xi, force -k_t(delta) xi), "mindlin_rescale" and
    "mindlin_rescale/force" (the same, shrunk by a / a_prev as the contact radius a falls).
    Anything but "auto" requires Mindlin's spring (the Hertz law)."""
    overlap: str = "auto"
    """Overlap with the plate: "auto" (closed-form segment for a disc, half-plane clip for a
    polygon), "halfplane", or "parry" (general convex-convex intersection; polygons only)."""
    tol: float = 1e-6
    """Target absolute error of e_N, e_T, e_kin and omega_out r / v for ``integrator="adaptive"``,
    in [1e-12, 1e-2]; its records estimate their own error in ``err_est``. Ignored by the others."""
    error_estimate: bool = False
    """gear5 / verlet: estimate each record's error (``err_est``) from a second run at half the step
    (costs 3x); the adaptive path always estimates it. False: ``err_est`` is null."""
    max_steps: int | None = None
    """Most integration steps one impact may take (>= 1): past it the impact ends with
    ``timed_out = True`` and ``stop = "step_budget"``. None: the default budget, a fixed multiple
    of the contact's own number of steps (docs/model.md, "Bounded work"); every record says
    which budget it ran under (``step_budget``)."""
    partner: Shape | None = None
    """What the particle hits: None, the plate (default); or a second, free particle (a ``Disc``,
    ``RegularPolygon`` or ``ConvexPolygon`` for a disc or a polygon, a ``Sphere`` for a sphere), in
    which case ``v`` is the relative speed and ``theta_deg`` the angle between the relative velocity
    and the tangent at first touch, the line of centres' normal (docs/model.md, sections 17, 17.8)."""
    partner_rho: float | None = None
    """The partner's density (kg/m^3); None: the particle's ``rho``."""
    partner_E: float | None = None
    """The partner's Young's modulus (Pa); None: the particle's ``E``."""
    partner_nu: float | None = None
    """The partner's Poisson's ratio (Hertz law); None: the particle's ``nu``."""

    def __post_init__(self) -> None:
        # Python checks only what the engine cannot: types and choice names. Every rule on
        # values (ranges, combinations, the time-step bound) is the engine's, checked here once.
        if not isinstance(self.shape, (Disc, RegularPolygon, ConvexPolygon, Sphere)):
            raise TypeError("`shape` must be Disc, RegularPolygon, ConvexPolygon or Sphere "
                            f"(found {type(self.shape).__name__})")
        if self.partner is not None and not isinstance(self.partner, (Disc, RegularPolygon, ConvexPolygon, Sphere)):
            raise TypeError("`partner` must be None (the plate), Disc, RegularPolygon, ConvexPolygon or Sphere "
                            f"(found {type(self.partner).__name__})")
        values = self.engine_values()
        row = tuple(map(values.__getitem__, _engine.CASE_COLUMNS))
        try:
            _engine.check_one(row, self.template_vertices())
        except _engine.RestitutionError as err:
            raise err.at_case(None) from None  # a scene is not a case of a sweep
        # Its row of engine columns, kept (the scene is frozen): each simulate() writes only
        # its angle and spin into a copy.
        object.__setattr__(self, "_row", row)

    def engine_values(self) -> dict[str, float]:
        """The scene's value of every engine column (``theta_deg`` 90 and ``omega_in`` 0 until
        an impact sets them; None as NaN; a choice as its code)."""
        values: dict[str, float] = {"theta_deg": 90.0, "omega_in": 0.0, "r": self.r,
                                    "n": float(self.shape.n if not isinstance(self.shape, ConvexPolygon) else 0),
                                    "phi0_deg": _engine.real("phi0_deg", self.shape.phi0_deg),
                                    "body": float(_engine.code("body", "sphere" if isinstance(self.shape, Sphere)
                                                               else "prism")),
                                    **self._partner_values()}
        values.update(_field_values(self.__dict__))
        return values

    def _partner_values(self) -> dict[str, float]:
        """The partner's shape as engine columns (``partner_body`` "plate" and NaN without one;
        its spin ``partner_omega_in`` 0 until an impact sets it)."""
        nan = float("nan")
        shape = self.partner
        if shape is None:
            return {"partner_body": float(_engine.code("partner_body", "plate")), "partner_n": nan,
                    "partner_r": nan, "partner_phi0_deg": nan, "partner_omega_in": 0.0}
        return {"partner_body": float(_engine.code("partner_body", "sphere" if isinstance(shape, Sphere) else "prism")),
                "partner_n": float(0 if isinstance(shape, ConvexPolygon) else shape.n), "partner_r": float(shape.r),
                "partner_phi0_deg": _engine.real("partner_phi0_deg", shape.phi0_deg), "partner_omega_in": 0.0}

    def _engine_row(self) -> tuple[float, ...]:
        """:meth:`engine_values` as one row in ``CASE_COLUMNS`` order, kept from construction."""
        row: tuple[float, ...] | None = self.__dict__.get("_row")
        if row is None:  # unpickled from a version that did not keep it
            row = _engine.row(self.engine_values())
            object.__setattr__(self, "_row", row)
        return row

    def template_vertices(self) -> Any:
        """Unit-circumradius vertices of a ConvexPolygon scene (the engine scales them by r), else None;
        with a ConvexPolygon partner, the pair (the particle's or None, the partner's)."""
        own = self.shape._template if isinstance(self.shape, ConvexPolygon) else None
        if isinstance(self.partner, ConvexPolygon):
            return own, self.partner._template
        return own

    @classmethod
    def paper(cls, shape: Shape | None = None, **changes: Any) -> Scene:
        """The study's preset and method (docs/model.md): a 120-gon of circumradius 0.01 m unless
        ``shape`` is given, integrated by Gear-5 at dt = 0.01 t_ref as in the study (``changes``
        may set another integrator)."""
        changes = {"integrator": "gear5", **changes}
        return cls(shape=shape if shape is not None else RegularPolygon(r=0.01, n=120, phi0_deg=0.0), **changes)

    def replace(self, **changes: Any) -> Scene:
        """A validated copy with some fields changed."""
        unknown = changes.keys() - _FIELD_NAMES
        if unknown:  # what dataclasses.replace would say
            raise TypeError(f"Scene.__init__() got an unexpected keyword argument '{sorted(unknown)[0]}'")
        # The copy's fields set directly and checked by __post_init__, as a new Scene's are:
        # dataclasses.replace reads every field and calls the frozen __init__, which sets each
        # one through object.__setattr__ (two thirds of a replace's cost).
        copy = object.__new__(Scene)
        state = copy.__dict__
        state.update(self.__dict__)
        state.update(changes)
        copy.__post_init__()
        return copy

    def to_lammps(self, theta_deg: float, omega_in: float = 0.0, *, partner_omega_in: float = 0.0,
                  steps_per_contact: int | None = None) -> str:
        """A complete LAMMPS input script (units si) of this scene's impact at ``theta_deg``
        (from the plate) with spin ``omega_in``: the particle, the plate as a ``fix wall/gran
        granular`` wall with this scene's law (a Disc or Sphere partner: a second atom, spin
        ``partner_omega_in``, and ``pair_style granular``), the step (the estimated contact time over
        ``steps_per_contact``, None: 1000), a run to separation, and a last line
        ``restitution: vx_out=... vy_out=... omega_out=... contact_time=...`` in this project's
        axes and signs. What LAMMPS cannot express (the area law, polygons) raises
        :class:`RestitutionError` naming the field and why. The mapping: docs/lammps.md,
        ``restitution.lammps.MAPPING``.

        Examples
        --------
        >>> import restitution as rs
        >>> ball = rs.Scene(shape=rs.Sphere(2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
        ...                 cor=0.98, mu=0.092, v=3.9)
        >>> script = ball.to_lammps(theta_deg=60.0)
        >>> "damping coeff_restitution tangential mindlin/force" in script
        True
        """
        from .lammps.script import write

        return write(self, theta_deg, omega_in, partner_omega_in, steps_per_contact)

    @property
    def max_dt_factor(self) -> float:
        """Largest ``dt_factor`` this scene accepts: its integrator's stability bound for its
        stiffness and damping (E, kn, kt, gamma, cn, gamma_t, mu, shape), with a margin of 2.
        It holds for any v, theta and spin. Computed by the engine (one formula; see
        docs/model.md, "Stability bounds")."""
        bounds, _ = _engine.dt_bounds(_engine.columns(self.engine_values(), {}, 1), self.template_vertices())
        return float(bounds[0])

    @property
    def r(self) -> float:
        """Circumradius of the particle (m)."""
        return float(self.shape.r)


#: Largest accepted ``dt_factor`` per integrator for the study's preset on the exact disc,
#: ``Scene()``; ``Scene.paper()`` (the 120-gon) is within 0.2 %. Another scene's own bound,
#: which depends on its stiffness and damping, is ``scene.max_dt_factor``.
MAX_DT_FACTOR = {name: Scene(integrator=name).max_dt_factor for name in INTEGRATORS}

#: Every field's default (each a plain value: shapes are frozen), hence every field's name.
_DEFAULTS = {f.name: f.default for f in dataclasses.fields(Scene)}
_FIELD_NAMES = frozenset(_DEFAULTS)
_DATACLASS_INIT = Scene.__init__


def _init(self: Scene, **fields: Any) -> None:
    # The generated __init__ of a frozen dataclass sets each of the 28 fields through
    # object.__setattr__: 5 of a scene's 12 us. This one sets them in two dict updates and runs
    # the same __post_init__; the signature (for help() and IDEs) and the refusal of an unknown
    # name are the generated one's. Type checkers and the docs read the fields, as before.
    unknown = fields.keys() - _FIELD_NAMES
    if unknown:
        raise TypeError(f"Scene.__init__() got an unexpected keyword argument '{sorted(unknown)[0]}'")
    state = self.__dict__
    state.update(_DEFAULTS)
    state.update(fields)
    self.__post_init__()


_init.__signature__ = inspect.signature(_DATACLASS_INIT)  # type: ignore[attr-defined]
_init.__doc__ = _DATACLASS_INIT.__doc__
_init.__name__, _init.__qualname__ = "__init__", "Scene.__init__"
Scene.__init__ = _init  # type: ignore[method-assign]
