"""The GIL is released inside update(), replay() and the readers: a Python thread keeps running
while mote works. Measured by the main thread's ticks while a worker thread is inside long
calls: holding the GIL would leave no tick inside a call. Checked in the middle half of each
call, not as a bound on the longest gap between ticks, which a main thread descheduled by a
loaded machine (ctest -j2) can break without the GIL having anything to do with it."""

import bisect
import threading
import time

import numpy as np

import mote
from conftest import ring_scan


def ticks_while(work):
    """Runs work(calls) in a thread, which appends each long call's (start, end) to calls;
    returns (the main thread's tick times while it ran, calls). An exception in the worker is
    raised here, so a call that fails cannot pass as one that released the GIL."""
    calls, failures = [], []

    def run():
        try:
            work(calls)
        except BaseException as e:  # noqa: B902: re-raised in the main thread
            failures.append(e)

    worker = threading.Thread(target=run)
    ticks = [time.perf_counter()]
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        if now - ticks[-1] >= 1e-4:  # a tick per 0.1 ms: calls last 0.1 s and more
            ticks.append(now)
        sum(range(100))  # some Python work
    worker.join()
    if failures:
        raise failures[0]
    return ticks, calls


def calls_without_a_tick(ticks, calls):
    """The calls with no main-thread tick in the middle half of their time."""
    silent = []
    for start, end in calls:
        quarter = 0.25 * (end - start)
        first = bisect.bisect_left(ticks, start + quarter)
        if first == len(ticks) or ticks[first] > end - quarter:
            silent.append((start, end))
    return silent


def timed(calls, call):
    t0 = time.perf_counter()
    result = call()
    calls.append((t0, time.perf_counter()))
    return result


def test_update_releases_the_gil(floorplan):
    # Updates at 1M particles on one thread, one after another for at least 0.6 s.
    n = 1_000_000
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(
        min_particles=n, max_particles=n, global_particles_per_bin=0.0, threads=1))
    loc.initialize_global()
    ran = []

    def updates(calls):
        t_end = time.perf_counter() + 0.6
        while len(calls) < 3 or time.perf_counter() < t_end:
            odometry = (0.3 * len(calls), 0.0, 0.0)  # past update_min_d: every update runs
            timed(calls, lambda: loc.update(odometry, ring_scan()))
            ran.append(loc.last_update.ran)

    ticks, calls = ticks_while(updates)
    assert len(calls) >= 3 and all(ran), ran
    assert calls_without_a_tick(ticks, calls) == [], (len(ticks), calls)


def test_replay_releases_the_gil(intel):
    ticks, calls = ticks_while(lambda calls: timed(calls, lambda: mote.replay(
        map=intel["map"], log=intel["log"], particles=5000, threads=1)))
    (start, end), = calls
    assert end - start > 0.2, f"replay too short to tell: {end - start:.3f} s"
    assert calls_without_a_tick(ticks, calls) == [], (len(ticks), calls)


def test_one_localizer_refuses_two_threads(floorplan):
    n = 1_000_000
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(
        min_particles=n, max_particles=n, global_particles_per_bin=0.0, threads=1))
    loc.initialize_global()
    errors = []
    started = threading.Event()

    def update():
        started.set()
        loc.update((0.0, 0.0, 0.0), ring_scan())

    worker = threading.Thread(target=update)
    worker.start()
    started.wait()
    deadline = time.perf_counter() + 5.0
    while worker.is_alive() and time.perf_counter() < deadline:
        try:
            loc.particles
        except mote.Error as e:
            errors.append(str(e))
            break
        time.sleep(0.001)
    worker.join()
    assert errors and "during an update" in errors[0], errors
    assert np.isfinite(loc.particles.x).all()
