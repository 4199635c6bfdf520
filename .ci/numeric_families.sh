#!/usr/bin/env bash
# CI: the numeric line-family tests twice more (issue #11): with numpy's
# optimized CPU kernels switched off, and in a fresh virtual environment with
# the lowest numpy and scipy that pyproject.toml declares.
set -euo pipefail
cd "$(dirname "$0")/.."
# (and the shared root finder on scipy's elementwise find_root, issue 12: its users
# are the ruled surfaces and the numeric contours; and the ray tests and transition
# functions of the monkey saddle and the surfaces of revolution; and many views
# rendered together, each as alone, issue 14; the contours and edges near the
# singular lines of a parametrization, issue 25; the self-intersections of Boy's
# surface and the Klein bottle, the flips at a numeric surface's own contour, and the
# flips and depth changes located on the net, on another sheet, on the own contour)
tests=(tests/test_field_lines.py tests/test_numeric_curvature.py tests/test_surface_curves.py
       tests/test_parametric.py lgraph/families lgraph/curvature.py
       tests/test_roots.py tests/test_ruled.py lgraph/_roots.py
       tests/test_polyroots.py tests/test_monkey_saddle_margins.py tests/test_surface_memo.py
       tests/test_revolution_fast.py tests/test_revolution_visibility.py
       tests/test_render_views.py tests/test_singular_edges.py
       "tests/test_onesided.py::test_boy_surface_self_intersection_is_three_equal_loops_through_the_triple_point"
       "tests/test_onesided.py::test_klein_bottle_self_intersection_is_one_closed_curve"
       "tests/test_certain_hidden_numeric.py::test_flips_at_a_numeric_surfaces_own_contour_are_exact"
       "tests/test_certain_hidden_numeric.py::test_flips_behind_a_numeric_contour_lie_on_it"
       "tests/test_certain_hidden_numeric.py::test_changes_where_a_line_passes_through_another_sheet_are_exact"
       "tests/test_certain_hidden_numeric.py::test_depth_changes_at_a_numeric_surfaces_own_contour")

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
# each pip step: at most 15 minutes in all, 60 s per network request, 2 retries
pip_min() { timeout 900 "$venv/bin/python" -m pip install -q --timeout 60 --retries 2 "$@"; }
pins=("numpy==$np_min.*" "scipy==$sp_min.*")
if ! pip_min "${pins[@]}"; then
  echo "ci: error: could not install ${pins[*]} into $venv for $("$venv/bin/python" --version)" \
       "(package index unreachable, pip timed out after 900 s, or no wheel for this Python)" >&2
  exit 1
fi
if ! pip_min -e ".[test]" "${pins[@]}"; then
  echo "ci: error: could not install lgraph[test] with ${pins[*]} into $venv" \
       "(a test dependency needs newer numpy/scipy, the index is unreachable, or pip timed out)" >&2
  exit 1
fi
"$venv/bin/python" -c "import numpy, scipy; print('ci: min venv has numpy', numpy.__version__, 'scipy', scipy.__version__)"
"$venv/bin/python" -m pytest -q -p no:cacheprovider "${tests[@]}"
rm -rf "$venv"
