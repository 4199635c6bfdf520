#!/usr/bin/env bash
# CI: install every example plugin in plugins/ (editable) and run its tests.
# Called by .ci/run after lgraph itself is installed; needs no network beyond
# PyPI (pip may fetch setuptools for the isolated build) and, for the TikZ
# compile test, Debian's TeX packages.
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
# plugins whose third-party dependencies may be missing from the package index:
# when they cannot be installed, their tests are skipped (with a message), not failed
optional=" vpype-lgraph "
skipped=" "
# a TeX system for the TikZ plugin's compile test (pdflatex, tikz); optional
if ! command -v pdflatex >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
  echo "ci: installing TeX (texlive-latex-base, texlive-pictures) for the TikZ compile test"
  tex="texlive-latex-base texlive-pictures"
  (timeout 900 apt-get install -y -qq --no-install-recommends $tex >/dev/null 2>&1 \
    || (timeout 120 apt-get update -qq >/dev/null 2>&1 \
        && timeout 900 apt-get install -y -qq --no-install-recommends $tex >/dev/null 2>&1)) \
    || echo "ci: TeX could not be installed; the TikZ compile tests will be skipped"
fi
for dir in plugins/*/; do
  name="$(basename "$dir")"
  [ -f "$dir/pyproject.toml" ] || continue
  echo "ci: plugin $name: install"
  if ! timeout 900 python -m pip install -q -e "$dir"; then
    if [[ "$optional" == *" $name "* ]]; then
      echo "ci: plugin $name: its dependencies could not be installed (package index" \
           "unreachable?); its tests are skipped"
      skipped="$skipped$name "
      continue
    fi
    echo "ci: plugin $name: install failed"
    exit 1
  fi
done
# test after all are installed: each plugin's tests then also run beside the others
for dir in plugins/*/; do
  name="$(basename "$dir")"
  [ -d "$dir/tests" ] || continue
  if [[ "$skipped" == *" $name "* ]]; then
    echo "ci: plugin $name: tests skipped (not installed)"
    continue
  fi
  echo "ci: plugin $name: tests"
  python -m pytest "plugins/$name/tests" "plugins/$name/src" -q -p no:cacheprovider || status=1
done
exit $status
