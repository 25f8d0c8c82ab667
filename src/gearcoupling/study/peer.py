"""Whether the peer at a scheduler address is a dask scheduler, found within a timeout.

A dask scheduler speaks first: on every connection it sends its handshake, one message in
dask's framing (little-endian 8-byte integers: the message's length, its number of frames,
each frame's length, then the frames, together about 60 bytes). The probe reads that much
with a raw socket before dask's client connects: dask's own connect waits on the handshake
without a deadline (an HTTP server made ``study`` hang) and allocates whatever length the
first 8 bytes claim (``HTTP/1.0 400`` read as a length made it run out of memory).
"""

from __future__ import annotations

import socket
import struct
import time

from ..errors import BackendError, brief

#: the longest handshake accepted (a dask scheduler's is about 60 bytes)
HANDSHAKE_BYTES = 64 * 1024
#: the most frames a handshake may have (a dask scheduler's has one)
HANDSHAKE_FRAMES = 16
#: bytes of a peer's answer quoted in the error
SHOWN = 60
_RETRY_S = 0.05


def host_port(address: str) -> tuple[str, int]:
    """``(host, port)`` of ``tcp://HOST:PORT``, ``HOST:PORT`` or ``[IPv6]:PORT``."""
    host, _, port = address.removeprefix("tcp://").rpartition(":")
    return host.strip("[]"), int(port)


def _connect(address: str, deadline: float, timeout_s: float) -> socket.socket:
    """A connection to ``address``, tried again while it is refused until ``deadline`` (a
    scheduler may still be starting)."""
    while True:
        left = deadline - time.monotonic()
        try:
            return socket.create_connection(host_port(address), timeout=max(left, 1e-3))
        except OSError as err:
            if time.monotonic() + _RETRY_S >= deadline:
                raise BackendError(f"cannot reach the dask scheduler (--scheduler) at "
                                   f"{address} within {timeout_s:g} s ({type(err).__name__}: "
                                   f"{err.strerror or err}); start one with 'dask scheduler' "
                                   "or drop --scheduler") from err
            time.sleep(_RETRY_S)


def _read(sock: socket.socket, size: int, got: bytes, deadline: float) -> tuple[bytes, str]:
    """``got`` extended to ``size`` bytes before ``deadline``; with what stopped it short
    (``""`` if nothing did)."""
    while len(got) < size:
        left = deadline - time.monotonic()
        if left <= 0:
            return got, "timeout"
        sock.settimeout(left)
        try:
            chunk = sock.recv(size - len(got))
        except TimeoutError:
            return got, "timeout"
        except OSError as err:
            return got, f"{type(err).__name__}"
        if not chunk:
            return got, "closed"
        got += chunk
    return got, ""


def _not_dask(address: str, got: bytes, why: str, timeout_s: float) -> BackendError:
    if not got:
        found = (f"it accepted the connection and sent nothing in {timeout_s:g} s"
                 if why == "timeout" else f"it accepted the connection and ended it ({why}) "
                 "without a word")
    else:
        found = f"it sent {brief(repr(got[:SHOWN]), 2 * SHOWN)}"
        if got.startswith(b"HTTP/"):
            found += " (an HTTP server)"
    return BackendError(f"the scheduler (--scheduler) at {address} is not a dask scheduler: "
                        f"{found}, where a dask scheduler sends its handshake first; check the "
                        "address and port")


def probe_scheduler(address: str, timeout_s: float) -> None:
    """Refuse, within ``timeout_s``, a peer at ``address`` that cannot be reached or does
    not send a dask handshake (see the module docstring): a
    :class:`~gearcoupling.errors.BackendError` saying what it found instead."""
    deadline = time.monotonic() + timeout_s
    with _connect(address, deadline, timeout_s) as sock:
        head, why = _read(sock, 16, b"", deadline)
        if why:
            raise _not_dask(address, head, why, timeout_s)
        length, frames = struct.unpack("<QQ", head)
        if not (16 <= length + 8 <= HANDSHAKE_BYTES and 1 <= frames <= HANDSHAKE_FRAMES
                and 8 + 8 * frames <= length):
            shown, _ = _read(sock, SHOWN, head, min(deadline, time.monotonic() + 0.2))
            raise _not_dask(address, shown, "", timeout_s)
        body, why = _read(sock, 8 + length, head, deadline)
        if why:
            raise _not_dask(address, body, why, timeout_s)
        sizes = struct.unpack(f"<{frames}Q", body[16:16 + 8 * frames])
        if 8 + 8 * frames + sum(sizes) != length:
            raise _not_dask(address, body, "", timeout_s)
