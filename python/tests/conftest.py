"""Shared fixtures: the repository's files, the thesis's values (tests/python/samples.json, generated
from src/samples.rs) and the C ABI through ctypes (tests/python/smoke.py's declarations)."""
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "python"))


@pytest.fixture(autouse=True)
def python_handles_ctrl_c():
    """Ctrl-C as an interactive Python sees it: SIGINT raises KeyboardInterrupt. A process started
    with SIGINT ignored (a background job of a non-interactive shell, `nohup`) inherits SIG_IGN,
    Python then installs no handler, and neither SIGINT nor `_thread.interrupt_main` interrupts
    anything — the interrupt tests would test the launcher, not the package. Restored after."""
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    if before is not None:
        signal.signal(signal.SIGINT, before)


@pytest.fixture(scope="session")
def samples():
    return json.loads((ROOT / "tests" / "python" / "samples.json").read_text())


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def cabi():
    """The cdylib through ctypes: ROCKING_LIB if set (then it must exist: CI sets it), else
    target/release/librocking.so if built, else the tests that compare with it skip."""
    import smoke  # the ctypes declarations of the C ABI (standard library only)

    path = os.environ.get("ROCKING_LIB")
    if path is None:
        default = ROOT / "target" / "release" / "librocking.so"
        if not default.exists():
            pytest.skip("no target/release/librocking.so (cargo build --release) and ROCKING_LIB unset")
        path = default
    return smoke, smoke.load(path)


@pytest.fixture(scope="session")
def cli(root):
    """`cli(*args)`: the JSON that the `rocking` CLI (ROCKING_CLI, else target/release/rocking)
    prints for `args`; skips when there is no CLI."""
    path = os.environ.get("ROCKING_CLI") or str(root / "target" / "release" / "rocking")
    if not os.path.exists(path):
        pytest.skip("no rocking CLI (cargo build --release -p rocking-cli) and ROCKING_CLI unset")

    def run(*args):
        out = subprocess.run([path, *map(str, args)], check=True, capture_output=True, text=True)
        return json.loads(out.stdout)

    return run


@pytest.fixture(scope="session")
def reversed_record(root, tmp_path_factory):
    """The bundled record reversed in time, as `reversed.AT2` in a temporary folder (a second
    record for the suites)."""
    lines = (root / "examples/records/synthetic.AT2").read_text().splitlines()
    values = [float(x) for line in lines[4:] for x in line.split()][::-1]
    body = ["".join(f"{v:16.7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    path = tmp_path_factory.mktemp("records") / "reversed.AT2"
    path.write_text("\n".join(lines[:4] + body) + "\n")
    return path
