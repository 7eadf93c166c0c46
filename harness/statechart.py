"""The route program's state diagrams, generated from the firmware's C sources (docs/firmware.md).

``python -m harness.statechart`` prints them (Mermaid ``stateDiagram-v2``); ``--write FILE`` puts
them into FILE between ``<!-- statechart:begin -->`` and ``<!-- statechart:end -->`` (``make
statechart`` does it for docs/firmware.md); ``--check FILE``: exit 1 when FILE's block differs from
what would be printed now (tests/docs/test_statechart.py runs it).

Nothing here is a hand-kept list of states. What is read:

- the names: the library's own (``ffr_names``: states, failure codes, route ops), matched to the
  C enums of ``ffr.h`` (``FFR_ST_*``, ``FFR_FAIL_*``, ``FFR_OP_*``) by value;
- ``room.c``: its phases (``enum { RP_... }``), the dispatcher's handler table
  (``handlers[RP_COUNT]``), the state each phase reports (``codes[RP_COUNT]`` in ``enter``), the
  first phase (``enter(st, RP_...)`` in ``ffr_room_begin``), and in each handler every phase it
  can return (``return RP_X;``, ``next = RP_X; ... return next;``, ``c ? RP_X : RP_STAY``, and
  through the file's helpers it returns, ``return flame_found(st);``), every ``ffr_fail`` and every
  result for route.c (``t->result = FFR_ROOM_...``);
- the mission: ``ffr_init``'s first state and ``ffr_step``'s ways out of it (``mission.c``),
  ``ffr_orient_begin``'s state (``home_orient.c``), what each route op starts (``begin_current``'s
  ``switch (s->op)``) and how each ends (``ffr_route_step``'s ``switch (s->op)``: ``next``,
  ``ffr_route_begin``, ``st->state = ...``, ``ffr_fail``) (``route.c``).

An edge's label is the condition of the ``if``s, ``else``s and ``case``s around the statement
that makes it, innermost last, written in words (``st->``/``cfg->``/``ffr_``/``FFR_`` dropped, a
call by its name alone); ``/`` then what the transition does (a failure's name, the route's next
step, the result handed to route.c). Earlier returns in the same handler take precedence; the
label does not repeat their negation.

The C is read by a small tokenizer and statement parser that knows blocks, ``if``/``else``,
``switch``/``case`` and simple statements: enough for the firmware's style (braces on every
branch, one statement a line), checked by the tests (every exported name drawn, every phase
reachable)."""

from __future__ import annotations

import re
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from sim_plant.broken_pipe import exit_with

REPO = Path(__file__).resolve().parents[1]
SRC = REPO / "firmware" / "src"
HEADER = REPO / "firmware" / "include" / "ffr.h"
DOC = REPO / "docs" / "firmware.md"
BEGIN = "<!-- statechart:begin -->"
END = "<!-- statechart:end -->"
NAMES_OPS = 16  # FFR_NAMES_OWN (ffr_contract.h): our route ops' names (ffr.h)
# calls followed into the file's helpers at most this deep: a guard against recursion, not a
# limit on the firmware's helpers (home_orient.c's deepest chain of pure helpers is 9 calls)
MAX_CALL_DEPTH = 12

# ---- reading C -------------------------------------------------------------------------------------

_TOKEN = re.compile(r"""
    (?P<id>[A-Za-z_]\w*)
  | (?P<num>0[xX][0-9a-fA-F]+[uUlL]*|\d+\.?\d*(?:[eE][-+]?\d+)?[fFuUlL]*|\.\d+[fF]?)
  | (?P<str>"(?:\\.|[^"\\])*"|'(?:\\.|[^'\\])*')
  | (?P<op>->|\+\+|--|<<=|>>=|<=|>=|==|!=|&&|\|\||\+=|-=|\*=|/=|&=|\|=|\^=|<<|>>|[{}()\[\];,?:.<>=!~+\-*/%&|^])
  | (?P<ws>\s+)
""", re.X)


class ChartError(RuntimeError):
    """The sources are not what the reader expects (a file, a table or a name is missing)."""


def tokenize(text: str) -> list[str]:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    text = re.sub(r"^\s*#.*?(?<!\\)$", " ", text, flags=re.M | re.S)
    out: list[str] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            raise ChartError(f"cannot read C at {text[pos:pos + 30]!r}")
        if m.lastgroup != "ws":
            out.append(m.group())
        pos = m.end()
    return out


def _close(toks: Sequence[str], i: int) -> int:
    """Index of the bracket that closes toks[i]."""
    pair = {"(": ")", "{": "}", "[": "]"}[toks[i]]
    depth = 0
    for j in range(i, len(toks)):
        if toks[j] == toks[i]:
            depth += 1
        elif toks[j] == pair:
            depth -= 1
            if depth == 0:
                return j
    raise ChartError(f"unbalanced {toks[i]!r}")


@dataclass(frozen=True)
class Cond:
    """One condition around a statement: ``toks`` holds (negated: its ``else``)."""

    toks: tuple[str, ...]
    negated: bool = False


@dataclass(frozen=True)
class Stmt:
    """A simple statement, or an ``if``'s condition (``cond``: its calls happen too)."""

    conds: tuple[Cond, ...]
    toks: tuple[str, ...]
    cond: bool = False


@dataclass
class Func:
    name: str
    params: list[str]
    body: list[Stmt]
    tokens: list[str] = field(repr=False)


def _statements(toks: list[str], i: int, end: int, conds: tuple[Cond, ...], out: list[Stmt]) -> None:
    while i < end:
        i = _statement(toks, i, conds, out)


def _statement(toks: list[str], i: int, conds: tuple[Cond, ...], out: list[Stmt]) -> int:
    t = toks[i]
    if t == "{":
        j = _close(toks, i)
        _statements(toks, i + 1, j, conds, out)
        return j + 1
    if t == "if":
        j = _close(toks, i + 1)
        c = tuple(toks[i + 2:j])
        out.append(Stmt(conds, c, cond=True))
        k = _statement(toks, j + 1, conds + (Cond(c),), out)
        if k < len(toks) and toks[k] == "else":
            return _statement(toks, k + 1, conds + (Cond(c, negated=True),), out)
        return k
    if t in ("while", "for"):
        j = _close(toks, i + 1)
        loop = (Cond(tuple(toks[i + 2:j])),) if t == "while" else ()
        return _statement(toks, j + 1, conds + loop, out)
    if t == "switch":
        j = _close(toks, i + 1)
        subject = tuple(toks[i + 2:j])
        if toks[j + 1] != "{":
            raise ChartError("a switch without a block")
        e = _close(toks, j + 1)
        k = j + 2
        labels: list[tuple[str, ...]] = []
        case_conds = conds
        while k < e:
            if toks[k] in ("case", "default"):
                colon = k + 1
                while toks[colon] != ":":
                    colon += 1
                value = tuple(toks[k + 1:colon]) if toks[k] == "case" else ("other",)
                if k > j + 2 and toks[k - 1] == ":" and labels:
                    labels.append(value)  # case A: case B: ...
                else:
                    labels = [value]
                expr: list[str] = []
                for v in labels:
                    expr += (["||"] if expr else []) + list(subject) + ["=="] + list(v)
                case_conds = conds + (Cond(tuple(expr)),)
                k = colon + 1
                continue
            k = _statement(toks, k, case_conds, out)
        return e + 1
    if t in ("break", "continue", ";"):
        while toks[i] != ";":
            i += 1
        return i + 1
    j = i
    while toks[j] != ";":
        j = _close(toks, j) + 1 if toks[j] in "({[" else j + 1
    out.append(Stmt(conds, tuple(toks[i:j])))
    return j + 1


def functions(text: str) -> dict[str, Func]:
    """The file's function definitions, each body as statements with their conditions."""
    toks = tokenize(text)
    funcs: dict[str, Func] = {}
    i = 0
    while i < len(toks):
        t = toks[i]
        if t in "{[(":
            j = _close(toks, i)
            if t == "(" and i > 0 and re.match(r"[A-Za-z_]", toks[i - 1]) and j + 1 < len(toks) \
                    and toks[j + 1] == "{" and (i < 2 or toks[i - 2] != "="):
                name = toks[i - 1]
                params = [_param(p) for p in _split(toks[i + 1:j]) if p and p != ["void"]]
                b = _close(toks, j + 1)
                body: list[Stmt] = []
                _statements(toks, j + 2, b, (), body)
                funcs[name] = Func(name, params, body, toks[j + 2:b])
                i = b + 1
                continue
            i = j + 1
            continue
        i += 1
    return funcs


def _param(decl: Sequence[str]) -> str:
    """A parameter's name: the last identifier before any ``[...]``."""
    names = [t for t in (decl[:decl.index("[")] if "[" in decl else decl) if re.match(r"[A-Za-z_]\w*$", t)]
    return names[-1]


def _split(toks: Sequence[str], sep: str = ",") -> list[list[str]]:
    """toks split at top-level ``sep``."""
    out: list[list[str]] = [[]]
    i = 0
    while i < len(toks):
        if toks[i] in "({[":
            j = _close(toks, i)
            out[-1] += toks[i:j + 1]
            i = j + 1
            continue
        if toks[i] == sep:
            out.append([])
        else:
            out[-1].append(toks[i])
        i += 1
    return out


def _calls(toks: Sequence[str]) -> list[tuple[str, list[list[str]]]]:
    """Every call ``name(args)`` in toks, outer first."""
    out = []
    for i in range(len(toks) - 1):
        if toks[i + 1] == "(" and re.match(r"[A-Za-z_]\w*$", toks[i]) and toks[i] not in ("if", "while", "sizeof"):
            j = _close(toks, i + 1)
            out.append((toks[i], _split(toks[i + 2:j])))
    return out


def _assignment(toks: Sequence[str]) -> tuple[list[str], list[str]] | None:
    depth = 0
    for i, t in enumerate(toks):
        depth += t in "([{"
        depth -= t in ")]}"
        if t == "=" and depth == 0:
            return list(toks[:i]), list(toks[i + 1:])
    return None


def _ternary(toks: Sequence[str]) -> tuple[list[str], list[str], list[str]] | None:
    q = _split(toks, "?")
    if len(q) != 2:
        return None
    bc = _split(q[1], ":")
    return (q[0], bc[0], bc[1]) if len(bc) == 2 else None


def _subst(toks: Sequence[str], env: dict[str, list[str]]) -> tuple[str, ...]:
    out: list[str] = []
    for i, t in enumerate(toks):
        if t in env and (i == 0 or toks[i - 1] not in ("->", ".")):
            out += env[t]
        else:
            out.append(t)
    return tuple(out)


def enum_values(text: str, prefix: str) -> dict[str, int]:
    """``NAME -> value`` of every enumerator starting with prefix in the text's enums."""
    out: dict[str, int] = {}
    for body in re.findall(r"\benum\b[^{;]*\{(.*?)\}", re.sub(r"/\*.*?\*/", " ", text, flags=re.S), re.S):
        value = -1
        for item in body.split(","):
            m = re.match(r"\s*(\w+)\s*(?:=\s*(\w+))?\s*$", item)
            if not m:
                continue
            value = int(m.group(2), 0) if m.group(2) and m.group(2)[0].isdigit() else \
                out.get(m.group(2) or "", value + 1) if m.group(2) else value + 1
            if m.group(1).startswith(prefix):
                out[m.group(1)] = value
    return out


def _table(func: Func, name: str) -> list[str]:
    """The identifiers of ``static const T name[...] = {a, b, ...};`` in the function."""
    for st in func.body:
        if name in st.toks and "=" in st.toks:
            i = st.toks.index("=")
            return [x[0] for x in _split(st.toks[i + 2:-1]) if x]
    raise ChartError(f"{func.name}: no table {name}")


# ---- conditions in words ---------------------------------------------------------------------------

_BASES = {"st", "cfg", "t", "r", "o", "in", "s", "odo"}
_WORDS = {"||": "or", "&&": "and", "==": "=", "!=": "≠", ">=": "≥", "<=": "≤", "<": "below", ">": "above",
          "*": "×", "&": "has"}


def words(toks: Sequence[str]) -> str:
    """A C expression as an edge label: member chains without their base, calls by name, no casts."""
    out: list[str] = []
    i = 0
    while i < len(toks):
        t = toks[i]
        if t == "(" and i + 2 < len(toks) and toks[i + 2] == ")" and toks[i + 1] in (
                "float", "int", "uint8_t", "uint16_t", "uint32_t", "int16_t", "int32_t"):
            i += 3  # a cast
            continue
        if re.match(r"[A-Za-z_]", t):
            chain = [t]
            while i + 2 < len(toks) and toks[i + 1] in ("->", ".") and re.match(r"[A-Za-z_]", toks[i + 2]):
                chain.append(toks[i + 2])
                i += 2
            if len(chain) > 1 and chain[0] in _BASES:
                chain = chain[1:]
            if len(chain) > 1 and chain[0] == "cfg":
                chain = chain[1:]
            name = ".".join(chain)
            if i + 1 < len(toks) and toks[i + 1] == "(":
                i = _close(toks, i + 1)  # a call: its name alone
            out.append(re.sub(r"^(ffr_|FFR_|RP_)", "", name))
            i += 1
            continue
        if re.match(r"\d", t):
            t = re.sub(r"\.0*[fF]?$|[uUfF]+$", "", t)
        out.append(_WORDS.get(t, "not " if t == "!" else t))
        i += 1
    text = " ".join(out)
    for a, b in (("( ", "("), (" )", ")"), (" [ ", "["), ("[ ", "["), (" ]", "]"), ("not  ", "not ")):
        text = text.replace(a, b)
    text = re.sub(r"\s+", " ", text).strip()
    while _wrapped(text):
        text = text[1:-1]  # a cast's leftover
    return text


def _simple(text: str) -> bool:
    """No ``or``/``and`` outside parentheses."""
    depth = 0
    for i, ch in enumerate(text):
        depth += ch == "("
        depth -= ch == ")"
        if depth == 0 and (text.startswith(" or ", i) or text.startswith(" and ", i)):
            return False
    return True


def _wrapped(text: str) -> bool:
    """One parenthesised group, end to end."""
    return text.startswith("(") and _close(list(text), 0) == len(text) - 1


def cond_words(c: Cond) -> str:
    w = words(c.toks)
    if c.negated:
        return f"not {w}" if " " not in w or _wrapped(w) else f"not ({w})"
    return w


def join(parts: Sequence[str], action: str = "") -> str:
    """Conditions (already in words) and what the transition does: ``a and b / action``."""
    if len(parts) > 1:
        parts = [p if _simple(p) else f"({p})" for p in parts]
    text = " and ".join(parts)
    return f"{text} / {action}" if action and text else (action or text)


def label(conds: Sequence[Cond], action: str = "") -> str:
    return join([cond_words(c) for c in conds], action)


# ---- the charts ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Edge:
    src: str
    dst: str
    label: str = ""


@dataclass
class Chart:
    """One state diagram: nodes (id -> note), the first node, edges; ``[*]`` is the start/end."""

    title: str
    start: str
    nodes: dict[str, str]
    edges: list[Edge]
    choices: tuple[str, ...] = ()

    def mermaid(self) -> str:
        lines = ["```mermaid", "stateDiagram-v2"]
        lines += [f"    state {c} <<choice>>" for c in self.choices]
        # a state's text: its id, then its note (``id : note`` would show the note alone)
        lines += [f'    state "{n} ({note})" as {n}' for n, note in self.nodes.items() if note]
        lines.append(f"    [*] --> {self.start}")
        for e in self.edges:
            lines.append(f"    {e.src} --> {e.dst}" + (f" : {e.label}" if e.label else ""))
        lines.append("```")
        return "\n".join(lines)

    def reachable(self) -> set[str]:
        seen = {self.start}
        todo = [self.start]
        while todo:
            n = todo.pop()
            for e in self.edges:
                if e.src == n and e.dst not in seen:
                    seen.add(e.dst)
                    todo.append(e.dst)
        return seen


@dataclass(frozen=True)
class Names:
    """The library's names (ffr_names) by the C enumerators of ffr.h."""

    states: dict[str, str]  # FFR_ST_X -> name
    fails: dict[str, str]   # FFR_FAIL_X -> name
    ops: dict[str, str]     # FFR_OP_X -> name

    @staticmethod
    def load(header: Path = HEADER, library: str | None = None) -> Names:
        from ffr_link.library import firmware_info

        info = firmware_info(library)
        text = header.read_text(encoding="utf-8")

        def by_value(prefix: str, names: Sequence[str], skip: str = "") -> dict[str, str]:
            out = {}
            for k, v in enum_values(text, prefix).items():
                if k == skip:
                    continue
                if not 0 <= v < len(names):
                    raise ChartError(f"{header.name}: {k} = {v}, but the library names {len(names)} codes")
                out[k] = names[v]
            return out

        return Names(by_value("FFR_ST_", info.state_names, "FFR_ST_COUNT"),
                     by_value("FFR_FAIL_", info.fail_names, "FFR_FAIL_NONE"),
                     by_value("FFR_OP_", info.names.get(NAMES_OPS, ())))

    def fail(self, toks: Sequence[str]) -> list[tuple[tuple[Cond, ...], str]]:
        """``ffr_fail(st, code)``'s code (``c ? A : B``: each with its condition) as an action."""
        tern = _ternary(toks)
        if tern:
            return [((Cond(tuple(tern[0]), neg),) + cs, a) for neg, branch in ((False, tern[1]), (True, tern[2]))
                    for cs, a in self.fail(branch)]
        if len(toks) != 1 or toks[0] not in self.fails:
            raise ChartError(f"ffr_fail with no known code: {' '.join(toks)}")
        return [((), "failed: " + self.fails[toks[0]])]


def _read(src: Path, name: str) -> str:
    p = src / name
    if not p.is_file():
        raise ChartError(f"{p}: not found")
    return p.read_text(encoding="utf-8")


def _need(funcs: dict[str, Func], name: str, where: str) -> Func:
    if name not in funcs:
        raise ChartError(f"{where}: function {name} not found")
    return funcs[name]


def room_chart(src: Path, names: Names) -> Chart:
    """room.c's phases: one handler each, every phase a handler returns."""
    text = _read(src, "room.c")
    funcs = functions(text)
    phases = [p for p in enum_values(text, "RP_") if p not in ("RP_COUNT",)]
    step = _need(funcs, "ffr_room_step", "room.c")
    handlers = _table(step, "handlers")
    codes = _table(_need(funcs, "enter", "room.c"), "codes")
    if len(handlers) != len(phases) or len(codes) != len(phases):
        raise ChartError(f"room.c: {len(phases)} phases, {len(handlers)} handlers, {len(codes)} reported states")
    begin = _need(funcs, "ffr_room_begin", "room.c")
    first = next((c[1][1][0] for st in begin.body for c in _calls(st.toks) if c[0] == "enter"), None)
    if first is None:
        raise ChartError("room.c: ffr_room_begin enters no phase")

    def short(p: str) -> str:
        return p.removeprefix("RP_")

    edges: list[Edge] = []
    nodes = {short(p): f"reports {names.states[c]}" for p, c in zip(phases, codes, strict=True)}

    def outcomes(fn: Func, env: dict[str, list[str]], conds: tuple[Cond, ...], depth: int = 0
                 ) -> list[tuple[tuple[Cond, ...], str, str]]:
        """(conditions, kind, value): kind 'phase' (value RP_X), 'fail' (label), 'result' (FFR_ROOM_X)."""
        if depth > MAX_CALL_DEPTH:
            raise ChartError(f"room.c: {fn.name}: helpers call each other too deep")
        returned = {st.toks[1] for st in fn.body if len(st.toks) == 2 and st.toks[0] == "return"}
        out: list[tuple[tuple[Cond, ...], str, str]] = []

        def value(cs: tuple[Cond, ...], expr: Sequence[str]) -> None:
            expr = list(_subst(expr, env))
            tern = _ternary(expr)
            if tern:
                value(cs + (Cond(tuple(tern[0])),), tern[1])
                value(cs + (Cond(tuple(tern[0]), negated=True),), tern[2])
                return
            if len(expr) == 1 and expr[0] in phases + ["RP_STAY"]:
                out.append((cs, "phase", expr[0]))
                return
            if len(expr) == 1 and expr[0] in returned:
                return  # a local returned: its assignments are the values
            calls = _calls(expr)
            if calls and calls[0][0] in funcs and _close(expr, 1) == len(expr) - 1:
                g = funcs[calls[0][0]]
                out.extend(outcomes(g, dict(zip(g.params, calls[0][1], strict=False)), cs, depth + 1))
                return
            raise ChartError(f"room.c: {fn.name} returns {' '.join(expr)}: not a phase")

        for st in fn.body:
            cs = conds + tuple(Cond(_subst(c.toks, env), c.negated) for c in st.conds)
            toks = list(st.toks)
            for name, args in _calls(toks):
                if name == "ffr_fail":
                    out.extend((cs + more, "fail", a) for more, a in names.fail(args[1]))
            asg = _assignment(toks)
            if st.cond:
                continue
            if toks[0] == "return" and len(toks) > 1:
                value(cs, toks[1:])
            elif asg and asg[0] and asg[0][-1] in returned:
                value(cs, asg[1])
            elif asg and asg[0][-1:] == ["result"]:
                out.append((cs, "result", asg[1][0]))
        return out

    for p, h in zip(phases, handlers, strict=True):
        if h not in funcs:
            raise ChartError(f"room.c: handler {h} not found")
        found = outcomes(funcs[h], {}, ())
        results = {cs: v for cs, kind, v in found if kind == "result"}
        for cs, kind, v in found:
            act = re.sub(r"^FFR_", "", results.get(cs, ""))
            if kind == "phase" and v != "RP_STAY":
                edges.append(Edge(short(p), short(v), label(cs, act)))
            elif kind == "phase" and cs in results:
                edges.append(Edge(short(p), "[*]", label(cs, act)))
            elif kind == "fail":
                edges.append(Edge(short(p), "FAILED", label(cs, v)))
    if any(e.dst == "FAILED" for e in edges):
        nodes["FAILED"] = "the mission ends"
    return Chart("room", short(first), nodes, _unique(edges))


def _unique(edges: list[Edge]) -> list[Edge]:
    return list(dict.fromkeys(edges))


def mission_chart(src: Path, names: Names, room: Chart) -> Chart:
    """The mission: ffr_init's state, orientation at home, the route's steps, the room task, the end."""
    funcs: dict[str, Func] = {}
    for f in ("mission.c", "home_orient.c", "route.c"):
        funcs.update(functions(_read(src, f)))
    init = _need(funcs, "ffr_init", "mission.c")
    step_fn = _need(funcs, "ffr_step", "mission.c")
    begin = _need(funcs, "begin_current", "route.c")
    route_step = _need(funcs, "ffr_route_step", "route.c")
    STEP = "next_step"

    def state_of(toks: Sequence[str]) -> str | None:
        asg = _assignment(toks)
        if asg and asg[0][-1:] == ["state"] and len(asg[1]) == 1 and asg[1][0] in names.states:
            return names.states[asg[1][0]]
        return None

    initial = next((s for st in init.body if (s := state_of(st.toks))), None)
    if initial is None:
        raise ChartError("mission.c: ffr_init sets no state")

    def effects(fn: Func, env: dict[str, list[str]], conds: tuple[Cond, ...], pc: str = "", depth: int = 0
                ) -> list[tuple[tuple[Cond, ...], str, str]]:
        """(conditions, target node, action) of everything fn does that changes the state."""
        if depth > MAX_CALL_DEPTH:
            raise ChartError(f"{fn.name}: calls nest too deep")
        out: list[tuple[tuple[Cond, ...], str, str]] = []
        for st in fn.body:
            cs = conds + tuple(Cond(_subst(c.toks, env), c.negated) for c in st.conds)
            toks = _subst(st.toks, env)
            asg = _assignment(toks)
            if asg and asg[0][-2:] == [".", "pc"]:
                pc = "pc = " + words(asg[1])
            if (s := state_of(toks)) is not None:
                out.append((cs, s, ""))
            for name, args in _calls(toks):
                if name == "ffr_fail":
                    out.extend((cs + more, "FAILED", a) for more, a in names.fail(args[1]))
                elif name == "begin_current":
                    out.append((cs, STEP, pc))
                elif name == "ffr_room_begin":
                    out.append((cs, "ROOM", ""))
                elif name in funcs and name not in ("ffr_route_step", "ffr_orient_step", "ffr_fail"):
                    g = funcs[name]
                    out.extend(effects(g, dict(zip(g.params, args, strict=False)), cs, pc, depth + 1))
        return out

    edges: list[Edge] = []
    op_node: dict[str, str] = {}
    # what each op starts (begin_current): the choice node's ways out
    for cs, dst, act in effects(begin, {}, ()):
        case = next((c for c in cs if not c.negated and any(t in names.ops for t in c.toks)), None)
        rest = [cond_words(c) for c in cs if c is not case]
        if case is not None:
            ops = [names.ops[t] for t in case.toks if t in names.ops] + ["other"] * ("other" in case.toks)
            if dst != "FAILED":
                op_node.update({t: dst for t in case.toks if t in names.ops})
            rest.insert(0, "op = " + " or ".join(ops))
        edges.append(Edge(STEP, dst, join(rest, act)))
    # ffr_step: out of the first state, out of ORIENT
    for cs, dst, act in effects(step_fn, {}, ()):
        src = initial
        keep: list[Cond] = []
        for c in cs:
            if "state" in c.toks and "==" in c.toks:
                src = next(names.states[t] for t in c.toks if t in names.states)
            elif "started" not in c.toks:
                keep.append(c)
        edges.append(Edge(src, dst, label(keep, act)))
    orient_calls = [c for st in step_fn.body for c in _calls(st.toks) if c[0] == "ffr_orient_step"]
    orient = names.states["FFR_ST_ORIENT"]
    if orient_calls and not any(e.src == orient for e in edges):
        raise ChartError("mission.c: ffr_step runs ffr_orient_step but leaves ORIENT nowhere")
    # how each op ends (ffr_route_step): from the state its op started
    for cs, dst, act in effects(route_step, {}, ()):
        case = next((c for c in cs if not c.negated and any(t in names.ops for t in c.toks)), None)
        if case is None:
            continue  # switch (s->op)'s default: an op begin_current never starts (it failed there)
        keep = [c for c in cs if c is not case]
        for o in dict.fromkeys(t for t in case.toks if t in names.ops):
            if o not in op_node:
                raise ChartError(f"route.c: ffr_route_step runs {o}, which begin_current never starts")
            edges.append(Edge(op_node[o], dst, label(keep, act)))
    # the room task's failures (its handlers, room.c)
    for e in room.edges:
        if e.dst == "FAILED":
            edges.append(Edge("ROOM", "FAILED", e.label.split(" / ")[-1]))
    done = names.states["FFR_ST_DONE"]
    failed = names.states["FFR_ST_FAILED"]
    edges += [Edge(done, "[*]"), Edge(failed, "[*]")]
    room_states = sorted(set(n.removeprefix("reports ") for k, n in room.nodes.items() if k != "FAILED"),
                         key=list(names.states.values()).index)
    nodes = {"ROOM": "the room task, below: reports " + ", ".join(room_states)}
    return Chart("mission", initial, nodes, _unique(edges), (STEP,))


def orient_chart(src: Path) -> Chart:
    """home_orient.c's phases (state ORIENT): each ``if (o->phase == PH_X)`` block of ffr_orient_step
    and every phase it (or a helper of the file it calls) sets."""
    text = _read(src, "home_orient.c")
    funcs = functions(text)
    phases = enum_values(text, "PH_")
    step = _need(funcs, "ffr_orient_step", "home_orient.c")

    def sets(fn: Func, env: dict[str, list[str]], conds: tuple[Cond, ...], depth: int = 0
             ) -> list[tuple[tuple[Cond, ...], str]]:
        if depth > MAX_CALL_DEPTH:
            raise ChartError(f"home_orient.c: {fn.name}: calls nest too deep")
        out: list[tuple[tuple[Cond, ...], str]] = []
        for st in fn.body:
            cs = conds + tuple(Cond(_subst(c.toks, env), c.negated) for c in st.conds)
            toks = _subst(st.toks, env)
            asg = None if st.cond else _assignment(toks)
            if asg and asg[0][-1:] == ["phase"] and len(asg[1]) == 1 and asg[1][0] in phases:
                out.append((cs, asg[1][0]))
            for name, args in _calls(toks):
                if name in funcs and name != fn.name:
                    g = funcs[name]
                    out.extend(sets(g, dict(zip(g.params, args, strict=False)), cs, depth + 1))
        return out

    begin = sets(_need(funcs, "ffr_orient_begin", "home_orient.c"), {}, ())
    if not begin:
        raise ChartError("home_orient.c: ffr_orient_begin sets no phase")
    first = begin[-1][1]  # the last phase it sets is where the step begins

    def short(p: str) -> str:
        return p.removeprefix("PH_")

    edges: list[Edge] = []
    for cs, dst in sets(step, {}, ()):
        src = [c for c in cs if not c.negated and "phase" in c.toks and "==" in c.toks]
        if len(src) != 1:
            raise ChartError(f"home_orient.c: ffr_orient_step sets {dst} outside one phase's block")
        frm = next(t for t in src[0].toks if t in phases)
        edges.append(Edge(short(frm), short(dst), label([c for c in cs if c is not src[0]])))
    ends = [p for p in phases if not any(e.src == short(p) for e in edges) and any(e.dst == short(p) for e in edges)]
    if not any(st.toks == ("return", "1") for st in step.body):
        raise ChartError("home_orient.c: ffr_orient_step never returns 1 (done)")
    edges += [Edge(short(p), "[*]", "ffr_orient_step returns 1: the route begins") for p in ends]
    return Chart("orient", short(first), {}, _unique(edges))


def charts(src: Path = SRC, header: Path = HEADER, library: str | None = None) -> tuple[Chart, Chart, Chart]:
    """The mission, orientation at home (ORIENT's phases) and the room task."""
    names = Names.load(header, library)
    room = room_chart(src, names)
    return mission_chart(src, names, room), orient_chart(src), room


def render(src: Path = SRC, header: Path = HEADER, library: str | None = None) -> str:
    """The block docs/firmware.md holds between the markers."""
    mission, orient, room = charts(src, header, library)
    return "\n".join([
        BEGIN,
        "<!-- generated by `make statechart` (python -m harness.statechart): do not edit by hand -->",
        "",
        "**The mission** (`mission.c`, `home_orient.c`, `route.c`; `next_step` is `begin_current`: the step",
        "at `pc` starts by its op):",
        "",
        mission.mermaid(),
        "",
        "**At home, state ORIENT** (`home_orient.c`: `ffr_orient_step`'s phases):",
        "",
        orient.mermaid(),
        "",
        "**The room task** (`room.c`: one handler a phase, the state each reports):",
        "",
        room.mermaid(),
        END,
    ])


def replace_block(doc: str, block: str, where: str = "docs/firmware.md") -> str:
    if doc.count(BEGIN) != 1 or doc.count(END) != 1 or doc.index(BEGIN) > doc.index(END):
        raise ChartError(f"{where}: needs one {BEGIN} ... {END} block")
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return head + block + tail


def main(argv: Sequence[str] | None = None) -> int:
    from harness.cli_args import UsageError, _Parser  # one line for a bad argument, not usage + error

    ap = _Parser(prog="python -m harness.statechart", description=__doc__.splitlines()[0])
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--write", metavar="FILE", help="put the diagrams into FILE's statechart block")
    g.add_argument("--check", metavar="FILE", help="exit 1 if FILE's statechart block is not what is printed now")
    ap.add_argument("--src", default=str(SRC), help="the firmware's C sources (default: firmware/src)")
    try:
        a = ap.parse_args(argv)
    except UsageError as exc:
        print(f"python -m harness.statechart: {exc}", file=sys.stderr)
        return 2
    src = Path(a.src)
    if not src.is_dir():
        print(f"python -m harness.statechart: --src {a.src}: not a directory", file=sys.stderr)
        return 2
    target = a.write or a.check
    try:
        block = render(src)
        if target is None:
            print(block)
            return 0
        path = Path(target)
        if not path.is_file():
            print(f"python -m harness.statechart: {target}: not found", file=sys.stderr)
            return 2
        doc = path.read_text(encoding="utf-8")
        new = replace_block(doc, block, target)
    except ChartError as exc:
        print(f"python -m harness.statechart: {exc}", file=sys.stderr)
        return 2
    if a.check:
        if new != doc:
            print(f"{target}: the state diagrams are not what the code says now: run `make statechart`",
                  file=sys.stderr)
            return 1
        print(f"{target}: the state diagrams are what the code says")
        return 0
    if new != doc:
        path.write_text(new, encoding="utf-8")
    print(f"{target}: state diagrams written")
    return 0


if __name__ == "__main__":
    exit_with(main)
