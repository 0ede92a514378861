"""Scale-out of the synthesis starts on dask: local threads or a running dask.distributed cluster.

The work is partitioned by seed and start, never by worker: start ``k``
draws from ``numpy.random.default_rng([seed, k])``, a chunk of
:data:`CHUNK` consecutive starts is one task, and the results are reduced
deterministically (sorted by objective, then start index).  The answer is
therefore the same, bit for bit, for any number of workers and on any
scheduler.
"""

from __future__ import annotations

import math

from gearlever.errors import GearleverError

__all__ = ["run_starts", "CHUNK", "CONNECT_TIMEOUT"]

#: Starts per dask task.
CHUNK = 2
#: Seconds to wait for a dask.distributed scheduler before giving up.
CONNECT_TIMEOUT = 5


def _chunks(n: int):
    return [list(range(i, min(i + CHUNK, n))) for i in range(0, n, CHUNK)]


def _order(results):
    return sorted(results, key=lambda r: (r[0] if math.isfinite(r[0]) else math.inf, r[1]))


def _connect(address: str):
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - distributed is a dependency
        raise GearleverError("scheduler: dask.distributed is not installed") from None
    try:
        return Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise GearleverError(
            f"scheduler {address!r}: cannot connect to a dask scheduler within {CONNECT_TIMEOUT} s ({reason})"
        ) from None


def run_starts(spec, seed, n_starts, evals, method="de", *, workers=None, scheduler=None, progress=None, fn=None):
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
    return _order([r for chunk in out for r in chunk])
