"""Bad input is refused with an exception that names the parameter and its allowed range.

Every check here goes through the public API (Scene, shapes, simulate, sweep) and, at the end,
through the compiled engine directly: whatever slips past Python must come back as ValueError
or TypeError, never as a pyo3 PanicException (a BaseException that ``pytest.raises(ValueError)``
would not catch, so a panic fails these tests).
"""

from __future__ import annotations

import contextlib
import math
import pickle
from collections.abc import Iterator

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution import _core

NAN, INF = math.nan, math.inf

#: Scene fields and the allowed range their messages must state.
POSITIVE = ("rho", "E", "v", "kn", "kt")
NON_NEGATIVE = ("gamma", "gamma_t", "mu", "cn")


@contextlib.contextmanager
def raises_naming(exc: type[Exception], name: str, *fragments: str) -> Iterator[None]:
    """Expects ``exc`` (exactly that family) whose message holds `name` in backticks and every fragment."""
    with pytest.raises(exc) as info:
        yield
    message = str(info.value)
    for part in (f"`{name}`", *fragments):
        assert part in message, f"{part!r} missing from the message {message!r}"


# --- Scene fields -----------------------------------------------------------------------------

@pytest.mark.parametrize("name", POSITIVE)
@pytest.mark.parametrize("value", [NAN, INF, -INF, -1.0, 0.0, np.float64(NAN)])
def test_positive_fields_refuse_bad_values(name: str, value: float) -> None:
    with raises_naming(ValueError, name, "> 0"):
        rs.Scene(**{name: value})


@pytest.mark.parametrize("name", NON_NEGATIVE)
@pytest.mark.parametrize("value", [NAN, INF, -INF, -1e-12, -1.0])
def test_non_negative_fields_refuse_bad_values(name: str, value: float) -> None:
    with raises_naming(ValueError, name, ">= 0"):
        rs.Scene(**{name: value})


@pytest.mark.parametrize("name", NON_NEGATIVE)
def test_zero_is_allowed_where_documented(name: str) -> None:
    assert getattr(rs.Scene(**{name: 0.0}), name) == 0.0


@pytest.mark.parametrize("name", POSITIVE + NON_NEGATIVE + ("dt_factor",))
@pytest.mark.parametrize("value", ["1", True, [1.0], 1 + 0j])
def test_fields_refuse_wrong_types(name: str, value: object) -> None:
    # bool is an int in Python, but `mu=True` is a mistake, never a coefficient.
    with raises_naming(TypeError, name):
        rs.Scene(**{name: value})


@pytest.mark.parametrize("name", ("rho", "E", "v", "gamma", "gamma_t", "mu"))
def test_required_fields_refuse_none(name: str) -> None:
    with raises_naming(TypeError, name):
        rs.Scene(**{name: None})


@pytest.mark.parametrize(("integrator", "default"), [("gear5", 0.01), ("verlet", 0.01), ("reference", 0.01),
                                                     ("adaptive", 1.0)])
def test_dt_factor_none_is_the_integrators_default(integrator: str, default: float) -> None:
    # None: the fixed steps' 0.01 t_ref; the adaptive path's largest step 1 t_ref (its tol sets the steps).
    unset = rs.simulate(rs.Scene(integrator=integrator, mu=0.3), theta_deg=40.0)
    given = rs.simulate(rs.Scene(integrator=integrator, mu=0.3, dt_factor=default), theta_deg=40.0)
    assert unset.as_dict() == given.as_dict()
    with raises_naming(ValueError, "dt_factor", "None for the default"):
        rs.Scene(integrator=integrator, dt_factor=NAN)


@pytest.mark.parametrize("integrator", ["gear5", "verlet", "reference", "adaptive"])
@pytest.mark.parametrize("factor", [INF, -1.0, 0.0, 1.0001, 2.0, 100.0])
def test_dt_factor_names_the_integrators_bound(integrator: str, factor: float) -> None:
    bound = rs.MAX_DT_FACTOR[integrator]
    bad = bound * factor if factor > 1.0 else factor  # above the bound, or not positive/finite
    with raises_naming(ValueError, "dt_factor", f"(0, {bound:g}]", integrator):
        rs.Scene(integrator=integrator, dt_factor=bad)


@pytest.mark.parametrize("integrator", ["gear5", "verlet", "reference", "adaptive"])
def test_dt_factor_at_the_bound_is_accepted(integrator: str) -> None:
    bound = rs.MAX_DT_FACTOR[integrator]
    assert rs.Scene(integrator=integrator, dt_factor=bound).dt_factor == bound


@pytest.mark.parametrize(("name", "value"), [("integrator", "rk4"), ("integrator", "Gear5"),
                                             ("normal_law", "hooke"), ("inertia", "cube")])
def test_choices_list_the_allowed_names(name: str, value: str) -> None:
    with raises_naming(ValueError, name, f"found {value!r}"):
        rs.Scene(**{name: value})


def test_sphere_inertia_is_for_discs_only() -> None:
    assert rs.Scene(inertia="sphere").inertia == "sphere"
    with raises_naming(ValueError, "inertia", "sphere"):
        rs.Scene(inertia="sphere", shape=rs.RegularPolygon(r=0.01, n=6))


def test_shape_must_be_a_shape() -> None:
    with raises_naming(TypeError, "shape"):
        rs.Scene(shape=0.01)  # type: ignore[arg-type]


def test_scene_is_keyword_only_and_frozen() -> None:
    with pytest.raises(TypeError):
        rs.Scene(rs.Disc(0.01))  # type: ignore[misc]
    scene = rs.Scene()
    with pytest.raises(AttributeError):
        scene.mu = 1.0  # type: ignore[misc]


def test_replace_validates_and_leaves_the_original() -> None:
    scene = rs.Scene(mu=0.2)
    assert scene.replace(mu=1.0).mu == 1.0 and scene.mu == 0.2
    with raises_naming(ValueError, "mu", ">= 0"):
        scene.replace(mu=-0.1)


def test_the_kept_engine_row_is_the_scenes_values() -> None:
    # simulate() reads the row kept at construction: it must follow replace() and pickling.
    def row_of(scene: rs.Scene) -> list[float]:
        return [scene.engine_values()[name] for name in _core.CASE_COLUMNS]

    base = rs.Scene(mu=0.2, kt=None)
    verts = [(0.0, 0.0), (0.02, 0.0), (0.0, 0.01)]
    for scene in (base, base.replace(mu=0.7, integrator="adaptive"), rs.Scene.paper(),
                  rs.Scene(shape=rs.ConvexPolygon(verts), mu=0.3), pickle.loads(pickle.dumps(base))):
        np.testing.assert_array_equal(scene._engine_row(), row_of(scene))
    old = pickle.loads(pickle.dumps(base))
    del old.__dict__["_row"]  # as unpickled from a version that did not keep the row
    np.testing.assert_array_equal(old._engine_row(), row_of(base))


def test_defaults_are_the_paper_preset_of_model_md() -> None:
    s = rs.Scene()
    assert s.shape == rs.Disc(r=0.01)
    assert (s.rho, s.E, s.gamma, s.gamma_t, s.mu, s.v) == (2500.0, 1e7, 0.33, 0.5, 0.5, 0.0357)
    # The adaptive path to tol 1e-6 (dt_factor None: its default largest step, 1 t_ref).
    assert (s.integrator, s.dt_factor, s.tol, s.normal_law, s.inertia) == ("adaptive", None, 1e-6, "area", "shape")
    # Scene.paper(): the study's 120-gon and the study's method, Gear-5 at its 0.01 t_ref.
    p = rs.Scene.paper()
    assert p.shape == rs.RegularPolygon(r=0.01, n=120, phi0_deg=0.0) and p.integrator == "gear5"
    assert p.replace(shape=rs.Disc(r=0.01)) == s.replace(integrator="gear5")
    assert rs.Scene.paper(shape=rs.Disc(r=0.01), mu=1.0) == s.replace(mu=1.0, integrator="gear5")
    assert rs.Scene.paper(integrator="adaptive").integrator == "adaptive"


# --- Shapes -----------------------------------------------------------------------------------

@pytest.mark.parametrize("r", [0.0, -0.01, NAN, INF])
@pytest.mark.parametrize("make", [rs.Disc, lambda r: rs.RegularPolygon(r=r, n=6)])
def test_shapes_refuse_bad_radius(make, r: float) -> None:
    with raises_naming(ValueError, "r", "> 0"):
        make(r)


@pytest.mark.parametrize("n", [2, 1, 0, -3])
def test_regular_polygon_needs_three_corners(n: int) -> None:
    with raises_naming(ValueError, "n", ">= 3"):
        rs.RegularPolygon(r=0.01, n=n)


@pytest.mark.parametrize("n", [6.0, 3.5, "6", True, None])
def test_regular_polygon_needs_an_integer_n(n: object) -> None:
    with raises_naming(TypeError, "n", "integer"):
        rs.RegularPolygon(r=0.01, n=n)  # type: ignore[arg-type]


@pytest.mark.parametrize("phi", [NAN, INF])
def test_orientation_must_be_finite(phi: float) -> None:
    with raises_naming(ValueError, "phi0_deg", "finite"):
        rs.RegularPolygon(r=0.01, n=6, phi0_deg=phi)
    with raises_naming(ValueError, "phi0_deg", "finite"):
        rs.ConvexPolygon([(0, 0), (1, 0), (0, 1)], phi0_deg=phi)


SQUARE = [(0.0, 0.0), (0.02, 0.0), (0.02, 0.02), (0.0, 0.02)]


@pytest.mark.parametrize(("vertices", "fragment"), [
    (SQUARE[::-1], "counter-clockwise"),                                            # clockwise
    ([(0, 0), (0.02, 0), (0.01, 0.005), (0.02, 0.02), (0, 0.02)], "convex"),        # a dent
    ([(0, 0), (0.02, 0), (0.02, 0), (0.02, 0.02), (0, 0.02)], "distinct"),          # repeated vertex
    ([(0, 0), (0.01, 0), (0.02, 0), (0.02, 0.02), (0, 0.02)], "collinear"),         # straight angle
    ([(0, 0), (0.01, 0), (0.02, 0)], "counter-clockwise"),                          # zero area
    ([(0, 0), (0.02, NAN), (0, 0.02)], "finite"),
    ([(0, 0), (INF, 0), (0, 0.02)], "finite"),
    # a pentagram: every turn is left, but it winds twice
    ([(math.cos(a), math.sin(a)) for a in np.arange(5) * 4 * math.pi / 5], "simple"),
])
def test_convex_polygon_refuses_bad_vertices(vertices, fragment: str) -> None:
    with raises_naming(ValueError, "vertices", fragment):
        rs.ConvexPolygon(vertices)


@pytest.mark.parametrize("vertices", [
    np.zeros((3, 3)), np.zeros(6), np.zeros((2, 2)), np.zeros((0, 2)), np.zeros((3, 2, 1)),
])
def test_convex_polygon_refuses_wrong_array_shapes(vertices: np.ndarray) -> None:
    with raises_naming(ValueError, "vertices"):
        rs.ConvexPolygon(vertices)


@pytest.mark.parametrize("vertices", ["abc", [(0, 0), (1, 0), (1,)], [(0, 0), ("a", 0), (0, 1)]])
def test_convex_polygon_refuses_non_numbers(vertices) -> None:
    with raises_naming(TypeError, "vertices"):
        rs.ConvexPolygon(vertices)


def test_convex_polygon_is_centred_and_sized_by_its_farthest_vertex() -> None:
    # A right triangle: centroid at (a/3, a/3), farthest vertex at distance sqrt(5) a / 3.
    a = 0.03
    tri = rs.ConvexPolygon([(0, 0), (a, 0), (0, a)])
    assert tri.r == pytest.approx(math.sqrt(5) * a / 3, rel=1e-14)
    assert tri.n == 3
    sq = rs.ConvexPolygon(np.array(SQUARE) + 5.0)  # position in the body frame does not matter
    assert sq.r == pytest.approx(0.01 * math.sqrt(2), rel=1e-12)


# --- simulate's own arguments -----------------------------------------------------------------

@pytest.mark.parametrize("theta", [0.0, -1.0, -90.0, 90.0 + 1e-9, 91.0, 180.0, NAN, INF, -INF])
def test_theta_outside_0_90_is_refused(disc_scene: rs.Scene, theta: float) -> None:
    with raises_naming(ValueError, "theta_deg", "(0, 90]"):
        rs.simulate(disc_scene, theta_deg=theta)


@pytest.mark.parametrize("theta", ["45", None, [45.0]])
def test_theta_of_the_wrong_type_is_refused(disc_scene: rs.Scene, theta: object) -> None:
    with raises_naming(TypeError, "theta_deg"):
        rs.simulate(disc_scene, theta_deg=theta)  # type: ignore[arg-type]


@pytest.mark.parametrize("omega", [NAN, INF, -INF])
def test_omega_in_must_be_finite(disc_scene: rs.Scene, omega: float) -> None:
    with raises_naming(ValueError, "omega_in", "finite"):
        rs.simulate(disc_scene, theta_deg=45.0, omega_in=omega)


def test_simulate_needs_a_scene() -> None:
    with raises_naming(TypeError, "scene"):
        rs.simulate({"mu": 0.5}, theta_deg=45.0)  # type: ignore[arg-type]


def test_a_scene_the_law_cannot_describe_names_v_and_E() -> None:
    # docs/model.md, section 8: an estimated maximal depth above r / 2 is refused, naming v and E.
    with pytest.raises(ValueError, match=r"(?s)`v`.*E"):
        rs.simulate(rs.Scene(v=50.0), theta_deg=90.0)


# --- sweep axes ---------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["theta_deg", "mu", "omega_in", "gamma"])
def test_sweep_refuses_2d_axes(disc_scene: rs.Scene, name: str) -> None:
    axes = {"theta_deg": 45.0, name: np.full((2, 2), 30.0 if name == "theta_deg" else 0.1)}
    with raises_naming(ValueError, name, "1-D"):
        rs.sweep(disc_scene, **axes)


@pytest.mark.parametrize(("name", "values", "fragment"), [
    ("theta_deg", [30.0, 0.0], "(0, 90]"),
    ("theta_deg", [30.0, 95.0], "(0, 90]"),
    ("theta_deg", [30.0, NAN], "(0, 90]"),
    ("mu", [0.1, -0.5], ">= 0"),
    ("mu", [0.1, INF], "finite"),
    ("gamma", [-1.0], ">= 0"),
    ("gamma_t", [NAN], "finite"),
    ("omega_in", [0.0, NAN], "finite"),
    ("v", [0.0357, 0.0], "> 0"),
    ("E", [-1e7], "> 0"),
    ("rho", [0.0], "> 0"),
    ("r", [0.01, -0.01], "> 0"),
    ("kt", [0.0], "> 0"),
    ("dt_factor", [0.0], "(0, "),
    ("dt_factor", [0.01, 1e3], "(0, 10] for the adaptive integrator"),
    ("n", [6, 2], ">= 3"),
    ("integrator", ["gear5", "rk4"], "gear5"),
    ("normal_law", ["hooke"], "area"),
    ("theta_deg", [], "non-empty"),
    ("mu", [], "non-empty"),
])
def test_sweep_names_the_axis_with_a_bad_value(disc_scene: rs.Scene, name: str, values: list, fragment: str) -> None:
    axes = {"theta_deg": 45.0, name: values}
    with raises_naming(ValueError, name, fragment):
        rs.sweep(disc_scene, **axes)


@pytest.mark.parametrize(("name", "values"), [("theta_deg", ["a"]), ("mu", [{"x": 1}]), ("n", [6.0])])
def test_sweep_axes_of_the_wrong_type(disc_scene: rs.Scene, name: str, values: list) -> None:
    with raises_naming(TypeError, name):
        rs.sweep(disc_scene, **{"theta_deg": 45.0, name: values})


def test_sweep_refuses_unknown_axes_and_lists_the_allowed(disc_scene: rs.Scene) -> None:
    with raises_naming(ValueError, "friction", "theta_deg", "omega_in", "mu"):
        rs.sweep(disc_scene, theta_deg=[45.0], friction=[0.1])
    with raises_naming(ValueError, "theta_deg", "required"):
        rs.sweep(disc_scene, mu=[0.1])


def test_sweep_n_axis_is_refused_for_a_convex_polygon() -> None:
    scene = rs.Scene(shape=rs.ConvexPolygon(SQUARE))
    with raises_naming(ValueError, "n", "ConvexPolygon"):
        rs.sweep(scene, theta_deg=45.0, n=[4, 6])


def test_cases_frame_with_unknown_or_missing_columns(disc_scene: rs.Scene) -> None:
    with pytest.raises(ValueError, match=r"(?s)not axes.*'friction'.*allowed"):
        rs.sweep(disc_scene, cases=pl.DataFrame({"theta_deg": [30.0], "friction": [0.3]}))
    with raises_naming(ValueError, "theta_deg"):
        rs.sweep(disc_scene, cases=pl.DataFrame({"mu": [0.3]}))
    with raises_naming(ValueError, "theta_deg", "(0, 90]"):
        rs.sweep(disc_scene, cases=pl.DataFrame({"theta_deg": [30.0, None]}))
    with raises_naming(ValueError, "mu", ">= 0"):
        rs.sweep(disc_scene, cases=pl.DataFrame({"theta_deg": [30.0, 40.0], "mu": [0.1, -0.1]}))
    with pytest.raises(ValueError, match="either `cases` or axes"):
        rs.sweep(disc_scene, cases=pl.DataFrame({"theta_deg": [30.0]}), mu=[0.1])
    with raises_naming(TypeError, "cases"):
        rs.sweep(disc_scene, cases={"theta_deg": [30.0]})  # type: ignore[arg-type]


@pytest.mark.parametrize("threads", [0, -1, 1.5, True, "2"])
def test_sweep_threads_must_be_a_positive_integer(disc_scene: rs.Scene, threads: object) -> None:
    with raises_naming(ValueError, "threads", "in [1, 4096]"):
        rs.sweep(disc_scene, theta_deg=45.0, threads=threads)  # type: ignore[arg-type]


# --- the compiled engine, bypassing the Python checks --------------------------------------------

def _columns(**override: np.ndarray) -> dict[str, np.ndarray]:
    cols = {k: np.array([v]) for k, v in rs.Scene().engine_values().items()}
    cols["theta_deg"] = np.array([45.0])
    cols.update(override)
    return cols


LINEAR = np.array([float(_core.CHOICES["normal_law"].index("linear"))])

ENGINE_BAD = [(name, value) for name in ("theta_deg", "omega_in", "v", "mu", "gamma", "gamma_t", "E", "rho",
                                          "r", "phi0_deg", "dt_factor", "kt")
              for value in (NAN, INF, -1.0, 0.0)
              if not (name in ("omega_in", "phi0_deg") and value in (-1.0, 0.0))
              and not (name in ("mu", "gamma", "gamma_t") and value == 0.0)
              and not (name in ("kt", "dt_factor") and value != value)]  # NaN: the engine's default


def _row(**override: float) -> list[float]:
    """The one-case entries' row: ``_columns`` as a value per ``CASE_COLUMNS`` name, in order."""
    cols = _columns(**{name: np.array([value]) for name, value in override.items()})
    return [float(cols[name][0]) for name in _core.CASE_COLUMNS]


@pytest.mark.parametrize(("name", "value"), ENGINE_BAD)
def test_engine_refuses_what_python_would_have(name: str, value: float) -> None:
    with pytest.raises(rs.RestitutionError, match="require") as info:
        _core.run_cases(_columns(**{name: np.array([value])}), None, 1)
    assert info.value.parameter == name and info.value.case == 0
    with pytest.raises(rs.RestitutionError, match="require"):
        _core.check_cases(_columns(**{name: np.array([value])}), None)
    for one_case in (_core.run_case, _core.trace_case):
        with pytest.raises(rs.RestitutionError, match="require") as info:
            one_case(_row(**{name: value}), None)
        assert info.value.parameter == name


@pytest.mark.parametrize(("name", "value"), [("kn", 0.0), ("kn", INF), ("cn", -1.0), ("cn", INF)])
def test_engine_checks_the_linear_law_parameters(name: str, value: float) -> None:
    with pytest.raises(rs.RestitutionError, match=f"`{name}`"):
        _core.run_cases(_columns(normal_law=LINEAR, **{name: np.array([value])}), None, 1)


@pytest.mark.parametrize(("override", "vertices"), [
    ({"n": np.array([2.0])}, None),
    ({"n": np.array([-7.0])}, None),
    ({"n": np.array([3.5])}, None),
    ({"integrator": np.array([9.0])}, None),
    ({"integrator": np.array([0.5])}, None),
    ({"n": np.array([6.0]), "inertia": np.array([1.0])}, None),
    ({"normal_law": np.array([7.0])}, None),
    ({"inertia": np.array([-1.0])}, None),
    ({"overlap": np.array([NAN])}, None),
    ({"mu": np.array([0.1, 0.2])}, None),          # length mismatch
    ({"mu": np.array([[0.1]])}, None),             # 2-D column
    ({"n": np.array([0])}, None),                  # wrong dtype
    ({"theta_deg": np.array([45])}, None),         # wrong dtype
    ({}, np.zeros((3, 3))),
    ({}, np.zeros((3, 2))),                        # coinciding vertices
    ({}, np.full((3, 2), NAN)),
    ({}, np.zeros((1, 2))),
    ({}, np.zeros((0, 2))),
    ({}, np.array([[0.0, 1.0], [1.0, 0.0], [0.0, -1.0]])),  # clockwise
])
def test_engine_never_panics_on_malformed_input(override, vertices) -> None:
    with pytest.raises((ValueError, TypeError)):
        _core.run_cases(_columns(**override), vertices, 1)


def test_engine_reports_a_missing_column() -> None:
    cols = _columns()
    del cols["mu"]
    with pytest.raises(KeyError, match="mu"):
        _core.run_cases(cols, None, 1)


def test_one_case_entries_take_one_row_of_every_column() -> None:
    row = _row()
    for one_case in (_core.run_case, _core.trace_case):
        for bad in (row[:-1], [*row, 0.0]):
            with pytest.raises((ValueError, TypeError)):
                one_case(bad, None)
        with pytest.raises(TypeError):
            one_case([*row[:-1], "x"], None)
    with pytest.raises(ValueError, match="require"):
        _core.trace_case(_row(theta_deg=NAN), None)
    # The row's values are the columns' row: the same record either way.
    columns = _core.run_cases(_columns(), None, 1)

    def first(name: str) -> object:
        valid = columns.get(f"{name}_valid")
        value = columns[name][0]
        if valid is not None and not valid[0]:
            return None
        return value.item() if isinstance(value, np.generic) else value

    assert _core.run_case(row, None) == tuple(first(name) for name in _core.RECORD_COLUMNS)


def test_engine_max_dt_factor_matches_the_python_bounds() -> None:
    for code, (name, bound) in enumerate(rs.MAX_DT_FACTOR.items()):
        assert _core.CHOICES["integrator"][code] == name
        assert _core.max_dt_factor_for(_columns(integrator=np.array([float(code)])), None)[0][0] == bound
    with raises_naming(ValueError, "integrator"):
        _core.max_dt_factor_for(_columns(integrator=np.array([7.0])), None)
