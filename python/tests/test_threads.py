"""Calls into the library release the GIL (cffi does so around every
call): shown without timing, by a call that blocks inside C until another
Python thread acts, and by a long fit during which another thread runs. A worker fits ON with its parameters read from a FIFO,
so the library's fopen/read blocks; only the main thread, which must run
Python meanwhile, writes the FIFO. Were the GIL held during the call, the
main thread could never write and the run would hang (CTest's timeout
fails it)."""

import os
import sys
import threading
import time

import brdffit


def test_a_blocked_library_call_lets_other_threads_run(tmp_path):
    fifo = tmp_path / "on_params.fifo"
    os.mkfifo(fifo)
    ds = brdffit.Dataset.from_arrays([[0.1, 0.0, 0.2, 3.0],
                                      [0.5, 0.0, 0.3, 1.0]], [0.4, 0.3])
    result = {}

    def worker():
        try:
            result["fit"] = brdffit.fit(ds, "ON", on_params=str(fifo),
                                        stats=False)
        except Exception as exc:  # reported by the main thread
            result["error"] = exc

    t = threading.Thread(target=worker)
    t.start()
    with open(fifo, "w") as f:  # runs only while the worker is in C
        f.write("1 0.25 0.5\n")
    t.join(60)
    assert not t.is_alive(), "the worker never returned"
    assert "error" not in result, result.get("error")
    assert result["fit"].parameters == {"rho": 0.25, "sigma": 0.5}


def test_a_long_fit_lets_another_thread_run(curet):
    """A worker runs a study of several (sample, model) pairs; the main
    thread counts while it sleeps in short steps, and the worker's
    progress callback records the count after each pair. With the switch
    interval at 1000 s no thread is made to give up the GIL, so the count
    can grow between two pairs only if the library's work released it."""
    ticks = [0]
    seen = []
    done = threading.Event()
    errors = []

    def worker():
        try:
            brdffit.compare(curet, models=["WNO-R"], samples=[1, 2, 3, 4],
                            fit="exact",
                            progress=lambda d, t: seen.append(ticks[0]))
        except Exception as exc:  # reported by the main thread
            errors.append(exc)
        finally:
            done.set()

    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        t = threading.Thread(target=worker)
        t.start()
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.0005)  # releases the GIL
        t.join()
    finally:
        sys.setswitchinterval(old)
    assert not errors, errors
    assert len(seen) == 4 and seen[-1] > seen[0], seen
