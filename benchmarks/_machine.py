"""What every benchmark prints first: the CPU, and the instruction-set paths numpy, OpenBLAS and numba take.

Speed ratios depend on the CPU (these benchmarks have run on an AMD EPYC and on
an Intel Xeon with AVX-512), and on a given CPU on which SIMD paths the
libraries dispatch to.  A machine without AVX-512 (an AMD EPYC of the Zen 2 or
Zen 3 generations) can be imitated on one that has it: numpy skips its
AVX-512 kernels with ``NPY_DISABLE_CPU_FEATURES="X86_V4 AVX512_ICL
AVX512_SPR"``, OpenBLAS takes its Zen kernels with ``OPENBLAS_CORETYPE=Zen``,
and numba compiles for Zen 2 with ``NUMBA_CPU_NAME=znver2``.  That imitates
the instruction paths, not the other CPU's clock, caches or latencies: the
line printed here says which was run.
"""

from __future__ import annotations

import os
import platform
from pathlib import Path


def cpu_name() -> str:
    """The CPU's model name from /proc/cpuinfo (or what ``platform`` knows)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def simd_paths() -> str:
    """numpy's widest dispatched x86 level, and the OpenBLAS and numba targets asked for in the environment."""
    try:
        from numpy._core._multiarray_umath import __cpu_features__ as features
    except ImportError:  # numpy < 2
        from numpy.core._multiarray_umath import __cpu_features__ as features
    if features.get("X86_V4") or features.get("AVX512_SKX"):
        level = "AVX-512 (X86_V4)"
    elif features.get("X86_V3") or features.get("AVX2"):
        level = "AVX2 (X86_V3)"
    else:
        level = "baseline"
    disabled = os.environ.get("NPY_DISABLE_CPU_FEATURES")
    parts = [f"numpy SIMD {level}" + (f" [NPY_DISABLE_CPU_FEATURES={disabled}]" if disabled else "")]
    parts.append(f"OpenBLAS {os.environ.get('OPENBLAS_CORETYPE', 'auto')}")
    parts.append(f"numba target {os.environ.get('NUMBA_CPU_NAME', 'host')}")
    return ", ".join(parts)


def machine_line() -> str:
    """One line: CPU, cores, SIMD paths, load average."""
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return f"CPU: {cpu_name()}, {os.cpu_count()} cores; {simd_paths()}; load average {load:.1f}"
