"""Scale-out of the synthesis starts on dask: local threads or a running dask.distributed cluster.

The work is partitioned by seed and start, never by worker: start ``k``
draws from ``numpy.random.default_rng([seed, k])``, a chunk of
:data:`CHUNK` consecutive starts is one task, and the results are reduced
deterministically (sorted by objective at :data:`TIE_DIGITS` digits, then
start index).  The answer is therefore the same, bit for bit, for any number
of workers and on any scheduler.  The reduction and the records of the starts
are :mod:`gearlever.synthesis.driver`'s; this module only runs chunks of them.

A leaf: imports :mod:`gearlever.errors` and :mod:`gearlever.synthesis._search`
(dask and dask.distributed when work is run).
"""

from __future__ import annotations

import numbers
import re

from gearlever.errors import GearleverError
from gearlever.synthesis._search import STOP

__all__ = ["run_tasks", "check_address", "CHUNK", "CONNECT_TIMEOUT", "SCHEMES"]

#: Starts per dask task.
CHUNK = 2
#: Seconds to wait for a dask.distributed scheduler before giving up.
CONNECT_TIMEOUT = 5


def _chunks(n: int):
    return [list(range(i, min(i + CHUNK, n))) for i in range(0, n, CHUNK)]


#: Significant digits at which two starts' objectives are compared; objectives
#: below :data:`TIE_FLOOR` of the largest finite one are equal (zero) (see
#: :func:`gearlever.synthesis.driver.order`).
TIE_DIGITS = 6
TIE_FLOOR = 1e-12


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


def _workers(workers) -> tuple:
    """``(threads, scheduler, mapper)`` of a ``workers`` value: an int, a map-like or a scheduler address."""
    if workers is None or (isinstance(workers, numbers.Integral) and not isinstance(workers, bool)):
        return workers, None, None
    if isinstance(workers, str):
        return None, workers, None
    if callable(getattr(workers, "map", None)):
        return None, None, workers
    raise GearleverError(
        f"workers must be a number of threads, a map-like (with .map) or a scheduler address, got {workers!r}"
    )


def run_tasks(fn, args: tuple, n_starts: int, evals: int, method: str = "de", *, workers=None, progress=None) -> list:
    """``fn(*args, ks, evals, method)`` for chunks ``ks`` of :data:`CHUNK` starts; the chunks' lists joined in order.

    Parameters
    ----------
    fn : callable
        Chunk function returning a list (module-level, for a scheduler).
    args : tuple
        Its leading arguments (plain data or module-level callables: sent to workers).
    n_starts, evals : int
        Number of starts, evaluations per start.
    method : str
    workers : int, map-like or str, optional
        Local dask threads (an int; default dask's default), anything with a
        ``.map`` (called in chunk order), or the address of a running
        dask.distributed scheduler (:func:`check_address`).
    progress : callable, optional
        ``progress("starts", done, total)`` after each finished chunk.

    Examples
    --------
    >>> def chunk(base, ks, evals, method):
    ...     return [base + k for k in ks]
    >>> run_tasks(chunk, (10,), 5, 1, workers=1)
    [10, 11, 12, 13, 14]
    >>> from concurrent.futures import ThreadPoolExecutor
    >>> with ThreadPoolExecutor(2) as pool:
    ...     run_tasks(chunk, (10,), 5, 1, workers=pool)
    [10, 11, 12, 13, 14]
    """
    threads, scheduler, mapper = _workers(workers)
    STOP.clear()
    chunks = _chunks(n_starts)
    total = len(chunks)
    if scheduler is not None:
        client = _connect(scheduler)
        try:
            futs = [client.submit(fn, *args, ks, evals, method, pure=False) for ks in chunks]
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
    elif mapper is not None:
        out = []
        try:
            for done, res in enumerate(mapper.map(_Call(fn, args, evals, method), chunks), 1):
                out.append(res)
                if progress is not None:
                    progress("starts", done, total)
        except KeyboardInterrupt:
            STOP.set()
            raise
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

        tasks = [dask.delayed(fn, pure=False)(*args, ks, evals, method) for ks in chunks]
        try:
            with _Tick():
                out = dask.compute(*tasks, scheduler="threads", num_workers=threads)
        except KeyboardInterrupt:
            STOP.set()  # the worker threads end their searches at the next generation
            raise
    return [r for chunk in out for r in chunk]


class _Call:
    """``fn(*args, ks, evals, method)`` as a one-argument callable of ``ks`` (picklable for process pools)."""

    def __init__(self, fn, args, evals, method):
        self.fn, self.args, self.evals, self.method = fn, args, evals, method

    def __call__(self, ks):
        return self.fn(*self.args, ks, self.evals, self.method)
