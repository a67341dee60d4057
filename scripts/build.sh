#!/usr/bin/env bash
# Builds everything once (library, Python module, demo, C++ tests) through pip/scikit-build-core
# into build/py, reusing that folder and ccache, and installs the `weft` package.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --no-build-isolation --progress-bar off -q . \
    -Cbuild-dir=build/py -Ccmake.define.WEFT_BUILD_TESTS=ON -Cbuild.verbose=false
echo "build: weft $(python3 -c 'import weft; print(weft.__version__)') installed; native build in build/py"
