"""TOML sweep configs: ranges expand as documented, the example is valid, and every bad key,
value or range stops with one line naming the key and what is allowed (exit code 2)."""

from __future__ import annotations

import dataclasses

from pathlib import Path

import numpy as np
import pytest

import restitution as rs
from restitution.cli import main
from restitution import _engine
from restitution.runs.config import ConfigError, load_config, spec_from_dict, spec_to_dict
from restitution.runs.dataset import make_manifest
from restitution.runs.sweep import SweepSpec

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "sweep_config.toml"


def test_example_config_expands_as_documented() -> None:
    spec, chunk = load_config(EXAMPLE)
    assert chunk == 64
    assert spec.axis_names == ("omega_in", "theta_deg")
    np.testing.assert_array_equal(spec.axes["theta_deg"], np.arange(4.0, 90.0))  # stop 89 included
    np.testing.assert_allclose(spec.axes["omega_in"], np.linspace(-0.873, 0.873, 5), rtol=0, atol=1e-15)
    assert spec.n_cases == 5 * 86
    assert spec.scene == rs.Scene(mu=0.1, integrator="gear5", dt_factor=0.01, shape=rs.Disc(r=0.01))


def test_ranges_step_num_and_lists() -> None:
    spec, _ = spec_from_dict({"axes": {"theta_deg": {"start": 10, "stop": 30, "step": 10}, "mu": {"start": 0, "stop": 1, "step": 0.1},
                                       "n": {"start": 0, "stop": 6, "step": 3}, "gamma": {"start": 0.1, "stop": 0.3, "num": 3},
                                       "integrator": ["verlet"], "omega_in": 2}})
    assert spec.axes["theta_deg"].tolist() == [10.0, 20.0, 30.0]
    assert spec.axes["mu"].tolist() == [round(0.1 * k, 1) for k in range(11)]  # 0.3, not 0.30000000000000004
    assert spec.axes["n"].tolist() == [0, 3, 6]
    assert spec.axes["gamma"].tolist() == [0.1, 0.2, 0.3]
    assert spec.axis_values("integrator") == ["verlet"] and spec.axes["omega_in"].tolist() == [2.0]


def test_presets_shapes_and_round_trip() -> None:
    spec, _ = spec_from_dict({"scene": {"preset": "paper", "mu": 1}, "axes": {"theta_deg": 45}})
    assert spec.scene == rs.Scene.paper(mu=1.0)
    tri = [[0.0, 0.0], [0.02, 0.0], [0.0, 0.01]]
    for shape in ({"kind": "regular_polygon", "r": 0.02, "n": 7, "phi0_deg": 3.0},
                  {"kind": "convex_polygon", "vertices": tri, "phi0_deg": 0.0}):
        spec, _ = spec_from_dict({"scene": {"shape": shape}, "axes": {"theta_deg": [30.0, 60.0], "omega_in": [0.0]}})
        again, chunk = spec_from_dict(spec_to_dict(spec, 5))
        assert again.scene == spec.scene and chunk == 5
        assert spec_to_dict(again) == spec_to_dict(spec)


BAD = [
    ('[scene]\nmu = "a"\n[axes]\ntheta_deg = 30', "scene.mu: require a number (found str 'a')"),
    ("[scene]\nmuu = 0.1\n[axes]\ntheta_deg = 30", "scene.muu: unknown key (did you mean `mu`?); allowed: preset, shape, rho, E"),
    ("[scene]\nE = -1.0\n[axes]\ntheta_deg = 30", "scene.E: require `E` finite and > 0 (found -1.0)"),
    ('[scene]\npreset = "ppr"\n[axes]\ntheta_deg = 30', "scene.preset: require one of 'default', 'paper' (found 'ppr')"),
    ('[scene]\nintegrator = "rk4"\n[axes]\ntheta_deg = 30', 'scene.integrator: require `integrator` one of "gear5", "verlet"'),
    ('[scene.shape]\nkind = "square"\n[axes]\ntheta_deg = 30', "scene.shape.kind: require one of 'disc', 'sphere', 'regular_polygon', 'convex_polygon'"),
    ('[scene.shape]\nkind = "disc"\nn = 3\n[axes]\ntheta_deg = 30', "scene.shape.n: unknown key; allowed: r"),
    ('[scene.shape]\nkind = "regular_polygon"\nn = 2\n[axes]\ntheta_deg = 30', "scene.shape: require `n` >= 3 (found 2)"),
    ("[axes]\ntheta_deg = [0, 30]", "axes.theta_deg: case 0: require `theta_deg` in (0, 90] degrees"),
    ("[axes]\ntheta_deg = 30\nthetaa = 1", "axes.thetaa: unknown axis (did you mean `theta_deg`?); allowed: theta_deg, omega_in"),
    ('[axes]\ntheta_deg = 30\nintegrator = ["rk4"]', "axes.integrator: require values in 'gear5', 'verlet', 'reference', 'adaptive' (found 'rk4')"),
    ("[axes]\ntheta_deg = 30\nn = [0, 2]", "axes.n: case 1: require `n` an integer >= 3, or 0 for an exact disc (found 2.0)"),
    ("[axes]\ntheta_deg = 30\nn = [0.5]", "axes.n: require integers: 0 (exact disc) or >= 3 (found 0.5)"),
    ("[axes]\ntheta_deg = 30\nmu = []", "axes.mu: require at least one value"),
    ("[axes]\ntheta_deg = 30\ndt_factor = [0.6]\n[scene]\nintegrator = \"gear5\"",
     f"axes.dt_factor: case 0: require `dt_factor` in (0, {rs.MAX_DT_FACTOR['gear5']}] for the gear5 integrator"),
    ("[axes]\ntheta_deg = 30\ndt_factor = [20]\n[scene]\nintegrator = \"adaptive\"",
     "axes.dt_factor: case 0: require `dt_factor` in (0, 10] for the adaptive integrator"),
    ("[axes]\ntheta_deg = { start = 4, stop = 1, step = 1 }", "axes.theta_deg.stop: require stop >= start (found start 4.0, stop 1.0)"),
    ("[axes]\ntheta_deg = { start = 4, stop = 10, step = -1 }", "axes.theta_deg.step: require step > 0 (found -1.0)"),
    ("[axes]\ntheta_deg = { start = 4, stop = 10 }", "axes.theta_deg: a range needs exactly one of `step` (spacing) or `num`"),
    ("[axes]\ntheta_deg = { start = 4, stop = 10, stepp = 1 }", "axes.theta_deg.stepp: unknown key (did you mean `step`?); allowed: start, stop, step, num"),
    ("[axes]\ntheta_deg = { stop = 10, num = 3 }", "axes.theta_deg: a range needs `start`, `stop` and one of `step`, `num` (missing `start`)"),
    ("[axes]\ntheta_deg = { start = 4, stop = 10, num = 0 }", "axes.theta_deg.num: require an integer >= 1 (found 0)"),
    ("[axes]\ntheta_deg = { start = 1, stop = 89, step = 1e-9 }", "axes.theta_deg: the range has 88000000001 values; at most 10000000"),
    ("[axes]\ntheta_deg = 30\nn = { start = 3, stop = 4, step = 0.5 }", "axes.n: require integer start and step"),
    ('[axes]\ntheta_deg = 30\nnormal_law = { start = 0, stop = 1, step = 1 }', "axes.normal_law: a range makes no sense for names"),
    ("[sweep]\nchunk_size = 0\n[axes]\ntheta_deg = 30", "sweep.chunk_size: require an integer >= 1 (found 0)"),
    ("[sweep]\nchunks = 3\n[axes]\ntheta_deg = 30", "sweep.chunks: unknown key (did you mean `chunk_size`?); allowed: chunk_size, cases"),
    ('[sweep]\ncases = "c.parquet"\n[axes]\ntheta_deg = 30', "sweep.cases: give either [axes] or sweep.cases, not both"),
    ('[sweep]\ncases = "missing.parquet"', "sweep.cases: cannot read"),
    ("[scene]\nmu = 0.1", "axes: require an [axes] table (with theta_deg) or sweep.cases"),
    ("[axes]\nmu = 0.1", "axes: `theta_deg` is required"),
    ("foo = 1", "foo: unknown key; allowed: scene, axes, sweep"),
    ("[axes\ntheta_deg = 30", "invalid TOML: "),
]


@pytest.mark.parametrize(("text", "message"), BAD)
def test_config_errors_name_the_key_and_the_allowed_values(tmp_path: Path, text: str, message: str,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text + "\n")
    with pytest.raises(ConfigError) as info:
        load_config(cfg)
    assert str(info.value).startswith(f"{cfg}: ")
    assert message in str(info.value)
    assert main(["sweep", str(cfg), "--out", str(tmp_path / "never")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err
    assert not (tmp_path / "never").exists()


def test_cases_file_relative_to_the_config(tmp_path: Path) -> None:
    import polars as pl

    pl.DataFrame({"theta_deg": [30.0, 60.0], "mu": [0.0, 1.0]}).write_csv(tmp_path / "cases.csv")
    (tmp_path / "c.toml").write_text('[sweep]\ncases = "cases.csv"\n')
    spec, _ = load_config(tmp_path / "c.toml")
    assert spec.n_cases == 2 and spec.axis_names == ("theta_deg", "mu")
    (tmp_path / "d.toml").write_text('[sweep]\ncases = "cases.csv"\n[scene]\nmu = 0.5\n')
    pl.DataFrame({"theta_deg": [30.0, 95.0]}).write_csv(tmp_path / "cases.csv")
    with pytest.raises(ConfigError, match=r"sweep.cases: case 1: require `theta_deg` in \(0, 90\]"):
        load_config(tmp_path / "d.toml")


# --- every Scene field: a TOML key that round-trips and that the dataset digest sees -----------

#: Scenes a field is changed from: the default, one where the Hertz sphere's fields apply, and a
#: pair (where the partner's fields apply).
BASES = (rs.Scene(), rs.Scene(shape=rs.Sphere(r=0.0025), normal_law="hertz", E=3.8e11, rho=4000.0, nu=0.23,
                              cor=0.98, mu=0.092, v=3.9),
         rs.Scene(partner=rs.Disc(r=0.01)))


def _candidates(name: str, value: object) -> list[object]:
    """Values other than ``value`` to try, found generically so that a new field is covered."""
    if name == "shape":
        return [rs.RegularPolygon(r=0.01, n=12, phi0_deg=3.0), rs.Sphere(r=0.003)]
    if name == "partner":
        return [rs.Disc(r=0.02)]
    if isinstance(value, str):
        return [alt for alt in _engine.CHOICES[name] if alt != value]
    if value is None:
        return [0.3, 0.5, 1.0, 1e3, 0.5 * rs.Scene().E, 0.005]
    if isinstance(value, bool):
        return [not value]
    if isinstance(value, int):
        return [value * 2 if value else 1]
    return [float(value) * 0.5 if value else 0.1, float(value) * 1.5]


def _changed(name: str) -> tuple[rs.Scene, rs.Scene]:
    """(a base scene, the same with ``name`` changed to another valid value)."""
    for base in BASES:
        for alt in _candidates(name, getattr(base, name)):
            try:
                return base, base.replace(**{name: alt})
            except ValueError:
                continue
    raise AssertionError(f"no valid alternative value found for `{name}`: extend _candidates")


def _toml(value: object) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def _write_config(path: Path, scene: rs.Scene) -> Path:
    spec_dict = spec_to_dict(SweepSpec(scene, axes={"theta_deg": [30.0, 60.0]}))
    tables = {key: spec_dict["scene"].pop(key) for key in ("shape", "partner") if key in spec_dict["scene"]}
    lines = ["[scene]"] + [f"{k} = {_toml(v)}" for k, v in spec_dict["scene"].items()]
    for key, table in tables.items():
        lines += [f"[scene.{key}]"] + [f"{k} = {_toml(v)}" for k, v in table.items()]
    lines += ["[axes]", "theta_deg = [30.0, 60.0]"]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("name", [f.name for f in dataclasses.fields(rs.Scene)])
def test_every_scene_field_round_trips_through_toml_and_changes_the_digest(tmp_path: Path, name: str) -> None:
    default, changed = _changed(name)
    assert getattr(changed, name) != getattr(default, name)
    spec, _ = load_config(_write_config(tmp_path / "c.toml", changed))
    assert spec.scene == changed
    digests = {make_manifest(SweepSpec(s, axes={"theta_deg": [30.0, 60.0]}), 8)["spec_sha256"] for s in (default, changed)}
    assert len(digests) == 2, f"the dataset digest ignores `{name}`"
