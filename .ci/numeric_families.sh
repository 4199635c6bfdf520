#!/usr/bin/env bash
# CI: the numeric line-family tests twice more (issue #11): with numpy's
# optimized CPU kernels switched off, and in a fresh virtual environment with
# the lowest numpy and scipy that pyproject.toml declares.
set -euo pipefail
cd "$(dirname "$0")/.."
tests=(tests/test_field_lines.py tests/test_numeric_curvature.py tests/test_surface_curves.py
       tests/test_parametric.py lgraph/families lgraph/curvature.py)

features="$(python .ci/npy_dispatch.py)"
echo "ci: numeric families with NPY_DISABLE_CPU_FEATURES='$features'"
NPY_DISABLE_CPU_FEATURES="$features" python - <<'PY'
try:
    from numpy._core._multiarray_umath import __cpu_dispatch__ as d, __cpu_features__ as f
except ImportError:
    from numpy.core._multiarray_umath import __cpu_dispatch__ as d, __cpu_features__ as f
on = [k for k in d if f.get(k)]
assert not on, f"dispatch still on: {on}"
print("ci: numpy dispatch targets off:", " ".join(d) or "(none)")
PY
NPY_DISABLE_CPU_FEATURES="$features" python -m pytest -q -p no:cacheprovider "${tests[@]}"

# lowest declared versions
read -r np_min sp_min < <(python - <<'PY'
import re, tomllib
deps = tomllib.load(open("pyproject.toml", "rb"))["project"]["dependencies"]
low = {re.split(r"[<>=!~ ;\[]", d)[0].lower(): re.search(r">=\s*([\w.]+)", d) for d in deps}
print(low["numpy"].group(1), low["scipy"].group(1))
PY
)
venv="${TMPDIR:-/tmp}/lgraph-min-versions"
echo "ci: numeric families with numpy==$np_min scipy==$sp_min (venv $venv)"
rm -rf "$venv"
python -m venv "$venv"
if ! { timeout 900 "$venv/bin/python" -m pip install -q "numpy==$np_min.*" "scipy==$sp_min.*" \
    && timeout 900 "$venv/bin/python" -m pip install -q -e ".[test]" "numpy==$np_min.*" "scipy==$sp_min.*"; }; then
  echo "ci: error: could not install numpy $np_min / scipy $sp_min into $venv (package index unreachable, or no wheel for this Python)" >&2
  exit 1
fi
"$venv/bin/python" -c "import numpy, scipy; print('ci: min venv has numpy', numpy.__version__, 'scipy', scipy.__version__)"
"$venv/bin/python" -m pytest -q -p no:cacheprovider "${tests[@]}"
rm -rf "$venv"
