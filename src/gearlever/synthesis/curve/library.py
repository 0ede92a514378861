"""The retrieval library of the curve synthesis: built from random mechanisms, kept in the user's cache folder.

:func:`build_library` simulates a library of random
dyadic mechanisms (about 0.6 s for the default 14 400).  A larger library
finds closer starts but takes longer, so it can be built once
(``gearlever curve library build --size N``) and stored as a compressed
``.npz`` in the cache folder (:func:`cache_folder`), named by its size, its
seed and :data:`FORMAT` (:func:`library_path`).  The synthesis loads it
(:func:`cached_library`) when a library of its size, seed and format is
there, and otherwise builds the same library in memory: the stored arrays
are the built ones bit for bit, so the designs do not depend on the cache.
A file that is unreadable, of another format or of other build settings is
not used (the library is built in memory instead).

Notes
-----
Cache folder as the XDG Base Directory Specification (freedesktop.org)
describes: ``$XDG_CACHE_HOME/gearlever``, else ``~/.cache/gearlever``;
``$GEARLEVER_CACHE`` overrides both.  Arrays stored with
:func:`numpy.savez_compressed` (no pickles, read with ``allow_pickle=False``).

>>> import os, tempfile
>>> os.environ["GEARLEVER_CACHE"] = tempfile.mkdtemp()
>>> lib, path = build_cached(300, 0)
>>> path.name, cached_library(300, 0).rms.size == lib.rms.size
('curves-library-v1-size300-seed0.npz', True)
>>> del os.environ["GEARLEVER_CACHE"]
"""

from __future__ import annotations

import os
import re
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis.curve.score import resample
from gearlever.synthesis.curve.simulate import simulate
from gearlever.synthesis.curve.topology import _topology, prune, random_sketches, random_topology

__all__ = [
    "FORMAT",
    "Library",
    "build_library",
    "descriptor",
    "library_counts",
    "build_cached",
    "cache_folder",
    "cached_library",
    "library_files",
    "library_path",
    "load_library",
    "save_library",
]

#: Most dyads of a library topology (eight joints beyond the crank: up to 12 joints).
MAX_LIBRARY_DYADS = 8
#: Library topologies and sketches per topology (built at run time with a fixed seed).
LIBRARY_TOPOLOGIES = 48
LIBRARY_SKETCHES = 300
#: Most mechanisms a library may simulate (``--size``): about 1.9 x 10^5 entries, 230 MB of memory at the peak,
#: 11 s to build, a 40 MB file (measured).
MAX_LIBRARY_SIZE = 200_000
#: Fourier harmonics of the descriptor.
HARMONICS = 12
#: Format version of a stored library: raised whenever the file layout or the library's construction changes.
FORMAT = 1
#: Largest library file read (bytes): the largest library (2 x 10^5 mechanisms) takes 40 MB.
MAX_FILE_BYTES = 2**30
#: File name of a stored library.
NAME = re.compile(r"curves-library-v(\d+)-size(\d+)-seed(\d+)\.npz")


def descriptor(curves, harmonics: int = HARMONICS) -> np.ndarray:
    """Rotation-, start-, direction- and size-invariant Fourier descriptor of curves (B, M, 2) -> (B, 2 H)."""
    c = resample(curves, 64)
    z = c[..., 0] + 1j * c[..., 1]
    z = z[:, :-1] - z[:, :-1].mean(1, keepdims=True)
    rms = np.sqrt((np.abs(z) ** 2).mean(1, keepdims=True))
    with np.errstate(invalid="ignore", divide="ignore"):
        C = np.abs(np.fft.fft(z / rms, axis=1)) / z.shape[1]
    k = np.arange(1, harmonics + 1)
    a, b = C[:, k], C[:, -k]
    return np.concatenate([a + b, np.abs(a - b)], 1)


@dataclass(frozen=True, eq=False)
class Library:
    """Pre-simulated curves: topology per entry, its sketch, descriptor and the curve's RMS radius.

    Examples
    --------
    >>> lib = build_library(0, 4, 30)
    >>> lib.descriptors.shape[1], len(lib.sketches) == lib.rms.size == lib.entry_topology.size
    (24, True)
    >>> four = lib.limited(4)
    >>> max(four.topologies[t].n for t in four.entry_topology) <= 4 < max(t.n for t in lib.topologies)
    True
    """

    topologies: list
    entry_topology: np.ndarray
    sketches: list
    descriptors: np.ndarray
    rms: np.ndarray
    #: Joints of the topology each entry was simulated in (before pruning).
    source_joints: np.ndarray

    def limited(self, max_joints: int) -> Library:
        """The entries whose (pruned) linkage has at most ``max_joints`` joints, in the same order.

        Equal, array for array, to :func:`build_library` run with that
        ``max_joints`` (the random draws do not depend on it).
        """
        ok = self.source_joints <= max_joints
        if ok.all():
            return self
        index, topos, ent = {}, [], []
        for t in self.entry_topology[ok].tolist():  # numbered in the order of their first entry, as built
            if t not in index:
                index[t] = len(topos)
                topos.append(self.topologies[t])
            ent.append(index[t])
        keep = np.flatnonzero(ok)
        return Library(
            topos,
            np.array(ent, dtype=self.entry_topology.dtype),
            [self.sketches[int(e)] for e in keep],
            self.descriptors[keep],
            self.rms[keep],
            self.source_joints[keep],
        )


def library_counts(size: int, sketches: int | None = None) -> list[int]:
    """Sketches per topology of a library of ``size`` mechanisms: ``sketches`` each (the last one fewer).

    >>> len(library_counts(14400)), library_counts(700, 300)
    (48, [300, 300, 100])
    """
    per = LIBRARY_SKETCHES if sketches is None else int(sketches)
    size = int(size)
    if not 1 <= size <= MAX_LIBRARY_SIZE:
        raise GearleverError(f"library_size must be 1 to {MAX_LIBRARY_SIZE}, got {size}")
    full, rest = divmod(size, per)
    return [per] * full + ([rest] if rest else [])


def build_library(
    seed: int = 0,
    topologies: int | None = None,
    sketches: int | None = None,
    max_joints: int = 20,
    *,
    size: int | None = None,
    progress=None,
) -> Library:
    """Random topologies x random sketches, simulated in batches; each turning moving joint is an entry.

    Parameters
    ----------
    seed : int
        Seed of the library's random draws (the synthesis uses 0).
    topologies, sketches : int, optional
        Topologies and sketches per topology (default :data:`LIBRARY_TOPOLOGIES`
        and :data:`LIBRARY_SKETCHES`).
    max_joints : int
        Entries whose pruned linkage has more joints are left out (the
        random draws are the same: see :meth:`Library.limited`).
    size : int, optional
        Mechanisms simulated in all, 1 to :data:`MAX_LIBRARY_SIZE`, in place
        of ``topologies``: ``sketches`` per topology, the last one fewer
        (:func:`library_counts`).
    progress : callable, optional
        ``progress(label, done, total)`` after each topology.

    Returns
    -------
    Library

    Examples
    --------
    >>> lib = build_library(0, 2, 50)
    >>> 0 < lib.rms.size <= 2 * 50 * 3
    True
    """
    per = LIBRARY_SKETCHES if sketches is None else int(sketches)
    if size is not None:
        counts = library_counts(size, per)
    else:
        counts = [per] * (LIBRARY_TOPOLOGIES if topologies is None else int(topologies))
    rng = np.random.default_rng([seed, 271828])
    topos, ent_t, ent_x, descs, rmss, src = [], [], [], [], [], []
    cache = {}
    for n, count in enumerate(counts):
        n_dyads = 1 + n % MAX_LIBRARY_DYADS
        n_fixed = 2 + (n // MAX_LIBRARY_DYADS) % 2
        topo = random_topology(rng, n_dyads, n_fixed)
        x0 = random_sketches(rng, topo, count)
        if progress is not None:
            progress("library", n + 1, len(counts))
        if topo.n > max_joints:
            continue  # drawn all the same, so that a smaller max_joints only leaves entries out
        x = simulate(x0, topo.plan, steps=100)
        turns = np.isfinite(x).all(axis=(1, 2, 3))
        if not turns.any():
            continue
        xs, xt = x0[turns], x[turns]
        for target in range(topo.n):
            if target in set(topo.fixed.tolist()) or target == topo.motor[1] and n_dyads > 1:
                continue
            sub, keep = prune(topo, target)
            if sub.n > max_joints:
                continue
            curves = xt[:, target]
            d = descriptor(curves)
            ok = np.isfinite(d).all(1)
            if not ok.any():
                continue
            key = sub.key()
            if key not in cache:  # numbered in the order of their first entry
                cache[key] = len(topos)
                topos.append(sub)
            c = curves[ok] - curves[ok].mean(1, keepdims=True)
            rmss.append(np.sqrt((c**2).sum(-1).mean(1)))
            descs.append(d[ok])
            ent_t.append(np.full(ok.sum(), cache[key]))
            ent_x.extend(xs[ok][:, keep])
            src.append(np.full(ok.sum(), topo.n))
    if not descs:
        z = np.zeros(0, dtype=int)
        return Library([], z, [], np.zeros((0, 2 * HARMONICS)), np.zeros(0), z)
    ent_t, descs, rmss, src = (np.concatenate(a) for a in (ent_t, descs, rmss, src))
    return Library(topos, ent_t, ent_x, descs, rmss, src)


def cache_folder() -> Path:
    """The user's cache folder of gearlever: ``$GEARLEVER_CACHE``, else ``$XDG_CACHE_HOME/gearlever``, else
    ``~/.cache/gearlever`` (it may not exist yet).

    >>> import os
    >>> os.environ["GEARLEVER_CACHE"] = "/tmp/glc"
    >>> str(cache_folder())
    '/tmp/glc'
    >>> del os.environ["GEARLEVER_CACHE"]
    """
    own = os.environ.get("GEARLEVER_CACHE")
    if own:
        return Path(own).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and os.path.isabs(xdg):  # the specification: a relative path is to be ignored
        return Path(xdg) / "gearlever"
    return Path.home() / ".cache" / "gearlever"


def library_path(size: int, seed: int = 0) -> Path:
    """Where the library of ``size`` mechanisms and ``seed`` is stored.

    >>> library_path(14400).name
    'curves-library-v1-size14400-seed0.npz'
    """
    return cache_folder() / f"curves-library-v{FORMAT}-size{int(size)}-seed{int(seed)}.npz"


def _settings(size: int, seed: int) -> np.ndarray:
    return np.array([FORMAT, size, seed, LIBRARY_SKETCHES, MAX_LIBRARY_DYADS, HARMONICS], dtype=np.int64)


def _arrays(lib, size: int, seed: int) -> dict:
    """The library as flat arrays (topologies by their edges, fixed joints, motor and traced joint)."""
    T = lib.topologies
    return {
        "settings": _settings(size, seed),
        "topology_joints": np.array([t.n for t in T], dtype=np.int64),
        "topology_edge_count": np.array([len(t.edges) for t in T], dtype=np.int64),
        "topology_edges": np.concatenate([t.edges for t in T]).astype(np.int64) if T else np.zeros((0, 2), np.int64),
        "topology_fixed_count": np.array([len(t.fixed) for t in T], dtype=np.int64),
        "topology_fixed": np.concatenate([t.fixed for t in T]).astype(np.int64) if T else np.zeros(0, np.int64),
        "topology_motor": np.array([t.motor for t in T], dtype=np.int64).reshape(-1, 2),
        "topology_target": np.array([t.target for t in T], dtype=np.int64),
        "entry_topology": np.asarray(lib.entry_topology, dtype=np.int64),
        "entry_source_joints": np.asarray(lib.source_joints, dtype=np.int64),
        "sketches": np.concatenate(lib.sketches) if lib.sketches else np.zeros((0, 2)),
        "descriptors": np.asarray(lib.descriptors, dtype=float),
        "rms": np.asarray(lib.rms, dtype=float),
    }


def save_library(lib, path, size: int, seed: int) -> Path:
    """Write ``lib`` (built with ``size`` and ``seed``) to ``path`` atomically: the whole file or none.

    The folder is created if missing.  Ctrl-C or an error on the way leaves no
    file (see :func:`gearlever._io.atomic_path`).
    """
    from gearlever._io import atomic_path

    arrays = _arrays(lib, int(size), int(seed))
    with atomic_path(path, mkdir=True) as tmp, open(tmp, "wb") as fh:
        np.savez_compressed(fh, **arrays)
    return Path(path)


def load_library(path, size: int, seed: int):
    """Read a stored library and check it: its format, size, seed and build settings must be the current ones.

    Raises
    ------
    GearleverError
        Naming the file: unreadable, not a library, other settings or format.
    """
    p = Path(path)
    try:
        if p.stat().st_size > MAX_FILE_BYTES:
            raise GearleverError(f"{p}: larger than the cap of {MAX_FILE_BYTES} bytes")
        with np.load(p, allow_pickle=False) as z:
            d = {k: z[k] for k in z.files}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
        raise GearleverError(f"{p}: not a readable library ({exc})") from None
    try:
        if not np.array_equal(d["settings"], _settings(int(size), int(seed))):
            raise GearleverError(f"{p}: built with other settings or format {d['settings'].tolist()}")
        n, ne, nf = d["topology_joints"], d["topology_edge_count"], d["topology_fixed_count"]
        eo, fo = np.concatenate([[0], np.cumsum(ne)]), np.concatenate([[0], np.cumsum(nf)])
        topos = [
            _topology(
                int(n[i]),
                d["topology_edges"][eo[i] : eo[i + 1]],
                d["topology_fixed"][fo[i] : fo[i + 1]],
                tuple(d["topology_motor"][i]),
                int(d["topology_target"][i]),
            )
            for i in range(n.size)
        ]
        et = d["entry_topology"]
        E = et.size
        if et.size and (et.min() < 0 or et.max() >= n.size):
            raise GearleverError(f"{p}: entry_topology out of range")
        rows = n[et]
        so = np.concatenate([[0], np.cumsum(rows)])
        sk = d["sketches"]
        if sk.shape != (int(so[-1]), 2) or d["descriptors"].shape[0] != E or d["rms"].shape != (E,):
            raise GearleverError(f"{p}: arrays of inconsistent shapes")
        if d["entry_source_joints"].shape != (E,):
            raise GearleverError(f"{p}: arrays of inconsistent shapes")
        sketches = np.split(sk, so[1:-1]) if E else []
    except GearleverError as exc:
        raise exc if str(exc).startswith(f"{p}: ") else GearleverError(f"{p}: {exc}") from None
    except KeyError as exc:
        raise GearleverError(f"{p}: not a library (no array {exc})") from None
    except (ValueError, IndexError, TypeError) as exc:
        raise GearleverError(f"{p}: not a library ({exc})") from None
    return Library(topos, et, sketches, d["descriptors"], d["rms"], d["entry_source_joints"])


def cached_library(size: int, seed: int = 0):
    """The stored library of ``size`` and ``seed`` if there is a usable one, else None (never an error)."""
    p = library_path(size, seed)
    if not p.is_file():
        return None
    try:
        return load_library(p, size, seed)
    except GearleverError:
        return None


def build_cached(size: int, seed: int = 0, progress=None):
    """Build the library of ``size`` mechanisms and ``seed`` and store it; return ``(library, path)``."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**31:
        raise GearleverError(f"seed must be an integer 0 to 2^31 - 1, got {seed!r}")
    lib = build_library(int(seed), size=int(size), progress=progress)
    return lib, save_library(lib, library_path(size, seed), size, seed)


def library_files() -> list[dict]:
    """The library files in the cache folder: path, size, seed, format, bytes, whether usable, and entries.

    >>> import os, tempfile
    >>> os.environ["GEARLEVER_CACHE"] = tempfile.mkdtemp()
    >>> library_files()
    []
    >>> del os.environ["GEARLEVER_CACHE"]
    """
    folder = cache_folder()
    if not folder.is_dir():
        return []
    out = []
    for p in sorted(folder.iterdir()):
        m = NAME.fullmatch(p.name)
        if m is None or not p.is_file():
            continue
        fmt, size, seed = (int(g) for g in m.groups())
        row = {"path": p, "format": fmt, "size": size, "seed": seed, "bytes": p.stat().st_size}
        row["entries"], row["problem"] = None, None
        if fmt != FORMAT:
            row["problem"] = f"format v{fmt}, this gearlever reads v{FORMAT}: not used (build it again)"
        else:
            try:
                row["entries"] = int(load_library(p, size, seed).rms.size)
            except GearleverError as exc:
                row["problem"] = f"{str(exc).removeprefix(f'{p}: ')}: not used (build it again)"
        out.append(row)
    out.sort(key=lambda r: (r["format"] != FORMAT, r["size"], r["seed"]))
    return out
