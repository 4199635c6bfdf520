#!/usr/bin/env bash
# CI: install every example plugin in plugins/ (editable) and run its tests.
# Called by .ci/run after lgraph itself is installed; needs no network beyond
# PyPI (pip may fetch setuptools for the isolated build).
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
for dir in plugins/*/; do
  name="$(basename "$dir")"
  [ -f "$dir/pyproject.toml" ] || continue
  echo "ci: plugin $name: install"
  python -m pip install -q -e "$dir"
done
# test after all are installed: each plugin's tests then also run beside the others
for dir in plugins/*/; do
  name="$(basename "$dir")"
  [ -d "$dir/tests" ] || continue
  echo "ci: plugin $name: tests"
  python -m pytest "plugins/$name/tests" "plugins/$name/src" -q -p no:cacheprovider || status=1
done
exit $status
