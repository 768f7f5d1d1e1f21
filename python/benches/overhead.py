#!/usr/bin/env python3
"""Calling overhead of rocking.impact_model from Python on the thesis's 2-block column (Eq. 10-11).

Usage (in a virtualenv with the package installed): python python/benches/overhead.py [ROCKING_LIB]

Prints, measured in one process: the library's impact model alone (the extension's benchmark hook
loops the Rust call), the Python call with numpy inputs, with lists, and the same call through the
C ABI with ctypes (with ROCKING_LIB or target/release/librocking.so). The overhead of the binding
is the Python call's time minus the Rust call's. The rounds interleave the ways of calling (so
that a busy machine slows them alike) and each figure is the best of 15 rounds.
"""
import ctypes
import sys
import timeit
from pathlib import Path

import numpy as np

import rocking
from rocking import _rocking

ROOT = Path(__file__).resolve().parents[2]


ROUNDS = 15


def per_call(stmt, number):
    return timeit.timeit(stmt, number=number) / number


def main():
    M, _ = rocking.column_mass_matrix([0.1, 0.1], [0.3, 0.3], [15.0, 15.0])
    status = np.array([0, 1], dtype=np.int8)
    velocity = np.array([0.0, 0.0, 0.0, -1.0])
    Ml, sl, vl = M.tolist(), status.tolist(), velocity.tolist()
    lib = None
    lib_path = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "target" / "release" / "librocking.so"
    if lib_path.exists():
        sys.path.insert(0, str(ROOT / "tests" / "python"))
        import smoke

        lib = smoke.load(lib_path)
    for n_impacts in (1, 2):
        ways = {
            "Rust call (library alone)": lambda: _rocking._time_impact_model(M, status, velocity, 1, n_impacts, 20_000),
            "Python, numpy arrays": lambda: per_call(lambda: rocking.impact_model(M, status, velocity, 1, n_impacts=n_impacts), 20_000),
            "Python, lists": lambda: per_call(lambda: rocking.impact_model(Ml, sl, vl, 1, n_impacts=n_impacts), 10_000),
        }
        if lib is not None:
            mass_c = smoke.doubles(M.ravel().tolist())
            opts = ctypes.byref(smoke.RockingOptions(n_impacts, 0, 1e-12))
            rep = smoke.RockingReport()

            def c_call():
                st, v = smoke.int8s([0, 1]), smoke.doubles([0.0, 0.0, 0.0, -1.0])
                return lib.rocking_impact_model(2, mass_c, st, v, 1, opts, ctypes.byref(rep))

            assert c_call() == 0
            ways["ctypes on the C ABI (for scale)"] = lambda: per_call(c_call, 10_000)
        times = {k: [] for k in ways}
        for _ in range(ROUNDS):
            for k, f in ways.items():
                times[k].append(f())
        best = {k: min(v) for k, v in times.items()}
        rust = best["Rust call (library alone)"]
        print(f"2-block impact, n_impacts = {n_impacts}:")
        for k, t in best.items():
            extra = "" if t is rust else f"   overhead {(t - rust) * 1e6:6.3f} us"
            print(f"  {k:33s} {t * 1e6:7.3f} us{extra}")
    print(f"rocking {rocking.__version__}, numpy {np.__version__}, Python {sys.version.split()[0]}")


if __name__ == "__main__":
    main()
