"""The packages depend on each other in one direction only: sim_plant and ffr_firmware at the
bottom, ffr_link on ffr_firmware (where our firmware's build is), hil_bridge on those two, harness
on all. Every import counts, the lazy ones inside functions
too: a circle between packages makes each change to one ripple through the other."""

from __future__ import annotations

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
# package -> its directory (the firmware's C tree ships as the package ffr_firmware)
DIRS = {"sim_plant": "sim_plant", "ffr_firmware": "firmware", "ffr_link": "ffr_link", "hil_bridge": "hil_bridge",
        "harness": "harness"}
PACKAGES = tuple(DIRS)


def _imports(path: Path) -> set[str]:
    """Every dotted name an import in the file may refer to (``from a.b import c``: a.b and a.b.c)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    out: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out |= {node.module} | {f"{node.module}.{a.name}" for a in node.names}
    return out


def _modules() -> dict[str, Path]:
    out = {}
    for pkg, d in DIRS.items():
        for f in (REPO / d).rglob("*.py"):
            name = ".".join((pkg, *f.relative_to(REPO / d).with_suffix("").parts))
            out[name.removesuffix(".__init__")] = f
    return out


def module_graph() -> dict[str, set[str]]:
    mods = _modules()
    return {m: {d for d in _imports(f) if d in mods and d != m} for m, f in mods.items()}


def package_graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {pkg: set() for pkg in PACKAGES}
    for m, deps in module_graph().items():
        graph[m.split(".")[0]] |= {d.split(".")[0] for d in deps}
    return {p: d - {p} for p, d in graph.items()}


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


def test_no_circle_between_the_modules() -> None:
    # e.g. cli <-> sweep_cli (now both on cli_args), arena <-> arena_jitter (now arena_report)
    graph = module_graph()
    assert {"harness.cli", "harness.sweep_cli", "sim_plant.arena"} <= set(graph)
    assert _cycle(graph) is None, f"import circle: {' -> '.join(_cycle(graph) or [])}"


def test_the_bottom_packages_import_no_other_package() -> None:
    graph = package_graph()
    assert graph["sim_plant"] == graph["ffr_firmware"] == set()
    assert graph["ffr_link"] == {"ffr_firmware"}
    assert graph["hil_bridge"] == {"ffr_link", "ffr_firmware"}
