"""The one error hierarchy of gearcoupling, based on builtin exceptions."""

from __future__ import annotations

#: characters of a field name and of a value's repr quoted in a message, and of the
#: allowed text (a 10 MB spec value makes a message of about a line, not of 10 MB)
FIELD_CHARS, VALUE_CHARS, ALLOWED_CHARS = 200, 200, 1000


def brief(text: str, most: int) -> str:
    """``text`` cut to ``most`` characters, saying how long it was."""
    return text if len(text) <= most else f"{text[:most]}... ({len(text)} characters)"


def _message(field: object, value: object, allowed: object, shown: str | None = None) -> str:
    quoted = repr(value) if shown is None else shown
    return (f"{brief(str(field), FIELD_CHARS)} = {brief(quoted, VALUE_CHARS)}: "
            f"{brief(str(allowed), ALLOWED_CHARS)}")


class GearCouplingError(Exception):
    """Base class of every error gearcoupling raises on purpose."""


class _Refusal(GearCouplingError, ValueError):
    """A refused value: the message names the field, the value and what is allowed;
    ``shown`` quotes the value where ``repr(value)`` is not what the user gave."""

    def __init__(self, field: str, value: object, allowed: str, shown: str | None = None):
        self.field = field
        self.value = value
        self.allowed = allowed
        self.shown = shown
        super().__init__(_message(field, value, allowed, shown))

    def __reduce__(self):  # pickled to and from worker processes with its fields
        return type(self), (self.field, self.value, self.allowed, self.shown)


class SpecError(_Refusal):
    """An invalid spec or study file value or combination, raised as ``SpecError(field,
    value, allowed)``; a length of an inch file is shown as given with its mm value beside
    it (``0.1 in (2.54 mm)``)."""


class GeometryError(GearCouplingError, ValueError):
    """A geometric query outside the domain where the surface exists (e.g. off the flank)."""


class BackendError(GearCouplingError, RuntimeError):
    """An optional back-end is missing or failed; the message says what to install or change."""


class ArgumentError(_Refusal):
    """An invalid argument of a library call or command line (not a value of a spec or
    study file), raised as ``ArgumentError(field, value, allowed)`` like :class:`SpecError`.
    The CLI maps it to exit status 2."""
