#!/usr/bin/env python3
"""Smoke test of the C ABI from Python with ctypes (standard library only).

Usage: python3 tests/python/smoke.py [LIB_PATH]
Without an argument it loads target/release/librocking.so. Runs the thesis's examples through
both entry points and checks that every error class returns its code with the arrays untouched.
The cases and the thesis's numbers come from samples.json beside this file, generated from
src/samples.rs (tests/c_abi.rs fails when it drifts). Exits 0 on success.
"""
import ctypes
import json
import math
import sys
from pathlib import Path


class RockingOptions(ctypes.Structure):
    _fields_ = [("n_impacts", ctypes.c_uint32), ("solver", ctypes.c_uint32), ("tolerance", ctypes.c_double)]


class RockingReport(ctypes.Structure):
    _fields_ = [
        ("solver", ctypes.c_uint32),
        ("changed", ctypes.c_uint32),
        ("tie", ctypes.c_uint32),
        ("impacts_applied", ctypes.c_uint32),
        ("configurations_examined", ctypes.c_uint64),
        ("admissible", ctypes.c_uint64),
        ("kinetic_before", ctypes.c_double),
        ("kinetic_after", ctypes.c_double),
        ("runner_up", ctypes.c_double),
        ("condition_estimate", ctypes.c_double),
    ]


D = ctypes.POINTER(ctypes.c_double)
I8 = ctypes.POINTER(ctypes.c_int8)
U8 = ctypes.POINTER(ctypes.c_uint8)
SIZE = ctypes.c_size_t


def load(path):
    lib = ctypes.CDLL(str(path))
    lib.rocking_impact_model.argtypes = [SIZE, D, I8, D, SIZE, ctypes.POINTER(RockingOptions), ctypes.POINTER(RockingReport)]
    lib.rocking_impact_model.restype = ctypes.c_int32
    lib.rocking_opening_model.argtypes = [SIZE, D, D, I8, D, ctypes.POINTER(RockingOptions), ctypes.POINTER(RockingReport)]
    lib.rocking_opening_model.restype = ctypes.c_int32
    lib.rocking_check_configuration.argtypes = [SIZE, D, D, I8, ctypes.c_double, U8, D, U8]
    lib.rocking_check_configuration.restype = ctypes.c_int32
    lib.rocking_column_mass_matrix.argtypes = [SIZE, D, D, D, D, D, D, ctypes.c_double, ctypes.c_double, D, D]
    lib.rocking_column_mass_matrix.restype = ctypes.c_int32
    lib.rocking_reduce.argtypes = [SIZE, SIZE, D, D, D, D, D]
    lib.rocking_reduce.restype = ctypes.c_int32
    lib.rocking_error_message.argtypes = [ctypes.c_int32]
    lib.rocking_error_message.restype = ctypes.c_char_p
    lib.rocking_last_error_message.argtypes = []
    lib.rocking_last_error_message.restype = ctypes.c_char_p
    lib.rocking_version.argtypes = []
    lib.rocking_version.restype = ctypes.c_char_p
    lib.rocking_abi_version.argtypes = []
    lib.rocking_abi_version.restype = ctypes.c_uint32
    return lib


def doubles(values):
    return (ctypes.c_double * len(values))(*values)


def int8s(values):
    return (ctypes.c_int8 * len(values))(*values)


def two_block_mass(lib, case):
    w, h, m = doubles(case["width"]), doubles(case["height"]), doubles(case["block_mass"])
    mass = doubles([0.0] * 16)
    code = lib.rocking_column_mass_matrix(2, w, h, m, None, None, None, 0.0, 9.81, mass, None)
    assert code == 0, lib.rocking_last_error_message()
    return list(mass)


def impact(lib, mass, status, velocity, closing, options=None):
    st, v, rep = int8s(status), doubles(velocity), RockingReport()
    opts = ctypes.byref(options) if options is not None else None
    code = lib.rocking_impact_model(len(status), doubles(mass), st, v, closing, opts, ctypes.byref(rep))
    return code, list(st), list(v), rep


def main():
    root = Path(__file__).resolve().parents[2]
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else root / "target" / "release" / "librocking.so"
    lib = load(path)
    print(f"rocking {lib.rocking_version().decode()} (ABI {lib.rocking_abi_version()}) from {path}")
    failures = 0
    passed = 0

    def check(name, ok, detail=""):
        nonlocal failures, passed
        print(f"  {'ok ' if ok else 'FAIL'} {name} {detail}")
        failures += 0 if ok else 1
        passed += 1 if ok else 0

    samples = json.loads((Path(__file__).resolve().parent / "samples.json").read_text())
    case = samples["two_block_impact"]
    mass = two_block_mass(lib, case)
    eq10 = case["thesis_eq10_mass"]
    check(f"Eq. 10 mass matrix to the printed digits ({eq10[2]:.3f} ...)",
          all(abs(got - want) < 5e-4 for got, want in zip(mass, eq10)))
    for answer in case["answers"]:
        n_imp, rates, loss = answer["n_impacts"], answer["rates"], answer["loss_percent"]
        code, st, v, rep = impact(lib, mass, case["status"], case["velocity"], case["closing"],
                                  RockingOptions(n_imp, 0, 1e-12))
        got_loss = 100 * (1 - rep.kinetic_after / rep.kinetic_before)
        check(f"{n_imp} impact(s): thesis rates {tuple(rates)}, loss {loss} %",
              code == 0 and st == [-1, -1] and abs(v[0] - rates[0]) < 5e-5 and abs(v[1] - rates[1]) < 5e-5
              and abs(got_loss - loss) < 0.05, f"-> code {code}, rates ({v[0]:.4f}, {v[1]:.4f}), loss {got_loss:.2f} %")

    # Opening (thesis Fig. 19e): horizontal force of 10 x one block's weight at the top.
    push = samples["two_block_top_push"]
    st, acc, rep = int8s([0, 0]), doubles([0.0] * 4), RockingReport()
    code = lib.rocking_opening_model(2, doubles(push["mass"]), doubles(push["load"]), st, acc, None,
                                     ctypes.byref(rep))
    check(f"opening Fig. 19e: status {push['expected_status']}",
          code == 0 and list(st) == push["expected_status"] and rep.changed == 1,
          f"-> code {code}, status {list(st)}")

    # Every error class: the code, a message, and the arrays untouched.
    cases = [
        ("n = 0", dict(n=0), -2),
        ("NaN in mass", dict(mass_at=(5, math.nan)), -3),
        ("non-symmetric mass", dict(mass_at=(1, 9.0)), -4),
        ("status 3", dict(status=[0, 3]), -5),
        ("closing interface out of range", dict(closing=5), -6),
        ("closing interface closed", dict(closing=0), -6),
        ("velocity on a closed DOF", dict(velocity=[0.2, 0, 0, -1.0]), -7),
        ("n_impacts = 0", dict(options=RockingOptions(0, 0, 1e-12)), -8),
        ("closing interface moving away", dict(velocity=[0, 0, 0, 1.0]), -9),
        ("indefinite mass", dict(mass=[-abs(x) if i % 5 == 0 else x for i, x in enumerate(mass)]), 1),
    ]
    for name, change, expected in cases:
        mm = list(change.get("mass", mass))
        if "mass_at" in change:
            i, value = change["mass_at"]
            mm[i] = value
        status = change.get("status", [0, 1])
        velocity = change.get("velocity", [0, 0, 0, -1.0])
        st, v, rep = int8s(status), doubles(velocity), RockingReport()
        rep.solver = 77
        opts = change.get("options")
        code = lib.rocking_impact_model(change.get("n", 2), doubles(mm), st, v, change.get("closing", 1),
                                        ctypes.byref(opts) if opts else None, ctypes.byref(rep))
        untouched = list(st) == status and list(v) == velocity and rep.solver == 77
        message = lib.rocking_last_error_message().decode()
        check(f"{name}: code {expected}", code == expected and untouched and message != "",
              f"-> code {code} ({lib.rocking_error_message(code).decode()}): {message}")
    code = lib.rocking_impact_model(2, None, int8s([0, 1]), doubles([0, 0, 0, -1.0]), 1, None, None)
    check("NULL mass: code -1", code == -1)

    print(f"{passed} passed, {failures} failed")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
