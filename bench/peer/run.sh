#!/bin/sh
# The scipy peer of `rocking bench accuracy`: creates bench/peer/.venv (numpy + scipy, a
# bench-only dependency), runs the single-block solver on scenes (a) and (b) and writes
# bench/peer/results.json. Extra arguments go to the script (e.g. --quick).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
if [ ! -x "$here/.venv/bin/python" ]; then
    python3 -m venv "$here/.venv"
    "$here/.venv/bin/pip" install --quiet --upgrade pip
    "$here/.venv/bin/pip" install --quiet numpy scipy
fi
"$here/.venv/bin/python" "$here/single_block_scipy.py" --out "$here/results.json" "$@"
echo "wrote $here/results.json"
