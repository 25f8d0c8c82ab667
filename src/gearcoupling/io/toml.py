"""TOML in: strict reading of spec and study files, dotted overrides.

One reader for every TOML file gearcoupling takes: each key is read once, a key left over
is refused (with the closest allowed key), and when the file's text is known an error
names ``file:line``. Text nested deeper than :data:`MAX_NESTING` levels is refused before
it is parsed (Python's TOML reader recurses once per level of arrays and inline tables,
and its time grows with the square of a dotted key's length).
"""

from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..arguments import parse_number
from ..errors import SpecError

#: the deepest nesting of tables and arrays in a spec or study file (a spec needs 4, a
#: study 6); the text is checked before it is parsed and the data after
MAX_NESTING = 32
_NESTING = (f"at most {MAX_NESTING} levels of tables, arrays and dotted keys in a spec or "
            "study file")
_LONG_STRINGS = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'')
_STRINGS = re.compile(r'"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*')
# the bytes a dotted key is written with (its strings replaced by ""): k dots in a run of
# them nest k tables in the root
_KEY_BYTES = np.zeros(256, dtype=bool)
_KEY_BYTES[[ord(c) for c in "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
            "0123456789_-\" \t."]] = True


def line_of(text: str | None, needle: str, start: int = 0) -> int:
    """First line (1-based) at or after ``start`` holding ``needle``; ``start`` if none."""
    for n, line in enumerate((text or "").splitlines(), 1):
        if n >= start and needle in line:
            return n
    return start


def _too_deep(where: str, line: int | None, levels: str) -> SpecError:
    """The refusal of text nested ``levels`` deep at ``where:line`` (no line: the data)."""
    return SpecError(where if line is None else f"{where}:{line}", None, _NESTING,
                     shown=f"nested {levels} levels deep")


def _plain(text: str) -> str:
    """TOML text with every string and comment replaced by ``""`` (lines kept)."""
    plain = _LONG_STRINGS.sub(lambda m: '""' + "\n" * m.group().count("\n"), text)
    return _STRINGS.sub('""', plain)


def _brackets(code: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(at, depth)``: the positions of the brackets and braces of ``code`` and the
    arrays and inline tables open just after each."""
    opens, closes = (code == ord("[")) | (code == ord("{")), (code == ord("]")) | (code == ord("}"))
    at = np.flatnonzero(opens | closes)
    return at, np.cumsum(np.where(opens[at], 1, -1))


def _longest_key(code: np.ndarray) -> tuple[int, int]:
    """``(dots, at)``: the most dots in one run of key bytes of ``code`` and where they
    are (numbers have one dot at most)."""
    dots = np.flatnonzero(code == ord("."))
    if dots.size <= MAX_NESTING:
        return int(dots.size), int(dots[0]) if dots.size else 0
    run = np.searchsorted(np.flatnonzero(~_KEY_BYTES[code]), dots)  # the run of each dot
    counts = np.bincount(run)
    most = int(np.argmax(counts))
    return int(counts[most]), int(dots[np.searchsorted(run, most)])


def _line(code: np.ndarray, at: int) -> int:
    return int(np.count_nonzero(code[:at] == ord("\n"))) + 1


def check_nesting_text(text: str, where: str) -> None:
    """Refuse TOML text whose arrays and inline tables, or a dotted key, nest deeper than
    :data:`MAX_NESTING` (strings and comments do not count), naming ``where:line`` (the
    line where text has more than one)."""
    code = np.frombuffer(_plain(text).encode(), dtype=np.uint8)
    lines = "\n" in text.rstrip("\n")
    dots, key_at = _longest_key(code)
    if dots > MAX_NESTING:
        raise _too_deep(where, _line(code, key_at) if lines else None, f"{dots + 1} or more")
    at, depth = _brackets(code)
    if depth.size and depth.max() + 1 > MAX_NESTING:  # and the root table
        first = int(at[np.argmax(depth + 1 > MAX_NESTING)])
        raise _too_deep(where, _line(code, first) if lines else None,
                        f"{int(depth.max()) + 1} or more")


def array_lengths(text: str, key: str) -> list[tuple[int, int]]:
    """``(line, commas)`` of each array assigned to ``key`` at the start of a line of TOML
    text, counted without parsing it: an array of ``n`` values has ``n - 1`` commas, or
    ``n`` with a trailing one, so ``commas`` is a lower bound of its length."""
    plain = _plain(text).encode()
    start = re.compile(rb"(?m)^[ \t]*" + re.escape(key.encode()) + rb"[ \t]*=[ \t]*\[")
    starts = [m.end() - 1 for m in start.finditer(plain)]
    if not starts:
        return []
    code = np.frombuffer(plain, dtype=np.uint8)
    at, depth = _brackets(code)
    commas = np.flatnonzero(code == ord(","))
    comma_depth = np.concatenate([[0], depth])[np.searchsorted(at, commas)]
    found = []
    for opening in starts:
        k = int(np.searchsorted(at, opening))  # this array's bracket among them
        level = depth[k]
        closing = np.flatnonzero(depth[k:] < level)
        end = at[k + closing[0]] if closing.size else code.size
        lo, hi = np.searchsorted(commas, (opening, end))
        found.append((_line(code, opening),
                      int(np.count_nonzero(comma_depth[lo:hi] == level))))
    return found


def nesting(data: Any) -> int:
    """Levels of tables and arrays in parsed TOML ``data`` (a table of scalars is 1),
    counted without recursion."""
    deepest, todo = 0, [(data, 1)]
    while todo:
        node, level = todo.pop()
        if isinstance(node, dict | list):
            deepest = max(deepest, level)
            items = node.values() if isinstance(node, dict) else node
            todo.extend((v, level + 1) for v in items if isinstance(v, dict | list))
    return deepest


def parse_toml(text: str, where: str) -> dict[str, Any]:
    """TOML text parsed, nested at most :data:`MAX_NESTING` levels (else a
    :class:`SpecError` naming ``where``); invalid TOML raises ``TOMLDecodeError``."""
    check_nesting_text(text, where)
    data = tomllib.loads(text)
    levels = nesting(data)
    if levels > MAX_NESTING:
        raise _too_deep(where, None, str(levels))
    return data


def read_toml(path: str | os.PathLike, precheck: Callable[[str], None] | None = None
              ) -> tuple[dict[str, Any], str]:
    """The parsed data and the text of a UTF-8 TOML file; a file that cannot be read or
    parsed, or nests deeper than :data:`MAX_NESTING`, is a :class:`SpecError` naming
    ``file:line``. ``precheck(text)`` runs before the text is parsed."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
        if precheck is not None:
            precheck(text)
        return parse_toml(text, str(p)), text
    except tomllib.TOMLDecodeError as err:
        m = re.search(r"at line (\d+)", str(err))
        where = f"{p}:{m.group(1)}" if m else str(p)
        raise SpecError(where, None, f"is not valid TOML: {err}") from err
    except UnicodeDecodeError as err:
        raise SpecError(str(p), None, f"is not UTF-8 text (byte {err.start}): save it as "
                        "UTF-8") from err
    except OSError as err:
        raise SpecError(str(p), None, f"cannot be read: {err.strerror}") from err


def unknown_key(name: str, value: Any, known: tuple[str, ...] | list[str]) -> SpecError:
    """The error for a key that is not allowed, with the closest allowed one."""
    close = difflib.get_close_matches(name.rpartition(" ")[2].rpartition(".")[2], known, n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    listing = f"allowed here: {', '.join(known)}" if known else ""
    return SpecError(name, value, f"unknown key ({hint}{listing})" if hint or listing
                     else "unknown key")


def set_dotted(data: dict[str, Any], key: str, value: Any,
               siblings: dict[str, str] | None = None) -> dict[str, Any]:
    """Set the dotted ``key`` of nested tables ``data`` (in place; returned); ``None``
    removes the key. Where ``siblings`` names the other key of a pair that says the same in
    other units (``torque_Nm`` / ``torque_lbf_in``), setting one removes the other."""
    parts = key.split(".")
    node = data
    for part in parts[:-1]:
        nxt = node.setdefault(part, {})
        if not isinstance(nxt, dict):
            raise SpecError(key, value, f"'{part}' is a value, not a table")
        node = nxt
    other = (siblings or {}).get(parts[-1])
    if other is not None:
        node.pop(other, None)
    if value is None:
        node.pop(parts[-1], None)
    else:
        node[parts[-1]] = value
    return data


def parse_override(text: str) -> tuple[str, Any]:
    """A command-line override ``KEY=VALUE``; the value is read as TOML, else as a string."""
    key, sep, raw = text.partition("=")
    if not (sep and key.strip()):
        raise SpecError("--set", text, "must look like KEY=VALUE, e.g. hub.crowning.radius=80")
    try:
        value = parse_toml(f"v = {raw.strip()}", f"--set {key.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw.strip()
    if isinstance(value, int | float) and not isinstance(value, bool):
        # TOML reads 0_5 as 5 and 0x10 as 16: numbers as a person writes them only
        parse_number(raw, f"--set {key.strip()}", nonfinite=True, error=SpecError)
    return key.strip(), value


class Table:
    """One table of a TOML file, read strictly.

    Each read pops its key; :meth:`done` refuses what is left. Lengths are multiplied by
    ``scale`` (the file's unit in mm). With the file's ``source`` and ``text`` an error is
    named ``file:line key``, else by the dotted key alone. ``defaulted`` collects the
    lengths that took their default and ``given`` the lengths and arrays as the file gave
    them with their scale, ``{key: (value, scale)}`` (both shared with sub-tables).
    """

    def __init__(self, data: Any, where: str = "", *, scale: float = 1.0,
                 source: str | None = None, text: str | None = None, line: int = 0,
                 defaulted: set[str] | None = None, given: dict[str, Any] | None = None):
        self.where, self.scale, self.source, self.text, self.line = (where, scale, source,
                                                                     text, line)
        self.defaulted = set() if defaulted is None else defaulted
        self.given = {} if given is None else given
        if not isinstance(data, dict):
            self.fail(where or "file", data, "must be a TOML table")
        self.data = dict(data)

    # ----------------------------------------------------------------- naming, errors
    def name(self, key: str) -> str:
        return f"{self.where}.{key}" if self.where else key

    def fail(self, name: str, value: Any, allowed: str, line: int | None = None):
        """Raise :class:`SpecError` for the dotted ``name``."""
        raise SpecError(self._located(name, line), value, allowed)

    def _located(self, name: str, line: int | None = None) -> str:
        if self.source is None:
            return name
        n = line if line is not None else line_of(self.text, name.rsplit(".", 1)[-1],
                                                  self.line)
        return f"{self.source}:{n} {name}"

    # ----------------------------------------------------------------- tables, keys
    def table(self, key: str, default: Any = None) -> Table:
        """The sub-table ``key`` (an empty one if absent)."""
        data = self.data.pop(key, {} if default is None else default)
        line = line_of(self.text, f"[{self.name(key)}]", self.line) if self.text else 0
        return Table(data, self.name(key), scale=self.scale, source=self.source,
                     text=self.text, line=line, defaulted=self.defaulted, given=self.given)

    def has(self, key: str) -> bool:
        return key in self.data

    def done(self, known: tuple[str, ...] | list[str] = ()) -> None:
        """Refuse the first key not read (naming the closest of ``known``)."""
        if self.data:
            key = sorted(self.data)[0]
            err = unknown_key(self._located(self.name(key)), self.data[key], known)
            raise err

    # ----------------------------------------------------------------- typed values
    def get(self, key: str, kind: Any, default: Any = None, required: bool = False) -> Any:
        """The value of ``key``, of type ``kind`` (an int is taken for a float)."""
        name = self.name(key)
        if key not in self.data:
            if required:
                self.fail(name, None, "is required", self.line)
            return default
        value = self.data.pop(key)
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
            self.fail(name, value, f"must be of type {getattr(kind, '__name__', kind)}")
        return value

    def _number(self, key: str, value: Any) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float) or math.isnan(value):
            self.fail(self.name(key), value, "must be a number")
        return float(value)

    def number(self, key: str, default: float | None = None) -> float:
        """A number; required unless ``default`` is given."""
        if key not in self.data:
            if default is None:
                self.fail(self.name(key), None, "is required (a number)")
            return float(default)  # type: ignore[arg-type]
        return self._number(key, self.data.pop(key))

    def length(self, key: str, default: float | None = None) -> float:
        """A length in mm (the file's unit times ``scale``); a default is in mm."""
        if key not in self.data:
            if default is None:
                self.fail(self.name(key), None, "is required (a length)")
            self.defaulted.add(self.name(key))
            return float(default)  # type: ignore[arg-type]
        value = self._number(key, self.data.pop(key))
        self.given[self.name(key)] = (value, self.scale)
        return value * self.scale

    def angle(self, key: str, default_deg: float | None = None) -> float:
        """An angle given in degrees, in radians."""
        return math.radians(self.number(key, default_deg))

    def integer(self, key: str) -> int:
        """A required whole number."""
        value = self.data.pop(key, None)
        if not (isinstance(value, int) and not isinstance(value, bool)):
            self.fail(self.name(key), value, "is required and must be a whole number")
        return int(value)

    def string(self, key: str, default: str) -> str:
        """A string, or ``default`` if absent."""
        value = self.data.pop(key, default)
        if not isinstance(value, str):
            self.fail(self.name(key), value, "must be a string")
        return value

    def array(self, key: str, scale: float = 1.0) -> tuple[float, ...]:
        """An array of numbers, each times ``scale`` (empty if absent)."""
        value = self.data.pop(key, [])
        if not isinstance(value, list | tuple):
            self.fail(self.name(key), value, "must be an array of numbers")
        given = tuple(self._number(key, v) for v in value)
        self.given[self.name(key)] = (given, scale)
        return tuple(v * scale for v in given)

    def pair(self, si: str, other: str, factor: float) -> float | None:
        """The value of a pair of keys that say the same in SI and in other units (``other``
        is converted by ``factor``); at most one may be given; None if neither is."""
        if si in self.data and other in self.data:
            self.fail(self.name(other), self.data[other], f"give {si} or {other}, not both")
        if si in self.data:
            return self._number(si, self.data.pop(si))
        if other in self.data:
            return self._number(other, self.data.pop(other)) * factor
        return None
