"""The GIL is released while meshing: another Python thread runs during the C++ call."""
import threading
import time

import numpy as np

import ablmg


def run_alongside(work):
    """Runs work() on a thread; returns the main thread's loop timestamps and the work's span."""
    span = {}

    def worker():
        span["start"] = time.perf_counter()
        work()
        span["end"] = time.perf_counter()

    t = threading.Thread(target=worker)
    ticks = []
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
        sum(range(200))
    t.join()
    return np.array(ticks), span["start"], span["end"]


def test_main_thread_runs_while_remeshing():
    square = ablmg.Domain.rectangle(0, 0, 1, 1)
    m = ablmg.mesh(square, 0.02)
    h = 0.004 + 0.02 * np.abs(m.points[:, 0] - 0.5)
    ticks, start, end = run_alongside(lambda: ablmg.remesh(m.points, m.triangles, h))
    assert end - start > 0.2  # long enough to tell
    # the middle half of the call: a held GIL would leave no tick there (switch interval 5 ms)
    a, b = start + 0.25 * (end - start), start + 0.75 * (end - start)
    inside = ((ticks > a) & (ticks < b)).sum()
    assert inside > 100, f"{inside} ticks of the main thread during the remesh"


def test_two_remeshes_at_once_give_the_serial_results():
    square = ablmg.Domain.rectangle(0, 0, 1, 1)
    m = ablmg.mesh(square, 0.05)
    metrics = [np.full(m.num_vertices, h) for h in (0.02, 0.03)]
    serial = [ablmg.remesh(m.points, m.triangles, h) for h in metrics]
    results = [None, None]

    def run(i):
        results[i] = ablmg.remesh(m.points, m.triangles, metrics[i])

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for s, r in zip(serial, results):
        np.testing.assert_array_equal(s.points, r.points)


def test_callable_metric_from_a_thread_keeps_the_gil_rules():
    """A Python metric is called back with the GIL while another thread runs Python."""
    square = ablmg.Domain.rectangle(0, 0, 1, 1)
    calls = []

    def metric(x, y):
        calls.append(threading.get_ident())
        return 0.01 + 0.05 * np.abs(y - 0.5)

    out = {}
    ticks, start, end = run_alongside(lambda: out.setdefault("m", ablmg.mesh(square, metric)))
    assert out["m"].num_vertices > 1000
    assert len(set(calls)) == 1  # always from the meshing thread, never from OpenMP workers
    assert len(ticks) > 100
