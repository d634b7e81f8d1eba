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
    Field("v", "`velocity all set`", "v (cos theta, -sin theta, 0); theta_deg from the plate"),
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
    Field("theta_deg, omega_in", "`velocity all set`, `set atom 1 omega 0 0`", "project axes: the plate "
          "is `yplane 0.0 NULL`, x along it, spin about +z (counter-clockwise positive)"),
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
    "partner": "None (the plate): a partner body is not written yet",
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


def _moduli(scene: Any) -> tuple[float, float]:
    """E* and G* of the sphere on its plate (docs/model.md, 14.2 and 14.4)."""
    nu = scene.nu
    inv_e = (1.0 - nu * nu) / scene.E
    inv_g = (2.0 - nu) * 2.0 * (1.0 + nu) / scene.E
    if scene.plate_E is not None:
        nup = scene.plate_nu
        inv_e += (1.0 - nup * nup) / scene.plate_E
        inv_g += (2.0 - nup) * 2.0 * (1.0 + nup) / scene.plate_E
    return 1.0 / inv_e, 1.0 / inv_g


def _body(scene: Any) -> tuple[bool, float, float]:
    """(a sphere, its mass, its moment of inertia), as the engine takes them."""
    r, sphere = scene.r, isinstance(scene.shape, Sphere)
    mass = (4.0 / 3.0 * math.pi * r**3 if sphere else math.pi * r * r) * scene.rho
    kappa = 0.5 if (not sphere and scene.inertia == "shape") else 0.4
    return sphere, mass, kappa * mass * r * r


def _hertz(scene: Any, mass: float, v_n: float) -> tuple[list[str], float]:
    """The Hertz law's normal and tangential model words, and the contact time."""
    e_star, g_star = _moduli(scene)
    beta = _core.hertz_beta(scene.cor)
    if beta >= 1.0:
        raise _refuse("cor", scene.cor)
    e_lammps = math.exp(-math.pi * beta / math.sqrt(1.0 - beta * beta))
    delta_max = (15.0 * mass * v_n * v_n / (16.0 * e_star * math.sqrt(scene.r))) ** 0.4
    words = [f"hertz {4.0 / 3.0 * e_star!r} {e_lammps!r} damping coeff_restitution"]
    if scene.tangential == "linear":
        if scene.gamma_t != 0.0 and scene.mu != 0.0:
            raise _refuse("gamma_t", scene.gamma_t)
        words.append(f"tangential linear_history {scene.kt!r} 0.0 {scene.mu!r}")
    else:
        history = "mindlin/force" if scene.tangential_history == "auto" else scene.tangential_history
        words.append(f"tangential {history} {8.0 * g_star!r} {2.0 * math.sqrt(g_star / e_star)!r} {scene.mu!r}")
    return words, HERTZ_TIME * delta_max / v_n


def _linear(scene: Any, mass: float, inertia: float) -> tuple[list[str], float]:
    """The linear law's normal and tangential model words, and the contact time (undamped)."""
    kn = scene.kn if scene.kn is not None else scene.E
    cn = scene.cn if scene.cn is not None else 0.0
    kt = scene.kt if scene.kt is not None else 2.0 / 7.0 * kn
    m_t = 1.0 / (1.0 / mass + scene.r**2 / inertia)
    c_t = scene.gamma_t * math.sqrt(kt * m_t)
    if c_t != 0.0 and cn == 0.0 and scene.mu != 0.0:
        raise _refuse("gamma_t", scene.gamma_t)
    x_t = c_t / cn if cn > 0.0 else 0.0
    words = [f"hooke {kn!r} {cn!r} damping velocity", f"tangential linear_history {kt!r} {x_t!r} {scene.mu!r}"]
    return words, math.pi * math.sqrt(mass / kn)


def write(scene: Any, theta_deg: float, omega_in: float = 0.0, steps_per_contact: int | None = None) -> str:
    """The LAMMPS input script of one impact of ``scene`` (see ``Scene.to_lammps``); None
    steps: :data:`STEPS_PER_CONTACT`."""
    steps_per_contact = STEPS_PER_CONTACT if steps_per_contact is None else steps_per_contact
    _core.check_theta(float(theta_deg))
    if not math.isfinite(omega_in):
        raise RestitutionError("omega_in", omega_in, "finite (rad/s)")
    if scene.partner is not None:
        raise _refuse("partner", type(scene.partner).__name__)
    if not isinstance(scene.shape, (Sphere, Disc)):
        raise _refuse("shape", type(scene.shape).__name__)
    if scene.normal_law == "area":
        raise _refuse("normal_law", scene.normal_law)
    if isinstance(steps_per_contact, bool) or not isinstance(steps_per_contact, int) or steps_per_contact < 10:
        raise RestitutionError("steps_per_contact", steps_per_contact, "a whole number >= 10")
    sphere, mass, inertia = _body(scene)
    cos_t, sin_t = math.cos(math.radians(theta_deg)), math.sin(math.radians(theta_deg))
    if scene.normal_law == "hertz":
        model, t_c = _hertz(scene, mass, scene.v * sin_t)
    else:
        model, t_c = _linear(scene, mass, inertia)
    dt = t_c / steps_per_contact
    return _render(scene, sphere, mass, model, dt, steps_per_contact, float(theta_deg), float(omega_in),
                   (scene.v * cos_t if theta_deg != 90.0 else 0.0, -scene.v * sin_t))


def _render(scene: Any, sphere: bool, mass: float, model: list[str], dt: float, steps_per_contact: int,
            theta_deg: float, omega_in: float, velocity: tuple[float, float]) -> str:
    """The script's lines: the particle, the wall, the integrator, the run to separation and the
    line :func:`restitution.lammps.simulate` reads."""
    r = scene.r
    box = 1000.0 * r
    nve = "fix move all nve/sphere" + ("" if sphere or scene.inertia == "sphere" else " disc")
    lines = [
        f"# restitution: one impact, theta_deg = {theta_deg!r} (from the plate), omega_in = {omega_in!r} rad/s",
        "# axes: the plate is y = 0, the particle above it, spin counter-clockwise about +z",
        "units si",
        f"dimension {3 if sphere else 2}",
        "boundary p f p",
        "atom_style sphere",
        "atom_modify map array",
        f"region box block {-box!r} {box!r} {-r!r} {box!r} " + (f"{-box!r} {box!r}" if sphere else "-0.5 0.5"),
        "create_box 1 box",
        f"create_atoms 1 single 0.0 {r!r} 0.0",
        f"set atom 1 diameter {2.0 * r!r}",
        f"set atom 1 mass {mass!r}",
        f"velocity all set {velocity[0]!r} {velocity[1]!r} 0.0",
        f"set atom 1 omega 0.0 0.0 {omega_in!r}",
        f"comm_modify cutoff {4.0 * r!r}",
        f"fix wall all wall/gran granular {' '.join(model)} limit_damping yplane 0.0 NULL",
        nve,
        *([] if sphere else ["fix flat all enforce2d"]),
        f"timestep {dt!r}",
        "compute spin all property/atom omegaz",
        "compute omega all reduce sum c_spin",
        f"variable separated equal (y[1]>{r!r})*(vy[1]>0.0)",
        "fix halt all halt 1 v_separated > 0.5 error continue",
        "thermo_style custom step time",
        f"run {RUN_CONTACTS * steps_per_contact}",
        "run 0 post no",  # makes the spin's compute current for the print below
        f'print "restitution: vx_out=$(vx[1]:%.17g) vy_out=$(vy[1]:%.17g) omega_out=$(c_omega:%.17g) '
        f'contact_time=$(time-(y[1]-{r!r})/vy[1]:%.17g)"',
    ]
    return "\n".join(lines) + "\n"
