"""Shared fixtures: the scenes of docs/model.md that several test files start from."""

from __future__ import annotations

import pytest

import restitution as rs


@pytest.fixture
def disc_scene() -> rs.Scene:
    """The paper preset on an exact disc (``rs.Scene()``: r = 0.01 m, v = 0.0357 m/s, gamma = 0.33)."""
    return rs.Scene()


@pytest.fixture
def elastic_scene() -> rs.Scene:
    """mu = 0, gamma = 0 on an exact disc: the conservative limit (e_n = e_t = 1, energy conserved)."""
    return rs.Scene(mu=0.0, gamma=0.0)
