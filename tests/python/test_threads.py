"""The GIL is released while rendering, cancel() from another thread returns, and Ctrl+C stops a
render cleanly."""
import os
import signal
import threading
import time

import pathlab


def test_the_gil_is_released_while_rendering(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=64, height=64, threads=1))
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        start = time.monotonic()
        r.render(time=0.5)
        elapsed = time.monotonic() - start
    finally:
        done.set()
        counter.join()
    # Held, the counter would hardly run (a tick or two); released, up to once a millisecond (20
    # a second leaves room for a loaded machine).
    assert len(ticks) > 20 * elapsed, (len(ticks), elapsed)


def test_cancel_from_another_thread_returns_after_the_pass(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=32, height=32))
    timer = threading.Timer(0.3, r.cancel)
    timer.start()
    start = time.monotonic()
    image = r.render(spp=1_000_000)
    timer.join()
    assert time.monotonic() - start < 30
    assert 1 <= r.spp < 1_000_000
    assert image.shape == (32, 32, 3) and image.mean() > 0


def test_ctrl_c_raises_keyboard_interrupt_and_the_renderer_goes_on(box):
    # 256 x 256: passes of tens of milliseconds, so the signal may come within one or between two.
    r = pathlab.Renderer(box, pathlab.Settings(width=256, height=256))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        r.render(spp=1_000_000)
        raise AssertionError("render returned")
    except KeyboardInterrupt:
        pass
    timer.join()
    assert time.monotonic() - start < 30
    # Between passes every pass is kept; within one the renderer starts again from zero.
    before = r.spp
    assert before < 1_000_000
    assert r.render(spp=1).shape == (256, 256, 3) and r.spp == before + 1


def test_ctrl_c_stops_a_check(box):
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        pathlab.check(box, pathlab.Settings(width=64, height=64), time=600)
        raise AssertionError("check returned")
    except KeyboardInterrupt:
        pass
    timer.join()
    assert time.monotonic() - start < 30
