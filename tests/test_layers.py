"""The package's modules form layers: no module imports a module that imports it back.

docs/architecture.md promises it ("no module imports a module that imports it back"); issue 40
found ``runs/sweep.py`` and ``runs/config.py`` importing each other (one of them inside a
function). Every import statement counts, at the top or inside a function, since either ties
the two modules' definitions together. Imports of a package's ``__init__`` (which re-exports
its modules' names) are not edges.
"""

from __future__ import annotations

import ast
from pathlib import Path

import restitution

ROOT = Path(restitution.__file__).parent


def _modules() -> dict[str, Path]:
    out = {}
    for f in ROOT.rglob("*.py"):
        parts = list(f.relative_to(ROOT.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            continue
        out[".".join(parts)] = f
    return out


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The package's modules that ``name`` imports anywhere in its source."""
    package = name.split(".")[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = ".".join(package[:len(package) - node.level + 1] + ([node.module] if node.module else [])) \
                if node.level else (node.module or "")
            for alias in node.names:
                target = f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                if target in modules:
                    out.add(target)
        elif isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names if alias.name in modules)
    return out - {name}


def _cycle(edges: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of ``edges`` (depth-first search), or None."""
    state: dict[str, int] = {}
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(edges[node]):
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        state[node] = 2
        path.pop()
        return None

    for node in sorted(edges):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_the_cycle_finder_finds_a_cycle() -> None:
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_no_module_imports_a_module_that_imports_it_back() -> None:
    modules = _modules()
    assert "restitution.runs.sweep" in modules and "restitution.runs.config" in modules
    edges = {name: _imports(name, path, modules) for name, path in modules.items()}
    assert "restitution.runs.sweep" in edges["restitution.runs.config"]  # the finder sees imports
    assert _cycle(edges) is None, f"import cycle: {' -> '.join(_cycle(edges) or [])}"
