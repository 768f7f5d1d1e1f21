"""Long sweeps from Python: they release the GIL (other Python threads run meanwhile), Ctrl-C
(SIGINT, or ``_thread.interrupt_main``) sent from another thread stops them promptly with
KeyboardInterrupt, and a parallel sweep equals the serial one bit for bit (the library's
determinism: every level and every pulse duration is computed on its own and collected in
order)."""
import _thread
import os
import signal
import threading
import time

import numpy as np
import pytest

import rocking

RECORD = "examples/records/synthetic.AT2"

# A sweep far longer than the interrupt's latency: 400 levels of 120 sizes, one thread (the full
# thesis grid, 80 levels, took 41 s on one thread of this machine under load; its slowest level
# 2.5 s). Interrupted, it must return within LATENCY of the signal: the unit of work is one
# level, and the running level finishes first.
LONG = dict(levels=400, sizes=120, threads=1)
LATENCY = 10.0


def interrupt_with_sigint():
    os.kill(os.getpid(), signal.SIGINT)


@pytest.mark.parametrize("send", [_thread.interrupt_main, interrupt_with_sigint])
def test_an_interrupt_from_another_thread_stops_a_sweep_promptly(root, send):
    started = threading.Event()
    sent = []

    def progress(done, total):
        if done >= 1:
            started.set()

    def interrupter():
        started.wait(60)
        sent.append(time.monotonic())
        send()

    # The GIL is released during the sweep: this thread ticks meanwhile.
    ticks, stop = [0], threading.Event()

    def ticker():
        while not stop.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    threads = [threading.Thread(target=interrupter), threading.Thread(target=ticker)]
    for t in threads:
        t.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rocking.oas(root / RECORD, progress=progress, **LONG)
        returned = time.monotonic()
    finally:
        stop.set()
        for t in threads:
            t.join()
    assert sent, "the sweep ended before the interrupt was sent"
    assert returned - sent[0] < LATENCY, f"returned {returned - sent[0]:.1f} s after the interrupt"
    assert ticks[0] > 10, "no other Python thread ran during the sweep"
    # The package is usable afterwards.
    assert rocking.oas(root / RECORD, levels=2, sizes=4).levels.shape == (2,)


def test_an_interrupt_stops_an_overturning_curve(root):
    started = threading.Event()
    timer = threading.Thread(target=lambda: (started.wait(60), _thread.interrupt_main()))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rocking.oc(ptp=400, levels=40, threads=1, progress=lambda d, n: d >= 1 and started.set())
    finally:
        timer.join()


def bits(a):
    """The bit patterns of a float64 array (NaN included, -0.0 distinct from 0.0)."""
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def test_parallel_sweeps_equal_the_serial_ones_bit_for_bit(root):
    grid = dict(levels=8, sizes=24, blocks=2, impacts=2)
    serial = rocking.oas(root / RECORD, threads=1, **grid)
    for threads in (2, None):
        parallel = rocking.oas(root / RECORD, threads=threads, **grid)
        for name in ("sizes", "levels", "size", "p", "f"):
            np.testing.assert_array_equal(bits(getattr(parallel, name)), bits(getattr(serial, name)), err_msg=name)
        np.testing.assert_array_equal(parallel.largest_unsafe, serial.largest_unsafe)
        np.testing.assert_array_equal(parallel.simulations, serial.simulations)
        for key in ("t1", "t1_prime", "beta", "f_min"):
            assert bits(np.array([parallel.summary[key]])) == bits(np.array([serial.summary[key]])), key
    one = rocking.oc("full-sine", blocks=2, ptp=10, levels=10, threads=1)
    for threads in (2, None):
        other = rocking.oc("full-sine", blocks=2, ptp=10, levels=10, threads=threads)
        np.testing.assert_array_equal(other.unsafe, one.unsafe)
        np.testing.assert_array_equal(bits(other.envelope), bits(one.envelope))
        np.testing.assert_array_equal(bits(other.t_p), bits(one.t_p))


SWEEPS = {
    "oas": lambda **kw: rocking.oas(RECORD, levels=2, sizes=3, **kw),
    "t1": lambda **kw: rocking.t1(RECORD, levels=2, sizes=3, converge_step=None, **kw),
    "oc": lambda **kw: rocking.oc("half-sine", ptp=2, levels=2, **kw),
    "arch_oas": lambda **kw: rocking.arch_oas(RECORD, voussoirs=4, radius_n=2, level_n=2, **kw),
    "arch_oc": lambda **kw: rocking.arch_oc("half-sine", voussoirs=4, ptp_n=2, level_n=2, **kw),
}


@pytest.mark.parametrize("sweep", sorted(SWEEPS))
@pytest.mark.parametrize("threads", [-1, 0, rocking._MAX_THREADS + 1, 10**6])
def test_a_thread_count_out_of_range_is_refused_before_any_thread_starts(root, monkeypatch, sweep, threads):
    """threads=-1 was an OverflowError that did not name it; threads=10**6 had rayon start a
    million threads and the process was killed (SIGKILL), the caller with it."""
    monkeypatch.chdir(root)
    with pytest.raises(rocking.RockingError, match=rf"threads = {threads}: must be"):
        SWEEPS[sweep](threads=threads)


@pytest.mark.parametrize("sweep", sorted(SWEEPS))
def test_a_progress_that_is_not_callable_is_refused_before_the_sweep(root, monkeypatch, sweep):
    monkeypatch.chdir(root)
    with pytest.raises(TypeError, match="progress: expected a callable"):
        SWEEPS[sweep](progress=3)


@pytest.mark.parametrize("call, name", [
    (lambda n: rocking.oas(RECORD, levels=n, sizes=2), "levels"),
    (lambda n: rocking.oas(RECORD, levels=2, sizes=n), "sizes"),
    (lambda n: rocking.t1(RECORD, levels=n, sizes=2, converge_step=None), "levels"),
    (lambda n: rocking.oc("half-sine", ptp=n, levels=2), "ptp"),
    (lambda n: rocking.oc("half-sine", ptp=2, levels=n), "levels"),
    (lambda n: rocking.arch_oas(RECORD, voussoirs=4, radius_n=n, level_n=2), "radius_n"),
    (lambda n: rocking.arch_oas(RECORD, voussoirs=4, radius_n=2, level_n=n), "level_n"),
    (lambda n: rocking.arch_oc("half-sine", voussoirs=4, ptp_n=n, level_n=2), "ptp_n"),
    (lambda n: rocking.arch_oc("half-sine", voussoirs=4, ptp_n=2, level_n=n), "level_n"),
])
def test_a_grid_count_too_large_is_refused_before_any_work(root, monkeypatch, call, name):
    """levels=10**9 allocated the 8 GB grid: under a memory limit the process aborted (memory
    allocation failed), the caller with it; without one it ran for ever."""
    monkeypatch.chdir(root)
    n = rocking._MAX_COUNT + 1
    with pytest.raises(rocking.RockingError, match=rf"{name} = {n}: .*at most {rocking._MAX_COUNT}"):
        call(n)
    with pytest.raises(rocking.RockingError, match=rf"{name} = {10**9}: "):
        call(10**9)
