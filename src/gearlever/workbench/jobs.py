"""Synthesis jobs of the workbench: one at a time, each in its own process, with progress and cancel.

:class:`JobRunner` starts a job (:func:`gearlever.workbench.engine.run_job`)
in a spawned process and follows it from a thread: the process sends
``("progress", stage, done, total)`` messages and then ``("done", results)``
or ``("failed", message)`` over a pipe.  A second job while one runs is
refused (the app answers 409 with the running job's id).  Cancel kills the
job's process: it stops at once, whatever the search is doing, and it
writes nothing (a job only answers designs as text; the page inserts one).
With a dask.distributed scheduler address (``--scheduler``) the path, curve
and law searches send their starts to that cluster
(:func:`gearlever.synthesis._dask.run_starts`); function and motion
synthesis are closed-form and run in the job's process.

The app streams a job's answer as server-sent events
(``GET /api/jobs/{id}/events``) whenever it changes.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import secrets
import threading
import time
from dataclasses import dataclass, field

__all__ = ["Job", "JobRunner", "MAX_KEPT", "MAX_JOB_SECONDS"]

#: Finished jobs kept for GET (the oldest are dropped).
MAX_KEPT = 20
#: Longest a job may run (s): past it the job is stopped and fails naming the cap.
MAX_JOB_SECONDS = 900.0


def _job_main(params: dict, conn, scheduler) -> None:
    """A job's process: check, run, send progress and the outcome."""
    import os
    import signal
    import warnings

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the whole group: the server stops us
    os.environ.setdefault("MPLBACKEND", "Agg")
    warnings.simplefilter("ignore")
    from gearlever.errors import GearleverError
    from gearlever.workbench import engine

    def progress(stage, done, total):
        conn.send(("progress", stage, done, total))

    try:
        checked = engine.check_job(params)
        results = engine.run_job(checked, progress=progress, scheduler=scheduler)
        conn.send(("done", results))
    except (GearleverError, ValueError, OverflowError) as exc:
        conn.send(("failed", " ".join(str(exc).split()) or type(exc).__name__))
    except Exception as exc:  # noqa: BLE001 - a bug: one line, no traceback
        conn.send(("failed", f"internal error (please report): {type(exc).__name__}: {' '.join(str(exc).split())}"))
    finally:
        with contextlib.suppress(Exception):
            conn.close()


@dataclass
class Job:
    """A synthesis job and what is known of it."""

    id: str
    kind: str
    state: str = "running"
    stage: str = "starting"
    done: int = 0
    total: int = 1
    results: list = field(default_factory=list)
    error: str = ""
    started: float = field(default_factory=time.monotonic)
    seconds: float = 0.0
    process: object = field(default=None, repr=False)
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def answer(self) -> dict:
        """The JSON answer of ``GET /api/jobs/{id}``."""
        with self.lock:
            out = {
                "id": self.id,
                "kind": self.kind,
                "state": self.state,
                "progress": {"stage": self.stage, "done": self.done, "total": self.total},
                "seconds": round(self.seconds if self.state != "running" else time.monotonic() - self.started, 2),
            }
            if self.state == "done":
                out["results"] = list(self.results)
            if self.error:
                out["error"] = self.error
            return out


class JobRunner:
    """One job at a time; each in a spawned process followed by a thread."""

    def __init__(self, scheduler: str | None = None, max_seconds: float = MAX_JOB_SECONDS):
        self.scheduler = scheduler
        self.max_seconds = max_seconds
        self._jobs: dict[str, Job] = {}
        self._lock = threading.Lock()
        self._ctx = multiprocessing.get_context("spawn")
        self._closed = False

    def running(self) -> str | None:
        """The id of the running job, or None."""
        with self._lock:
            for job in self._jobs.values():
                if job.state == "running":
                    return job.id
        return None

    def get(self, job_id: str) -> Job | None:
        with self._lock:
            return self._jobs.get(job_id)

    def start(self, params: dict) -> str:
        """Start a job (checked by the caller); its id.  Raises RuntimeError when one runs."""
        with self._lock:
            if self._closed:
                raise RuntimeError("the bench is stopping")
            if any(j.state == "running" for j in self._jobs.values()):
                raise RuntimeError("a job is running")
            job = Job(id=secrets.token_hex(8), kind=str(params.get("kind")))
            parent, child = self._ctx.Pipe(duplex=False)
            proc = self._ctx.Process(
                target=_job_main, args=(params, child, self.scheduler), daemon=True, name=f"gearlever-job-{job.id}"
            )
            job.process = proc
            self._jobs[job.id] = job
            finished = [j for j in self._jobs.values() if j.state != "running"]
            for old in finished[: max(0, len(self._jobs) - MAX_KEPT)]:
                del self._jobs[old.id]
        proc.start()
        child.close()
        threading.Thread(target=self._follow, args=(job, parent), daemon=True, name=f"follow-{job.id}").start()
        return job.id

    def _finish(self, job: Job, state: str, error: str = "", results=None) -> None:
        with job.lock:
            if job.state != "running":
                return
            job.state = state
            job.error = error
            if results is not None:
                job.results = results
            job.seconds = time.monotonic() - job.started

    def _follow(self, job: Job, conn) -> None:
        deadline = job.started + self.max_seconds
        try:
            while job.state == "running":
                left = deadline - time.monotonic()
                if left <= 0:
                    self._stop(job)
                    self._finish(job, "failed", f"stopped after the cap of {self.max_seconds:g} s per job")
                    return
                try:
                    if not conn.poll(min(left, 0.2)):
                        continue
                    msg = conn.recv()
                except (EOFError, OSError):
                    self._finish(job, "failed", "the job's process ended without an answer")
                    return
                if msg[0] == "progress":
                    with job.lock:
                        job.stage, job.done, job.total = msg[1], msg[2], msg[3]
                elif msg[0] == "done":
                    self._finish(job, "done", results=msg[1])
                else:
                    self._finish(job, "failed", msg[1])
        finally:
            with contextlib.suppress(Exception):
                conn.close()
            proc = job.process
            if proc is not None:
                proc.join(5)
                if proc.is_alive():
                    self._stop(job)

    @staticmethod
    def _stop(job: Job) -> None:
        proc = job.process
        if proc is not None and proc.is_alive():
            proc.terminate()
            proc.join(2)
            if proc.is_alive():
                proc.kill()
                proc.join(2)

    def cancel(self, job_id: str) -> bool:
        """Stop a running job (its process is ended); False if it had already ended."""
        job = self.get(job_id)
        if job is None or job.state != "running":
            return False
        self._finish(job, "cancelled")
        self._stop(job)
        return True

    def close(self) -> None:
        """Stop every running job (the server is stopping)."""
        with self._lock:
            self._closed = True
            jobs = list(self._jobs.values())
        for job in jobs:
            if job.state == "running":
                self._finish(job, "cancelled", "the bench stopped")
                self._stop(job)
