"""Calls into the library release the GIL (cffi does so around every
call): shown without timing, by a call that blocks inside C until another
Python thread acts. A worker fits ON with its parameters read from a FIFO,
so the library's fopen/read blocks; only the main thread, which must run
Python meanwhile, writes the FIFO. Were the GIL held during the call, the
main thread could never write and the run would hang (CTest's timeout
fails it)."""

import os
import threading

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
