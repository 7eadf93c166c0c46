"""The one schema layer for every input file (docs/inputs.md).

Each file kind declares its tables once, as ``msgspec.Struct`` types with
``forbid_unknown_fields=True`` and ``Meta(ge=..., le=...)`` ranges (plant-side
files: ``sim_plant/file_schemas.py``; scenarios, events and scoring:
``harness/scenario_schema.py``); cross-field rules sit in the struct's
``__post_init__`` (raise ``rule(field, why)``). ``check(data, Schema, source)``
validates a parsed TOML dict against it and turns msgspec's error into our
one-line ``FfrInputError``: ``file: table.path = value: why`` with a
"did you mean" for a misspelt key.

This module also holds what every reader shares: ``read_toml`` (one line for an
unreadable, non-UTF-8 or malformed file) and ``did_you_mean`` (the one wording
of an unknown key). It imports msgspec only when ``check`` first runs, so a
command that reads no file (``ffr run --help``) does not pay for it.
"""

from __future__ import annotations

import copy
import difflib
import math
import re
import tomllib
import typing
from functools import lru_cache
from pathlib import Path
from typing import Any

from sim_plant.errors import FfrInputError

__all__ = ["check", "did_you_mean", "read_toml", "rule"]


# -- reading files ------------------------------------------------------------------------------

def read_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file; unreadable, non-UTF-8 or malformed files raise FfrInputError."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise FfrInputError(str(p), "(file)", str(p), exc.strerror or "cannot be read") from None
    except UnicodeDecodeError as exc:
        raise FfrInputError(str(p), "(encoding)", f"byte {exc.start}",
                            "not UTF-8 text (TOML files are UTF-8)") from None
    try:
        return copy.deepcopy(_parse_toml(text))
    except tomllib.TOMLDecodeError as exc:
        raise FfrInputError(str(p), "(syntax)", None, str(exc).replace("\n", " ")) from None


@lru_cache(maxsize=32)
def _parse_toml(text: str) -> dict[str, Any]:
    # Parsed once per content: a sweep reads the same noise profile and scoring
    # files for every mission (~7 ms each time); read_toml hands out copies.
    return tomllib.loads(text)


# -- the schema check ------------------------------------------------------------------------------

def did_you_mean(key: str, known: typing.Iterable[str]) -> str:
    """``unknown field (did you mean 'x'? known: ...)``: the one wording of an unknown key."""
    names = sorted(known)
    near = difflib.get_close_matches(key, names, n=1)
    hint = f"did you mean {near[0]!r}? " if near else ""
    return f"unknown field ({hint}known: {', '.join(names)})"


def rule(field: str, why: str) -> ValueError:
    """The error a struct's ``__post_init__`` raises for a cross-field rule: ``field`` relative to
    the struct (``"x"``, ``"rooms[2].id"``); ``check`` reports it with the struct's path."""
    return ValueError(f"`{field}`: {why}")


Path_ = list[str | int]


def check(data: Any, schema: Any, source: str, prefix: str = "") -> Any:
    """``data`` converted to ``schema`` (a msgspec type), or FfrInputError naming file, path, value.

    ``prefix``: the path of ``data`` inside its file (e.g. ``"noise"`` for a scenario's inline
    profile). No value anywhere in an input file may be NaN or infinite."""
    import msgspec

    _finite(data, source, prefix)
    try:
        return msgspec.convert(data, schema, strict=True)
    except msgspec.ValidationError as exc:
        raise _error(str(exc), data, schema, source, _split(prefix)) from None


def _finite(v: Any, source: str, prefix: str, path: Path_ | None = None) -> None:
    path = path or []
    if isinstance(v, float) and not math.isfinite(v):
        raise FfrInputError(source, _fmt(_split(prefix) + path), v, "must be a finite number")
    if isinstance(v, dict):
        for k, x in v.items():
            _finite(x, source, prefix, [*path, k])
    elif isinstance(v, list):
        for i, x in enumerate(v):
            _finite(x, source, prefix, [*path, i])


_PART = re.compile(r"\.([^.\[\]]+)|\[(\d+|\.\.\.)\]")


def _split(text: str) -> Path_:
    """``"$.rooms[2].door"`` or ``"rooms[2].door"`` -> ["rooms", 2, "door"]."""
    text = text.removeprefix("$")
    if text and not text.startswith((".", "[")):
        text = "." + text
    out: Path_ = []
    for m in _PART.finditer(text):
        if m.group(1) is not None:
            out.append(m.group(1))
        else:
            out.append(int(m.group(2)) if m.group(2) != "..." else "...")
    return out


def _fmt(path: Path_) -> str:
    s = ""
    for p in path:
        s += f"[{p}]" if isinstance(p, int) else (f".{p}" if s else str(p))
    return s


def _lookup(data: Any, path: Path_) -> Any:
    for p in path:
        try:
            data = data[p]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _unwrap(tp: Any) -> tuple[Any, list[Any]]:
    """(the bare type, its msgspec.Meta annotations)."""
    metas: list[Any] = []
    while typing.get_origin(tp) is typing.Annotated:
        tp, *extra = typing.get_args(tp)
        metas += extra
    return tp, metas


def _is_struct(tp: Any) -> bool:
    import msgspec

    return isinstance(tp, type) and issubclass(tp, msgspec.Struct)


def _members(tp: Any) -> list[Any]:
    """The types a union (also one inside Annotated) is made of, None left out."""
    bare, _ = _unwrap(tp)
    if typing.get_origin(bare) in (typing.Union, type(int | str)):
        return [m for a in typing.get_args(bare) if a is not type(None) for m in _members(a)]
    return [tp]




def _pick(tp: Any, value: Any) -> Any:
    """The member of a union ``value`` was meant for (a table: the struct or dict; an array: the list)."""
    members = _members(tp)
    if len(members) == 1:
        return members[0]
    for m in members:
        bare, _ = _unwrap(m)
        origin = typing.get_origin(bare) or bare
        if isinstance(value, dict) and (_is_struct(bare) or origin is dict):
            return m
        if isinstance(value, list) and origin in (list, tuple):
            return m
    return tp


def _field_type(struct: Any, name: str) -> Any:
    import msgspec

    for f in msgspec.structs.fields(struct):
        if f.encode_name == name:
            return f.type
    return None


def _type_at(tp: Any, data: Any, path: Path_) -> Any:
    """The declared type at ``path`` (None when the path leaves the schema)."""
    for p in path:
        if tp is None:
            return None
        tp = _pick(tp, data)
        bare, _ = _unwrap(tp)
        origin = typing.get_origin(bare)
        if _is_struct(bare) and isinstance(p, str):
            tp = _field_type(bare, p)
        elif origin is dict:
            tp = typing.get_args(bare)[1]
        elif origin is list and isinstance(p, int):
            tp = typing.get_args(bare)[0]
        elif origin is tuple and isinstance(p, int):
            args = typing.get_args(bare)
            tp = args[p] if p < len(args) else None
        else:
            return None
        data = _lookup(data, [p])
    return tp


def _describe(tp: Any) -> str:
    """What a value of this type is, for 'must be ...'."""
    bare, metas = _unwrap(tp)
    for m in metas:
        if getattr(m, "description", None):
            return str(m.description)
    if typing.get_origin(bare) in (typing.Union, type(int | str)):
        return " or ".join(_describe(a) for a in typing.get_args(bare) if a is not type(None))
    origin = typing.get_origin(bare)
    if origin is typing.Literal:
        return "one of " + ", ".join(str(a) for a in typing.get_args(bare))
    if bare is bool:
        return "true or false"
    if bare is int:
        return "a whole number"
    if bare is float:
        return "a finite number"
    if bare is str:
        return "a string"
    if _is_struct(bare) or origin is dict:
        return "a table"
    if origin in (list, tuple):
        (elem, *_rest) = typing.get_args(bare) or (None,)
        if origin is list and elem is not None and _is_struct(_unwrap(elem)[0]):
            return "an array of tables"
        return "an array"
    return getattr(bare, "__name__", str(bare))


def _bounds(tp: Any) -> str:
    """'must be ...' for a range violation, from the type's Meta."""
    bare, metas = _unwrap(_members(tp)[0] if tp is not None else tp)
    lo = hi = None
    lo_open = hi_open = False
    for m in metas:
        if getattr(m, "ge", None) is not None:
            lo = m.ge
        if getattr(m, "gt", None) is not None:
            lo, lo_open = m.gt, True
        if getattr(m, "le", None) is not None:
            hi = m.le
        if getattr(m, "lt", None) is not None:
            hi, hi_open = m.lt, True
        if getattr(m, "min_length", None) is not None:
            return f"must be {_describe(tp)}"
    what = "a whole number " if bare is int else ""
    if lo is not None and hi is not None:
        return f"must be {what}in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
    if lo is not None:
        return f"must be {'>' if lo_open else '>='} {lo:g}"
    if hi is not None:
        return f"must be {'<' if hi_open else '<='} {hi:g}"
    return f"must be {_describe(tp)}"


def _error(msg: str, data: Any, schema: Any, source: str, prefix: Path_) -> FfrInputError:
    text, sep, where = msg.rpartition(" - at `")
    if not sep:
        text, where = msg, "$`"
    path = _split(where.rstrip("`"))
    if "..." in path:  # inside a dict: find the key whose value fails, and report that one
        import msgspec

        k = path.index("...")
        container = _lookup(data, path[:k])
        vtype = _type_at(schema, data, [*path[:k], "..."])
        if isinstance(container, dict):
            for key, value in container.items():
                try:
                    msgspec.convert(value, vtype, strict=True)
                except msgspec.ValidationError as exc:
                    return _error(str(exc), value, vtype, source, [*prefix, *path[:k], key])
        return FfrInputError(source, _fmt(prefix + path[:k]), container, text)
    m = re.match(r"Object contains unknown field `(.*)`$", text)
    if m:
        key = m.group(1)
        struct = _unwrap(_pick(_type_at(schema, data, path), _lookup(data, path)))[0]
        import msgspec

        known = [f.encode_name for f in msgspec.structs.fields(struct)] if _is_struct(struct) else []
        return FfrInputError(source, _fmt(prefix + [*path, key]), _lookup(data, [*path, key]),
                             did_you_mean(key, known))
    m = re.match(r"Object missing required field `(.*)`$", text)
    if m:
        return FfrInputError(source, _fmt(prefix + [*path, m.group(1)]), None, "missing")
    m = re.match(r"`([^`]*)`: (.*)$", text)
    if m:  # a cross-field rule (``rule``) raised by __post_init__
        sub = _split(m.group(1))
        return FfrInputError(source, _fmt(prefix + path + sub), _lookup(data, path + sub), m.group(2))
    # a wrong value: report the field (a point's coordinate -> the point), not its element
    inner = _type_at(schema, data, path)
    if inner is not None:
        inner = _pick(inner, _lookup(data, path))
    while path and isinstance(path[-1], int):
        parent = _unwrap(_pick(_type_at(schema, data, path[:-1]), _lookup(data, path[:-1])))[0]
        if typing.get_origin(parent) is list and _is_struct(_unwrap(typing.get_args(parent)[0])[0]):
            break
        path = path[:-1]
    tp = _type_at(schema, data, path)
    value = _lookup(data, path)
    if tp is not None:
        tp = _pick(tp, value)
    if re.match(r"Expected `[^`]*` (>=|>|<=|<) ", text):
        why = _bounds(inner)
    elif text.startswith("Expected `array` of length"):
        why = f"must be {_describe(tp)}"
    elif text.startswith("Invalid enum value"):
        why = f"must be {_describe(inner)}"
    elif text.startswith("Expected ") and tp is not None:
        why = f"must be {_describe(tp)}"
    else:
        why = text
    return FfrInputError(source, _fmt(prefix + path) or "(file)", value, why)
