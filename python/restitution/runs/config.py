"""Sweep configs: a TOML file (or the same structure as a dict) to a :class:`SweepSpec`, and back.

Layout (``examples/sweep_config.toml`` is a documented example)::

    [scene]                  # any Scene field; omitted fields keep the preset's value
    preset = "default"       # "default" (Scene(): exact disc) or "paper" (the study's 120-gon)
    mu = 0.5
    [scene.shape]            # replaces the preset's shape
    kind = "disc"            # "disc" (r) | "regular_polygon" (r, n, phi0_deg) | "convex_polygon" (vertices, phi0_deg)
    r = 0.01
    [scene.partner]          # optional: a second free particle instead of the plate (same kinds)
    kind = "disc"
    r = 0.01
    [axes]                   # first axis varies slowest; a value, a list, or a range
    theta_deg = { start = 4, stop = 89, step = 1 }     # stop included when on the grid
    omega_in = { start = -0.8, stop = 0.8, num = 5 }   # num points, both ends included
    mu = [0.0, 0.5, 1.0]
    [sweep]
    chunk_size = 4096        # cases per chunk file (the CLI's --chunk-size overrides it)
    cases = "cases.parquet"  # instead of [axes]: one impact per row (.parquet or .csv, relative to this file)

Every error is a ``ValueError`` of one line naming the key (``scene.mu``, ``axes.theta_deg.step``)
and what is allowed. The same structure, fully expanded (no preset, axes as explicit lists), is
what a dataset's manifest stores, so a resumed sweep can be compared key by key.
"""

from __future__ import annotations

import difflib
import math
import sys
from pathlib import Path
from typing import Any, Mapping

import polars as pl

from .._engine import CHOICES, is_real
from ..errors import RestitutionError
from ..scene import Scene
from ..shapes import ConvexPolygon, Disc, RegularPolygon, Sphere
from .sweep import AXES, SCENE_KEYS, SweepSpec, check_chunk_size, spec_to_dict

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

CHOICE_AXES = CHOICES
PRESETS = ("default", "paper")
SHAPE_KEYS = {"disc": ("r",), "sphere": ("r",), "regular_polygon": ("r", "n", "phi0_deg"), "convex_polygon": ("vertices", "phi0_deg")}
TOP_KEYS = ("scene", "axes", "sweep")
SWEEP_KEYS = ("chunk_size", "cases")
RANGE_KEYS = ("start", "stop", "step", "num")

#: Longest axis a range may expand to (a typo like step = 1e-9 should fail, not eat the memory).
MAX_AXIS_LEN = 10_000_000


class ConfigError(ValueError):
    """A bad config: one line naming the key and the allowed values."""


def load_config(path: str | Path) -> tuple[SweepSpec, int | None]:
    """Reads a TOML sweep config: (the spec, its ``[sweep] chunk_size`` or None)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError(f"{path}: cannot read the config ({err.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ConfigError(f"{path}: invalid TOML: {' '.join(str(err).split())}") from None
    return spec_from_dict(data, source=str(path), base_dir=path.parent)


def spec_from_dict(data: Mapping[str, Any], *, source: str = "config",
                   base_dir: Path | None = None) -> tuple[SweepSpec, int | None]:
    """The config structure (see the module doc) to (spec, chunk_size or None)."""
    fail = failer(source)
    _check_keys(data, TOP_KEYS, "", fail)
    scene, axes, cases, chunk = parts(data, fail, base_dir, axes_required=True)
    try:
        spec = SweepSpec(scene, axes=None if cases is not None else axes, cases=cases)
    except (ValueError, TypeError) as err:
        where = "sweep.cases" if cases is not None else _named_key("axes", err, axes)
        raise fail(where, str(err)) from None
    return spec, chunk


def failer(source: str) -> Any:
    """The error factory of one config: ``fail(key, msg)`` -> a one-line :class:`ConfigError`."""
    def fail(key: str, msg: str) -> ConfigError:
        msg = " ".join(msg.split())  # one line, whatever the wrapped error looked like
        return ConfigError(f"{source}: {key}: {msg}" if key else f"{source}: {msg}")

    return fail


def parts(data: Mapping[str, Any], fail: Any, base_dir: Path | None, *,
          axes_required: bool) -> tuple[Scene, dict[str, Any], pl.DataFrame | None, int | None]:
    """The [scene], [axes] and [sweep] tables: (scene, axes, cases table or None, chunk size or None)."""
    scene = _scene(_table(data, "scene", fail), fail)
    sweep_t = _table(data, "sweep", fail)
    _check_keys(sweep_t, SWEEP_KEYS, "sweep", fail)
    chunk = sweep_t.get("chunk_size")
    if chunk is not None:
        try:
            chunk = check_chunk_size(chunk)
        except ValueError:
            raise fail("sweep.chunk_size", f"require an integer >= 1 (found {chunk!r})") from None
    axes_t = _table(data, "axes", fail)
    cases = None
    if "cases" in sweep_t:
        if axes_t:
            raise fail("sweep.cases", "give either [axes] or sweep.cases, not both")
        cases = _read_cases(sweep_t["cases"], base_dir, fail)
    elif not axes_t and axes_required:
        raise fail("axes", f"require an [axes] table (with theta_deg) or sweep.cases; axes: {', '.join(AXES)}")
    for name in axes_t:
        if name not in AXES:
            raise fail(f"axes.{name}", f"unknown axis{_suggest(name, AXES)}; allowed: {', '.join(AXES)}")
    axes = {name: _axis_values(name, value, fail) for name, value in axes_t.items()}
    return scene, axes, cases, chunk


def _named_key(table: str, err: Exception, keys: Mapping[str, Any]) -> str:
    """``table.name`` when ``err`` names a parameter that is a key of ``table``, else ``table``."""
    name = err.parameter if isinstance(err, RestitutionError) else None
    return f"{table}.{name}" if name in keys else table


def _table(data: Mapping[str, Any], key: str, fail: Any) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise fail(key, f"require a table ([{key}]) (found {type(value).__name__})")
    return value


def _check_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str, fail: Any) -> None:
    for key in table:
        if key not in allowed:
            full = f"{where}.{key}" if where else key
            raise fail(full, f"unknown key{_suggest(key, allowed)}; allowed: {', '.join(allowed)}")


def _suggest(key: str, allowed: tuple[str, ...]) -> str:
    close = difflib.get_close_matches(key, allowed, n=1)
    return f" (did you mean `{close[0]}`?)" if close else ""


def _number(key: str, value: Any, fail: Any) -> float:
    if not is_real(value):
        raise fail(key, f"require a number (found {type(value).__name__} {value!r})")
    return float(value)


def _scene(table: dict[str, Any], fail: Any) -> Scene:
    _check_keys(table, ("preset", "shape") + SCENE_KEYS + ("partner",), "scene", fail)
    preset = table.get("preset", "default")
    if preset not in PRESETS:
        raise fail("scene.preset", f"require one of {', '.join(map(repr, PRESETS))} (found {preset!r})")
    fields: dict[str, Any] = {}
    for key in SCENE_KEYS:
        if key not in table:
            continue
        value = table[key]
        if key in CHOICES:
            if not isinstance(value, str):
                raise fail(f"scene.{key}", f"require a string (found {type(value).__name__} {value!r})")
            fields[key] = value
        else:
            fields[key] = _number(f"scene.{key}", value, fail)
    for key in ("shape", "partner"):
        if key in table:
            if not isinstance(table[key], dict):
                raise fail(f"scene.{key}", f"require a table ([scene.{key}]) with `kind`")
            fields[key] = _shape(table[key], fail, f"scene.{key}")
    try:
        return Scene.paper(**fields) if preset == "paper" else Scene(**fields)
    except (ValueError, TypeError) as err:
        raise fail(_named_key("scene", err, fields), str(err)) from None


def _shape(table: dict[str, Any], fail: Any, where: str = "scene.shape") -> Any:
    """The shape of the table at ``where`` ([scene.shape], or [scene.partner] for a pair)."""
    kind = table.get("kind")
    if kind not in SHAPE_KEYS:
        raise fail(f"{where}.kind", f"require one of {', '.join(map(repr, SHAPE_KEYS))} (found {kind!r})")
    allowed = SHAPE_KEYS[kind]
    _check_keys({k: v for k, v in table.items() if k != "kind"}, allowed, where, fail)
    args: dict[str, Any] = {}
    for key in allowed:
        if key not in table:
            continue
        value = table[key]
        if key == "n":
            if isinstance(value, bool) or not isinstance(value, int):
                raise fail(f"{where}.n", f"require an integer >= 3 (found {value!r})")
            args[key] = value
        elif key == "vertices":
            args[key] = value
        else:
            args[key] = _number(f"{where}.{key}", value, fail)
    if kind == "convex_polygon" and "vertices" not in args:
        raise fail(f"{where}.vertices", "require counter-clockwise [[x, y], ...] for a convex_polygon")
    cls = {"disc": Disc, "sphere": Sphere, "regular_polygon": RegularPolygon, "convex_polygon": ConvexPolygon}[kind]
    try:
        return cls(**args)
    except (ValueError, TypeError) as err:
        raise fail(where, str(err)) from None


def _axis_values(name: str, value: Any, fail: Any) -> Any:
    key = f"axes.{name}"
    if isinstance(value, dict):
        if name in CHOICE_AXES:
            raise fail(key, f"a range makes no sense for names; give a list of {', '.join(CHOICE_AXES[name])}")
        return _expand_range(key, value, integer=name == "n", fail=fail)
    values = value if isinstance(value, list) else [value]
    if not values:
        raise fail(key, "require at least one value")
    for v in values:
        if name in CHOICE_AXES:
            if v not in CHOICE_AXES[name]:
                raise fail(key, f"require values in {', '.join(map(repr, CHOICE_AXES[name]))} (found {v!r})")
        elif name == "n":
            if isinstance(v, bool) or not isinstance(v, int):
                raise fail(key, f"require integers: 0 (exact disc) or >= 3 (found {v!r})")
        else:
            _number(key, v, fail)
    return [float(v) for v in values] if name not in CHOICE_AXES and name != "n" else values


def _expand_range(key: str, rng: dict[str, Any], *, integer: bool, fail: Any) -> list[Any]:
    _check_keys(rng, RANGE_KEYS, key, fail)
    for k in ("start", "stop"):
        if k not in rng:
            raise fail(key, f"a range needs `start`, `stop` and one of `step`, `num` (missing `{k}`)")
    if ("step" in rng) == ("num" in rng):
        raise fail(key, "a range needs exactly one of `step` (spacing) or `num` (number of points)")
    start, stop = _number(f"{key}.start", rng["start"], fail), _number(f"{key}.stop", rng["stop"], fail)
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise fail(key, f"require finite `start` and `stop` (found {start}, {stop})")
    if stop < start:
        raise fail(f"{key}.stop", f"require stop >= start (found start {start}, stop {stop})")
    if "step" in rng:
        step = _number(f"{key}.step", rng["step"], fail)
        if not (math.isfinite(step) and step > 0.0):
            raise fail(f"{key}.step", f"require step > 0 (found {step})")
        # tolerance: stop is included when it lies on the grid up to rounding
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
    else:
        num = rng["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise fail(f"{key}.num", f"require an integer >= 1 (found {num!r})")
        if num == 1 and stop != start:
            raise fail(f"{key}.num", f"require num >= 2 when stop != start (found num 1, start {start}, stop {stop})")
        count = num
        step = (stop - start) / (num - 1) if num > 1 else 0.0
    if count > MAX_AXIS_LEN:
        raise fail(key, f"the range has {count} values; at most {MAX_AXIS_LEN} per axis")
    # start + k * step (no accumulated error), shown to 12 significant digits so that a 0.1
    # step gives 0.3 and not 0.30000000000000004; "num" ranges end exactly at stop.
    values = [float(f"{start + k * step:.12g}") for k in range(count)]
    if "num" in rng and count > 1:
        values[-1] = stop
    if integer:
        if any(v != int(v) for v in values):
            raise fail(key, "require integer start and step for `n` (0: exact disc, >= 3: n-gon)")
        return [int(v) for v in values]
    return values


def _read_cases(name: Any, base_dir: Path | None, fail: Any) -> pl.DataFrame:
    if not isinstance(name, str):
        raise fail("sweep.cases", f"require a file name (.parquet or .csv) (found {name!r})")
    path = Path(name) if base_dir is None or Path(name).is_absolute() else base_dir / name
    try:
        if path.suffix == ".parquet":
            return pl.read_parquet(path)
        if path.suffix == ".csv":
            return pl.read_csv(path)
    except (OSError, pl.exceptions.PolarsError) as err:
        raise fail("sweep.cases", f"cannot read {path}: {err}") from None
    raise fail("sweep.cases", f"require a .parquet or .csv file (found {name!r})")


__all__ = ["ConfigError", "load_config", "spec_from_dict", "spec_to_dict"]
