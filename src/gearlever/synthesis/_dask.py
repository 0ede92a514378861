"""Scale-out of the synthesis starts on dask: local threads or a running dask.distributed cluster.

The work is partitioned by seed and start, never by worker: start ``k``
draws from ``numpy.random.default_rng([seed, k])``, a chunk of
:data:`CHUNK` consecutive starts is one task, and the results are reduced
deterministically (sorted by objective at :data:`TIE_DIGITS` digits, then
start index).  The answer is therefore the same, bit for bit, for any number
of workers and on any scheduler.
"""

from __future__ import annotations

import math
import re

from gearlever.errors import GearleverError

__all__ = ["run_starts", "check_address", "CHUNK", "CONNECT_TIMEOUT", "SCHEMES"]

#: Starts per dask task.
CHUNK = 2
#: Seconds to wait for a dask.distributed scheduler before giving up.
CONNECT_TIMEOUT = 5


def _chunks(n: int):
    return [list(range(i, min(i + CHUNK, n))) for i in range(0, n, CHUNK)]


#: Significant digits at which two starts' objectives are compared; objectives
#: below :data:`TIE_FLOOR` of the largest finite one are equal (zero).
TIE_DIGITS = 6
TIE_FLOOR = 1e-12


def _order(results, tie: float | None = None):
    """Results sorted by objective, then start index; equally good starts keep their index order.

    The last digits of an objective differ between machines (OpenBLAS picks its
    kernels by CPU): compared at :data:`TIE_DIGITS` digits, and with exact
    solutions (objectives at rounding level) all equal, the start chosen is
    the same on every machine.  ``tie``: the objective below which a start
    is exact (default :data:`TIE_FLOOR` of the largest finite objective).
    """
    from gearlever._format import quantize

    fin = [abs(r[0]) for r in results if math.isfinite(r[0])]
    floor = float(tie) if tie is not None else (TIE_FLOOR * max(fin) if fin else 0.0)

    def key(r):
        f = r[0]
        if not math.isfinite(f):
            return (math.inf, r[1])
        return (0.0 if abs(f) <= floor else quantize(f, 0.0, TIE_DIGITS), r[1])

    return sorted(results, key=key)


#: Address schemes of a dask.distributed scheduler that can be reached from here.
SCHEMES = ("tcp", "tls", "ws", "wss")
_ADDRESS = re.compile(
    r"(?:(?P<scheme>[A-Za-z][A-Za-z0-9+.-]*)://)?(?P<host>\[[0-9A-Fa-f:.]+\]|[^\s:/\[\]]+):(?P<port>\d{1,5})"
)


def check_address(address) -> tuple:
    """``(scheme, host, port)`` of a scheduler address ``[SCHEME://]HOST:PORT``, or a refusal naming ``scheduler``.

    >>> check_address("tcp://127.0.0.1:8786")
    ('tcp', '127.0.0.1', 8786)
    >>> try:
    ...     check_address("nonsense")
    ... except GearleverError as exc:
    ...     print(str(exc)[:72])
    scheduler 'nonsense' must be an address [SCHEME://]HOST:PORT (scheme tcp
    """
    form = "must be an address [SCHEME://]HOST:PORT (scheme tcp, tls, ws or wss; e.g. tcp://127.0.0.1:8786)"
    if isinstance(address, str) and address.startswith("inproc://") and len(address) > len("inproc://"):
        return "inproc", address[len("inproc://") :], 0  # a scheduler in this process (LocalCluster(processes=False))
    m = _ADDRESS.fullmatch(address) if isinstance(address, str) else None
    if m is None:
        raise GearleverError(f"scheduler {address!r} {form}")
    scheme = (m.group("scheme") or "tcp").lower()
    if scheme not in SCHEMES:
        raise GearleverError(f"scheduler {address!r}: unknown scheme {scheme!r}; {form}")
    port = int(m.group("port"))
    if not 1 <= port <= 65535:
        raise GearleverError(f"scheduler {address!r}: the port must be 1..65535, got {port}")
    return scheme, m.group("host").strip("[]"), port


def _connect(address: str):
    """A client of the scheduler at ``address``, or one line naming it: bad form, nothing there, not dask.

    The address is checked first; then a client is made with a short
    timeout (:data:`CONNECT_TIMEOUT`).  A client that fails to connect is
    shut down here, quickly and quietly (left to the garbage collector, it
    would wait twice the timeout and print a traceback at exit).
    """
    check_address(address)
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - distributed is a dependency
        raise GearleverError("scheduler: dask.distributed is not installed") from None

    class _Client(Client):
        def __del__(self):  # a client that never connected has nothing to close gracefully
            if getattr(self, "status", None) == "running":
                super().__del__()
            else:
                _quiet_stop(self)

    try:
        return _Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except KeyboardInterrupt:
        raise
    except Exception as exc:  # noqa: BLE001 - whatever answered (or did not), it is not a usable scheduler
        if isinstance(exc, MemoryError):  # a peer that is not dask: its first bytes read as a frame length
            reason = "something answered that does not speak dask's protocol"
        else:
            reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise GearleverError(
            f"scheduler {address!r}: no dask scheduler answered within {CONNECT_TIMEOUT:g} s ({reason})"
        ) from None


def _quiet_stop(client) -> None:
    """Stop a client that failed to connect: its event-loop thread ends, no close handshake, nothing printed."""
    try:
        client.status = "closed"
        runner = getattr(client, "_loop_runner", None)
        if runner is not None:
            runner.stop()
    except Exception:  # noqa: BLE001 - best effort at garbage collection
        pass


def run_starts(
    spec, seed, n_starts, evals, method="de", *, workers=None, scheduler=None, progress=None, fn=None, tie=None
):
    """Run ``n_starts`` seeded starts in chunks on dask; results sorted by (objective, start).

    Parameters
    ----------
    spec : dict
        Keyword arguments of the problem (plain lists and numbers: sent to workers).
    seed, n_starts, evals : int
        Seed, number of starts, evaluations per start.
    method : str
    workers : int, optional
        Local threads (ignored with ``scheduler``).
    scheduler : str, optional
        Address of a running dask.distributed scheduler.
    progress : callable, optional
        ``progress("starts", done, total)`` after each finished chunk.
    fn : callable, optional
        Chunk function ``fn(spec, seed, ks, evals, method) -> list`` (default
        :func:`gearlever.synthesis.path.run_chunk`).
    tie : float, optional
        Objective at or below which a start counts as exact (see :func:`_order`): exact starts are
        taken in start order, whatever the last digits of their objectives.
    """
    from gearlever.synthesis._search import STOP

    if fn is None:
        from gearlever.synthesis.path import run_chunk as fn
    STOP.clear()
    chunks = _chunks(n_starts)
    total = len(chunks)
    if scheduler is not None:
        client = _connect(scheduler)
        try:
            futs = [client.submit(fn, spec, seed, ks, evals, method, pure=False) for ks in chunks]
            out = []
            try:
                for done, fut in enumerate(futs, 1):
                    out.append(fut.result())
                    if progress is not None:
                        progress("starts", done, total)
            except KeyboardInterrupt:
                client.cancel(futs)
                raise
        finally:
            client.close()
    else:
        import dask
        from dask.callbacks import Callback

        class _Tick(Callback):
            def __init__(self):
                super().__init__()
                self.done = 0

            def _posttask(self, key, result, dsk, state, id):
                if isinstance(result, list) and progress is not None:
                    self.done += 1
                    progress("starts", self.done, total)

        tasks = [dask.delayed(fn, pure=False)(spec, seed, ks, evals, method) for ks in chunks]
        try:
            with _Tick():
                out = dask.compute(*tasks, scheduler="threads", num_workers=workers)
        except KeyboardInterrupt:
            STOP.set()  # the worker threads end their searches at the next generation
            raise
    return _order([r for chunk in out for r in chunk], tie)
