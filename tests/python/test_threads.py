"""The GIL is released while rendering, cancel() from another thread returns, and Ctrl+C stops a
render cleanly."""
import os
import signal
import threading
import time

import numpy as np

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
    settings = pathlab.Settings(width=32, height=32)
    r = pathlab.Renderer(box, settings)
    timer = threading.Timer(0.3, r.cancel)
    timer.start()
    start = time.monotonic()
    image = r.render(time=20)  # a lost cancel() returns after 20 s, and fails below
    timer.join()
    assert time.monotonic() - start < 10
    assert r.spp >= 1
    # Every pass kept: the image of that many passes, bit for bit.
    assert np.array_equal(image, pathlab.Renderer(box, settings).render(spp=r.spp))


def test_cancel_before_render_stops_the_next_one(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=16, height=16))
    r.cancel()
    r.render(spp=5)
    assert r.spp == 0
    r.render(spp=2)  # the cancel was used up
    assert r.spp == 2


def test_one_render_at_a_time(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=64, height=64))
    errors = []

    def second():
        time.sleep(0.2)
        try:
            r.render(spp=1)
        except pathlab.Error as e:
            errors.append(str(e))
        r.cancel()

    other = threading.Thread(target=second)
    other.start()
    r.render(time=20)
    other.join()
    assert errors and "already rendering" in errors[0]


def test_ctrl_c_raises_keyboard_interrupt_after_the_pass_and_keeps_every_pass(box):
    # 256 x 256: passes of tens of milliseconds, so the signal comes within one or between two.
    settings = pathlab.Settings(width=256, height=256)
    r = pathlab.Renderer(box, settings)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        r.render(time=20)
        raise AssertionError("render returned")
    except KeyboardInterrupt:
        pass
    timer.join()
    assert time.monotonic() - start < 10
    kept = r.spp
    assert kept >= 1
    assert np.array_equal(r.image(), pathlab.Renderer(box, settings).render(spp=kept))
    assert r.render(spp=1).shape == (256, 256, 3) and r.spp == kept + 1


def test_ctrl_c_stops_a_check(box):
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        pathlab.check(box, pathlab.Settings(width=64, height=64), time=20)
        raise AssertionError("check returned")
    except KeyboardInterrupt:
        pass
    timer.join()
    assert time.monotonic() - start < 30
