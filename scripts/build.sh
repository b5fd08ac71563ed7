#!/usr/bin/env bash
# Configures and builds gradem (Release) into ./build and installs its Python module. Usage: scripts/build.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$(nproc)" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
# The Python module, when it was built (pybind11 found), into Debian's python3 site folder
# (/usr/local/lib/python3.X/dist-packages): `python3 -c "import gradem"` (python/README.md).
if compgen -G "build/python/gradem/_gradem*.so" > /dev/null; then
  cmake --install build --component python >> build.log 2>&1 || { tail -20 build.log; exit 1; }
  echo "build: Python module gradem installed (python/README.md)"
fi
echo "build: ok (log in build.log)"
