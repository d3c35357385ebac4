"""The GIL is released inside update(), replay() and the readers: a Python thread keeps running
while mote works. Measured as the longest gap between the main thread's ticks while a worker
thread is inside one long call; holding the GIL would make that gap the whole call."""

import threading
import time

import numpy as np

import mote
from conftest import ring_scan


def longest_gap_while(work):
    """Runs work() in a thread; returns (longest gap between main-thread ticks, call seconds)."""
    timing = {}

    def run():
        t0 = time.perf_counter()
        work()
        timing["s"] = time.perf_counter() - t0

    worker = threading.Thread(target=run)
    last = time.perf_counter()
    gap = 0.0
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        gap = max(gap, now - last)
        last = now
        sum(range(100))  # some Python work
    worker.join()
    return gap, timing["s"]


def test_update_releases_the_gil(floorplan):
    # Updates at 1M particles on one thread, one after another for at least 0.6 s: holding the
    # GIL would stall the main thread for a whole update each time, so its longest gap must be
    # well under the shortest update (however fast the machine makes them).
    n = 1_000_000
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(
        min_particles=n, max_particles=n, global_particles_per_bin=0.0, threads=1))
    loc.initialize_global()
    durations = []
    ran = []

    def updates():
        t_end = time.perf_counter() + 0.6
        while len(durations) < 3 or time.perf_counter() < t_end:
            odometry = (0.3 * len(durations), 0.0, 0.0)  # past update_min_d: every update runs
            t0 = time.perf_counter()
            loc.update(odometry, ring_scan())
            durations.append(time.perf_counter() - t0)
            ran.append(loc.last_update.ran)

    gap, _ = longest_gap_while(updates)
    assert all(ran), ran
    assert gap < 0.5 * min(durations), (gap, durations)


def test_replay_releases_the_gil(intel):
    gap, seconds = longest_gap_while(lambda: mote.replay(
        map=intel["map"], log=intel["log"], particles=5000, threads=1))
    assert seconds > 0.2, f"replay too short to tell: {seconds:.3f} s"
    assert gap < 0.5 * seconds, (gap, seconds)


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
