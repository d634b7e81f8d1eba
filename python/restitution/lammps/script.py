"""A scene as a LAMMPS input script: the mapping, Scene field by field, written once.

:data:`MAPPING` is the one table from the scene's fields to LAMMPS's keywords
(``pair granular`` / ``fix wall/gran granular``, ``atom_style sphere``, ``fix nve/sphere``):
:func:`write` follows it and ``docs/lammps.md`` prints it (:func:`mapping_markdown`; a test keeps
the two equal). What LAMMPS cannot express is refused with a :class:`RestitutionError` naming the
field and why (:data:`REFUSED`). The constants are derived from docs/model.md (sections 4.3, 5,
14.2-14.4 and 14.8) and LAMMPS's documentation of its granular models, not from either code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .. import _core
from ..errors import RestitutionError
from ..shapes import Disc, Sphere

#: LAMMPS steps per (estimated) contact time: fix nve/sphere is velocity Verlet, first order
#: with a tangential history and its dashpot. At 1000 the linear-law disc of docs/lammps.md
#: agrees with the engine's reference to 1.2e-3 of v in omega r (4.6e-3 at 200); the Hertz
#: sphere was within 2.4e-4 already at 200. One impact is then ~1e3 steps of one atom.
STEPS_PER_CONTACT = 1000
#: The run's length, in estimated contact times: it halts at separation long before.
RUN_CONTACTS = 100
#: Chung & Ooi / Hertz: contact time of an elastic Hertz impact in units of delta_max / v_n.
HERTZ_TIME = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)


@dataclass(frozen=True)
class Field:
    """One row of the mapping: a Scene field, where it goes in LAMMPS, and how."""

    field: str
    keyword: str
    how: str


#: Scene field -> LAMMPS keyword: the table :func:`write` follows and docs/lammps.md prints.
MAPPING: tuple[Field, ...] = (
    Field("shape", "`dimension 3` (`Sphere`) or `dimension 2` + `fix enforce2d` (`Disc`); "
          "`set atom 1 diameter`", "one `atom_style sphere` particle of diameter 2r; a disc is per unit depth"),
    Field("rho", "`set atom 1 mass`", "m = 4/3 pi r^3 rho (sphere), pi r^2 rho (disc, per metre of depth)"),
    Field("inertia", "`fix nve/sphere` [`disc`]", "I = 2/5 m r^2 (sphere; disc with \"sphere\"); "
          "`disc` keyword: I = 1/2 m r^2 (disc with \"shape\")"),
    Field("v", "`velocity particle set`", "v (cos theta, -sin theta, 0); theta_deg from the plate (a pair: "
          "from the tangent at first touch, v the relative speed)"),
    Field("normal_law", "`hertz` or `hooke` in `fix wall/gran granular`", "\"hertz\": `hertz` k_n = 4/3 E*; "
          "\"linear\": `hooke` k_n = kn"),
    Field("E, nu", "`hertz` k_n; `mindlin` k_t", "E* and G* of docs/model.md 14.2, 14.4, written as "
          "k_n = 4/3 E* and k_t = 8 G*: the engine's moduli exactly, the plate's included (`hertz/material` "
          "would leave the wall's mixing rule to LAMMPS)"),
    Field("plate_E, plate_nu", "folded into k_n and k_t", "1/E* = (1-nu^2)/E + (1-nu_p^2)/E_p, "
          "1/G* = (2-nu)/G + (2-nu_p)/G_p; None: a rigid plate, the plate's terms absent (exact)"),
    Field("cor", "`damping coeff_restitution` e_L", "LAMMPS's damping is the engine's Tsuji form with "
          "beta_L = -ln e_L / sqrt(ln^2 e_L + pi^2); e_L = exp(-pi beta / sqrt(1 - beta^2)) with the "
          "engine's calibrated beta(cor) (docs/model.md 14.3), so the head-on e_N is cor, not e_L"),
    Field("kn", "`hooke` k_n", "kn (N/m per metre of depth for a disc; N/m for a sphere)"),
    Field("cn", "`hooke` eta_n0, `damping velocity`", "eta_n = cn; `limit_damping`: the plate never pulls"),
    Field("mu", "`tangential ... mu_s`", "mu"),
    Field("tangential, tangential_history", "`tangential linear_history` or `mindlin`, `mindlin/force`, "
          "`mindlin_rescale`, `mindlin_rescale/force`", "\"auto\" history: `mindlin/force`"),
    Field("kt", "`linear_history` k_t", "kt (default 2/7 kn)"),
    Field("gamma_t", "`linear_history` x_gamma,t", "x = c_t / cn with c_t = gamma_t sqrt(kt m_t), "
          "m_t = (1/m + r^2/I)^-1"),
    Field("(Mindlin's damping)", "`mindlin` x_gamma,t", "x = c_t / c_n = 2 sqrt(G*/E*): the engine damps "
          "Mindlin's spring with the normal law's beta"),
    Field("theta_deg, omega_in", "`velocity particle set`, `set atom 1 omega 0 0`", "project axes: the plate "
          "is `yplane 0.0 NULL`, x along it, spin about +z (counter-clockwise positive)"),
    Field("partner", "`pair_style granular`, `pair_coeff * *`, atom 2", "a Disc or Sphere partner at rest at the "
          "origin, the particle at (0, r1 + r2); the coefficients are the pair's effective ones: LAMMPS takes "
          "R* and m* from the atoms"),
    Field("partner_rho, partner_E, partner_nu", "`set atom 2 mass`; folded into k_n and k_t",
          "E* and G* of the two bodies (docs/model.md 17.3); a linear-law pair's springs in series: "
          "k* = kn / 2, c* = cn / 2"),
    Field("partner_omega_in", "`set atom 2 omega 0 0`", "the partner's spin"),
    Field("integrator, dt_factor, tol, error_estimate, max_steps, overlap", "`timestep`, `run`, `fix halt`",
          "not mapped: LAMMPS integrates by velocity Verlet at `timestep` = t_c / steps_per_contact and "
          "halts at separation"),
)

#: What does not map, and why (each raises RestitutionError naming the field).
REFUSED: dict[str, str] = {
    "normal_law": "\"linear\" or \"hertz\": LAMMPS's granular models act on a point contact's depth, "
                  "not on an overlap area (the area law)",
    "shape": "a Sphere or a Disc: LAMMPS's granular particles are round (atom_style sphere), "
             "a polygon has no granular contact there",
    "partner": "None (the plate), a Disc or a Sphere: LAMMPS's granular particles are round, a polygon "
               "has no granular contact there",
    "gamma_t": "0 here: LAMMPS scales the tangential damping from the normal one (eta_t = x eta_n), "
               "so a tangential dashpot needs a normal one of the same form (cn > 0 with the linear "
               "law; none with the Hertz law's linear spring, whose eta_n varies with the depth)",
    "cor": "at least 0.1354 (beta < 1): LAMMPS's coeff_restitution damping reaches beta = 1 only as its "
           "e tends to 0",
}


def mapping_markdown() -> str:
    """:data:`MAPPING` and :data:`REFUSED` as the Markdown tables of docs/lammps.md."""
    rows = ["| Scene field | LAMMPS | how |", "|---|---|---|"]
    rows += [f"| `{f.field}` | {f.keyword} | {f.how} |".replace("`(", "(").replace(")`", ")")
             for f in MAPPING]
    rows += ["", "| refused unless | why |", "|---|---|"]
    rows += [f"| `{name}` | {why} |" for name, why in REFUSED.items()]
    return "\n".join(rows)


def _refuse(name: str, value: Any) -> RestitutionError:
    return RestitutionError(name, value, REFUSED[name])


@dataclass(frozen=True)
class _Contact:
    """What the laws read, as the engine derives it (docs/model.md 14, 17.3): the two bodies'
    masses and inertias (the plate's infinite), the effective mass, radius and tangential mass."""

    sphere: bool
    masses: tuple[float, ...]
    inertias: tuple[float, ...]
    radii: tuple[float, ...]

    @property
    def m_eff(self) -> float:
        return 1.0 / sum(1.0 / m for m in self.masses)

    @property
    def r_eff(self) -> float:
        return 1.0 / sum(1.0 / r for r in self.radii)

    @property
    def m_t(self) -> float:
        """1/m_t = sum 1/m_i + r_i^2/I_i: the contact point's tangential mass."""
        return 1.0 / sum(1.0 / m + r * r / i for m, r, i in zip(self.masses, self.radii, self.inertias))


def _contact(scene: Any) -> _Contact:
    """The particle, and the partner when there is one, as the engine takes them."""
    sphere = isinstance(scene.shape, Sphere)
    bodies = [(scene.shape.r, scene.rho)]
    if scene.partner is not None:
        bodies.append((scene.partner.r, scene.partner_rho if scene.partner_rho is not None else scene.rho))
    kappa = 0.5 if (not sphere and scene.inertia == "shape") else 0.4
    masses = tuple((4.0 / 3.0 * math.pi * r**3 if sphere else math.pi * r * r) * rho for r, rho in bodies)
    radii = tuple(r for r, _ in bodies)
    return _Contact(sphere, masses, tuple(kappa * m * r * r for m, r in zip(masses, radii)), radii)


def _moduli(scene: Any) -> tuple[float, float]:
    """E* and G* of the sphere on its plate or partner (docs/model.md 14.2, 14.4, 17.3)."""
    bodies = [(scene.E, scene.nu)]
    if scene.partner is not None:
        bodies.append((scene.partner_E if scene.partner_E is not None else scene.E,
                       scene.partner_nu if scene.partner_nu is not None else scene.nu))
    elif scene.plate_E is not None:
        bodies.append((scene.plate_E, scene.plate_nu))
    inv_e = sum((1.0 - nu * nu) / e for e, nu in bodies)
    inv_g = sum((2.0 - nu) * 2.0 * (1.0 + nu) / e for e, nu in bodies)
    return 1.0 / inv_e, 1.0 / inv_g


def _hertz(scene: Any, contact: _Contact, v_n: float) -> tuple[list[str], float]:
    """The Hertz law's normal and tangential model words, and the contact time."""
    e_star, g_star = _moduli(scene)
    beta = _core.hertz_beta(scene.cor)
    if beta >= 1.0:
        raise _refuse("cor", scene.cor)
    e_lammps = math.exp(-math.pi * beta / math.sqrt(1.0 - beta * beta))
    delta_max = (15.0 * contact.m_eff * v_n * v_n / (16.0 * e_star * math.sqrt(contact.r_eff))) ** 0.4
    words = [f"hertz {4.0 / 3.0 * e_star!r} {e_lammps!r} damping coeff_restitution"]
    if scene.tangential == "linear":
        if scene.gamma_t != 0.0 and scene.mu != 0.0:
            raise _refuse("gamma_t", scene.gamma_t)
        words.append(f"tangential linear_history {scene.kt!r} 0.0 {scene.mu!r}")
    else:
        history = "mindlin/force" if scene.tangential_history == "auto" else scene.tangential_history
        words.append(f"tangential {history} {8.0 * g_star!r} {2.0 * math.sqrt(g_star / e_star)!r} {scene.mu!r}")
    return words, HERTZ_TIME * delta_max / v_n


def _linear(scene: Any, contact: _Contact) -> tuple[list[str], float]:
    """The linear law's normal and tangential model words, and the contact time (undamped).
    A pair's two springs and dashpots are in series: k* = kn / 2, c* = cn / 2 (17.3)."""
    share = 0.5 if len(contact.masses) == 2 else 1.0
    kn = share * (scene.kn if scene.kn is not None else scene.E)
    cn = share * (scene.cn if scene.cn is not None else 0.0)
    kt = scene.kt if scene.kt is not None else 2.0 / 7.0 * kn
    c_t = scene.gamma_t * math.sqrt(kt * contact.m_t)
    if c_t != 0.0 and cn == 0.0 and scene.mu != 0.0:
        raise _refuse("gamma_t", scene.gamma_t)
    x_t = c_t / cn if cn > 0.0 else 0.0
    words = [f"hooke {kn!r} {cn!r} damping velocity", f"tangential linear_history {kt!r} {x_t!r} {scene.mu!r}"]
    return words, math.pi * math.sqrt(contact.m_eff / kn)


def _check(scene: Any, theta_deg: float, spins: tuple[float, float], steps_per_contact: int) -> None:
    """Refuses what LAMMPS cannot express and bad arguments, naming each."""
    _core.check_theta(float(theta_deg))
    for name, spin in zip(("omega_in", "partner_omega_in"), spins):
        if not math.isfinite(spin):
            raise RestitutionError(name, spin, "finite (rad/s)")
    if not isinstance(scene.shape, (Sphere, Disc)):
        raise _refuse("shape", type(scene.shape).__name__)
    if scene.partner is not None and not isinstance(scene.partner, (Sphere, Disc)):
        raise _refuse("partner", type(scene.partner).__name__)
    if scene.normal_law == "area":
        raise _refuse("normal_law", scene.normal_law)
    if isinstance(steps_per_contact, bool) or not isinstance(steps_per_contact, int) or steps_per_contact < 10:
        raise RestitutionError("steps_per_contact", steps_per_contact, "a whole number >= 10")


def write(scene: Any, theta_deg: float, omega_in: float = 0.0, partner_omega_in: float = 0.0,
          steps_per_contact: int | None = None) -> str:
    """The LAMMPS input script of one impact of ``scene`` (see ``Scene.to_lammps``); None
    steps: :data:`STEPS_PER_CONTACT`."""
    steps_per_contact = STEPS_PER_CONTACT if steps_per_contact is None else steps_per_contact
    _check(scene, theta_deg, (omega_in, partner_omega_in), steps_per_contact)
    contact = _contact(scene)
    cos_t, sin_t = math.cos(math.radians(theta_deg)), math.sin(math.radians(theta_deg))
    if scene.normal_law == "hertz":
        model, t_c = _hertz(scene, contact, scene.v * sin_t)
    else:
        model, t_c = _linear(scene, contact)
    lines = _header(float(theta_deg), float(omega_in), float(partner_omega_in), contact)
    velocity = (scene.v * cos_t if theta_deg != 90.0 else 0.0, -scene.v * sin_t)
    lines += _bodies(contact, velocity, (float(omega_in), float(partner_omega_in)))
    lines += _law(model, contact, scene.inertia)
    lines += _run(contact, t_c / steps_per_contact, steps_per_contact)
    return "\n".join(lines) + "\n"


def _header(theta_deg: float, omega_in: float, partner_omega_in: float, contact: _Contact) -> list[str]:
    pair = len(contact.masses) == 2
    return [
        f"# restitution: one impact, theta_deg = {theta_deg!r} (from the "
        + (f"tangent), omega_in = {omega_in!r}, partner_omega_in = {partner_omega_in!r} rad/s" if pair
           else f"plate), omega_in = {omega_in!r} rad/s"),
        "# axes: " + ("the partner (atom 2) at rest at the origin, the particle (atom 1) above it at first touch"
                      if pair else "the plate is y = 0, the particle above it") + ", spin counter-clockwise about +z",
        "units si",
        f"dimension {3 if contact.sphere else 2}",
        "boundary p p p" if pair else "boundary p f p",
        "atom_style sphere",
        "atom_modify map array sort 0 0.0",
        "comm_modify vel yes",  # the granular pair reads its neighbour's velocity
    ]


def _bodies(contact: _Contact, velocity: tuple[float, float], spins: tuple[float, float]) -> list[str]:
    """The box, the particle touching the plate (or its partner) and their state."""
    reach = sum(contact.radii) if len(contact.radii) == 2 else contact.radii[0]
    box = 20.0 * reach  # the bodies move a fraction of a radius during the contact
    z = f"{-box!r} {box!r}" if contact.sphere else "-0.5 0.5"
    lines = [f"region box block {-box!r} {box!r} {-contact.radii[0]!r} {box!r} {z}",
             "create_box 1 box", f"create_atoms 1 single 0.0 {reach!r} 0.0"]
    if len(contact.radii) == 2:
        lines[0] = f"region box block {-box!r} {box!r} {-box!r} {box!r} {z}"
        lines.append("create_atoms 1 single 0.0 0.0 0.0")
    for k, (radius, mass) in enumerate(zip(contact.radii, contact.masses), start=1):
        lines += [f"set atom {k} diameter {2.0 * radius!r}", f"set atom {k} mass {mass!r}",
                  f"set atom {k} omega 0.0 0.0 {spins[k - 1]!r}"]
    lines += ["group particle id 1", "group partner id 2", f"velocity particle set {velocity[0]!r} {velocity[1]!r} 0.0"]
    return lines


def _law(model: list[str], contact: _Contact, inertia: str) -> list[str]:
    """The contact law: a wall for the plate, a granular pair for a partner; the integrator."""
    if len(contact.radii) == 2:
        lines = ["pair_style granular", f"pair_coeff * * {' '.join(model)} limit_damping",
                 f"neighbor {0.5 * min(contact.radii)!r} bin", "neigh_modify every 1 delay 0 check yes"]
    else:
        lines = [f"comm_modify cutoff {4.0 * contact.radii[0]!r}",
                 f"fix wall all wall/gran granular {' '.join(model)} limit_damping yplane 0.0 NULL"]
    lines.append("fix move all nve/sphere" + ("" if contact.sphere or inertia == "sphere" else " disc"))
    return lines + ([] if contact.sphere else ["fix flat all enforce2d"])


def _run(contact: _Contact, dt: float, steps_per_contact: int) -> list[str]:
    """The step, the run halted at separation, and the line :func:`restitution.lammps.simulate` reads."""
    if len(contact.radii) == 2:
        reach = sum(contact.radii)
        gap = [f"variable gap equal sqrt((x[1]-x[2])^2+(y[1]-y[2])^2)-{reach!r}",
               "variable opening equal ((x[1]-x[2])*(vx[1]-vx[2])+(y[1]-y[2])*(vy[1]-vy[2]))"
               f"/(v_gap+{reach!r})"]
    else:
        gap = [f"variable gap equal y[1]-{contact.radii[0]!r}", "variable opening equal vy[1]"]
    partner = (" partner_vx_out=$(vx[2]:%.17g) partner_vy_out=$(vy[2]:%.17g) partner_omega_out=$(c_partner_omega:%.17g)"
               if len(contact.radii) == 2 else "")
    return [
        f"timestep {dt!r}",
        "compute spin all property/atom omegaz",
        "compute omega particle reduce sum c_spin",
        "compute partner_omega partner reduce sum c_spin",
        *gap,
        "variable separated equal (v_gap>0.0)*(v_opening>0.0)",
        "fix halt all halt 1 v_separated > 0.5 error continue",
        "thermo_style custom step time",
        f"run {RUN_CONTACTS * steps_per_contact}",
        "run 0 post no",  # makes the spins' computes current for the print below
        'print "restitution: vx_out=$(vx[1]:%.17g) vy_out=$(vy[1]:%.17g) omega_out=$(c_omega:%.17g) '
        'contact_time=$(time-v_gap/v_opening:%.17g)' + partner + '"',
    ]
