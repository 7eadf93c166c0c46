"""The packages depend on each other in one direction only: sim_plant and ffr_link at the bottom,
hil_bridge on ffr_link, harness on all three. Every import counts, the lazy ones inside functions
too: a circle between packages makes each change to one ripple through the other."""

from __future__ import annotations

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PACKAGES = ("sim_plant", "ffr_link", "hil_bridge", "harness")


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    out: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.add(node.module.split(".")[0])
    return out


def package_graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {}
    for pkg in PACKAGES:
        deps: set[str] = set()
        for f in (REPO / pkg).rglob("*.py"):
            deps |= _imports(f)
        graph[pkg] = (deps & set(PACKAGES)) - {pkg}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n: str) -> list[str] | None:
        state[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in state and (c := visit(m)) is not None:
                return c
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state and (c := visit(n)) is not None:
            return c
    return None


def test_the_cycle_finder_finds_a_circle() -> None:
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_no_circle_between_the_packages() -> None:
    graph = package_graph()
    assert _cycle(graph) is None, f"import circle: {' -> '.join(_cycle(graph) or [])}"


def test_the_bottom_packages_import_no_other_package() -> None:
    graph = package_graph()
    assert graph["sim_plant"] == set()
    assert graph["ffr_link"] == set()
    assert graph["hil_bridge"] == {"ffr_link"}
