#!/usr/bin/env bash
# Real OpenSees (openseespy) integrates a single block and the thesis 4.2 two-block column on
# compression-only contact springs; at every impact the rocking library (the Python package's
# coupling module rocking.opensees) decides the new configuration and velocities from OpenSees's
# own mass matrix, and at every opening it must pick what OpenSees did. Compared with Housner's exact ratio and with the C harness
# (c_examples/opensees_style_harness.c, itself checked against the Rust driver by
# tests/harness_vs_driver.rs, thesis Eq. 6) and with the Rust driver on the exact Lagrangian
# equations, which OpenSees's corotational blocks also integrate. Exits 0 on success.
#
# Then python/tests/test_opensees.py (pytest): `python -m rocking.opensees SCENE --compare` on the
# single block and the bundled two-block scene against the rigid driver.
#
# openseespy is an optional dependency (its licence forbids redistribution): it lives in
# tests/opensees/.venv, created here, with the package installed as `pip install ./python[opensees]`,
# and nowhere in the library. openseespy 3.7.1.2 has wheels for Python 3.11 (3.8 needs
# Python >= 3.12); set PYTHON to choose the interpreter.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SECONDS=0
py="${PYTHON:-$(command -v python3.11 || command -v python3)}"
if [ ! -x "$here/.venv/bin/python" ]; then
    "$py" -m venv "$here/.venv"
fi
"$here/.venv/bin/python" -m pip install -q --disable-pip-version-check openseespy==3.7.1.2 pytest
"$here/.venv/bin/python" -m pip install -q --disable-pip-version-check "$root/python[opensees]"
lib="$root/target/release/librocking.so"
[ -f "$lib" ] || (cd "$root" && cargo build --release)
mkdir -p "$root/target/c_examples"
exe="$root/target/c_examples/opensees_style_harness"
cc -std=c99 -O2 -I"$root/include" "$root/c_examples/opensees_style_harness.c" -o "$exe" \
    -L"$root/target/release" -lrocking -lm -Wl,-rpath,"$root/target/release"
# The rigid reference with the exact Lagrangian equations (velocity terms), which OpenSees's
# corotational blocks integrate too: the thesis 4.2 scene of the harness (scene c), DOP853.
cli="$root/target/release/rocking"
[ -x "$cli" ] || (cd "$root" && cargo build --release -p rocking-cli)
exact="$root/target/opensees_exact_4_2"
mkdir -p "$exact"
cat > "$exact/scene.json" <<'JSON'
{
  "title": "Thesis 4.2 as harness scene c, exact velocity terms",
  "blocks": [
    {"width": 0.1, "height": 0.3, "mass": 16.2, "contact_width": 0.096},
    {"width": 0.1, "height": 0.3, "mass": 16.2, "contact_width": 0.096}
  ],
  "initial_angles": [0.0, -0.153],
  "excitation": {"type": "none"},
  "impacts": 2, "duration": 0.35, "dt": 0.0005,
  "integrator": "dop853", "locator": "hermite", "exact_velocity_terms": true
}
JSON
"$cli" simulate "$exact/scene.json" --out "$exact" > /dev/null
# OpenSees prints a solver warning when GimmeMCK's analyze() meets the singular mass matrix
# (massless rotations) and "Process 0 Terminating" at exit: both harmless, filtered.
filter() { grep -v -e "FullGenLinLapackSolver::solve() -factorization failed" -e "^Process 0 Terminating" || true; }
set +e
"$here/.venv/bin/python" "$here/rocking_opensees.py" "$exe" "$exact/events.jsonl" 2>&1 | filter
status=${PIPESTATUS[0]}
# pytest from the root (not python/, whose rocking/ folder has no compiled extension).
(cd "$root" && ROCKING_CLI="$cli" ROCKING_LIB="$lib" "$here/.venv/bin/python" -m pytest -q -p no:cacheprovider \
    python/tests/test_opensees.py 2>&1 | filter; exit "${PIPESTATUS[0]}")
pytest_status=$?
set -e
[ "$status" -eq 0 ] && status=$pytest_status
echo "tests/opensees/run.sh: exit ${status} after ${SECONDS} s"
exit "$status"
