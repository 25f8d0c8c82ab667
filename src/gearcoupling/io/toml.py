"""TOML in: strict reading of spec and study files, dotted overrides.

One reader for every TOML file gearcoupling takes: each key is read once, a key left over
is refused (with the closest allowed key), and when the file's text is known an error
names ``file:line``.
"""

from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
from pathlib import Path
from typing import Any

from ..arguments import parse_number
from ..errors import SpecError


def line_of(text: str | None, needle: str, start: int = 0) -> int:
    """First line (1-based) at or after ``start`` holding ``needle``; ``start`` if none."""
    for n, line in enumerate((text or "").splitlines(), 1):
        if n >= start and needle in line:
            return n
    return start


def read_toml(path: str | os.PathLike) -> tuple[dict[str, Any], str]:
    """The parsed data and the text of a UTF-8 TOML file; a file that cannot be read or
    parsed is a :class:`SpecError` naming ``file:line``."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
        return tomllib.loads(text), text
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
        value = tomllib.loads(f"v = {raw.strip()}")["v"]
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
