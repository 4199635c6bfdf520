"""Print the CPU dispatch targets of the installed numpy (for NPY_DISABLE_CPU_FEATURES).

numpy documents NPY_DISABLE_CPU_FEATURES for switching its optimized kernels
off at run time; the names differ between numpy versions, so ask numpy.
"""

from __future__ import annotations

try:
    from numpy._core._multiarray_umath import __cpu_dispatch__ as dispatch
except ImportError:  # numpy < 2
    from numpy.core._multiarray_umath import __cpu_dispatch__ as dispatch

print(" ".join(dispatch))
