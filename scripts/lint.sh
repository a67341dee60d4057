#!/usr/bin/env bash
# The formatting check (part of scripts/test.sh): ruff over the Python code, with the rules and
# the 100-column limit of pyproject.toml's [tool.ruff], and clang-format 14 over the C++ code
# (cpp/, tests/) with .clang-format (100 columns too). Any finding fails.
# `bash scripts/lint.sh --fix` applies ruff's safe fixes and clang-format's layout first.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format=$(command -v clang-format-14 || command -v clang-format || true)
[ -n "$clang_format" ] || { echo "lint: clang-format is missing (scripts/install-deps.sh installs clang-format-14)" >&2; exit 1; }
mapfile -t cxx < <(git ls-files 'cpp/*.cpp' 'cpp/*.h' 'tests/*.cpp' 'tests/*.h')
if [ "${1:-}" = --fix ]; then
    python3 -m ruff check --fix python tests scripts
    "$clang_format" -i --style=file "${cxx[@]}"
fi
python3 -m ruff check python tests scripts
echo "lint: ruff clean"
"$clang_format" --dry-run -Werror --style=file "${cxx[@]}"
echo "lint: clang-format clean (${#cxx[@]} C++ files)"
