#!/usr/bin/env bash
# The formatting check (part of scripts/test.sh): ruff over the Python code, with the rules and
# the 100-column limit of pyproject.toml's [tool.ruff] (the C++ limit of .clang-format). Any
# finding fails. `bash scripts/lint.sh --fix` applies ruff's safe fixes first.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = --fix ]; then
    python3 -m ruff check --fix python tests scripts
fi
python3 -m ruff check python tests scripts
echo "lint: ruff clean"
