"""No input hangs bbb: adversarial values (NaN, ±inf, 1e±300, subnormals, −0.0, wrong types)
thrown at Params, InitialState and simulate either return or raise a one-line ValueError or
TypeError, each call within WATCHDOG seconds.

Every call runs in one long-lived worker process (spawned once per module, its kernels loaded
before the first timed call): a call that does not answer in time is killed and fails the
test instead of hanging the suite.  ``make test`` draws a few dozen examples per claim; the
tests marked slow draw hundreds.
"""

from __future__ import annotations

import math
import multiprocessing as mp

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

#: seconds a single call may take once the worker's kernels are loaded
WATCHDOG = 10.0
#: seconds the worker may take to start and load (or compile) its four kernels
WARMUP = 900.0
FAST, MANY = 25, 400

NASTY_FLOATS = [math.nan, math.inf, -math.inf, 1e300, -1e300, 1e-300, -1e-300, 5e-324, -5e-324,
                2.2250738585072014e-308, 0.0, -0.0, -1.0]
WRONG_TYPES = ["60", None, True, False, 1 + 2j, [60.0], np.bool_(True), b"6"]
VALID = dict(g=9800.0, A=0.1, f=60.0, R=15.0, S=2.0, alpha=0.7, beta=0.99)
FIELDS = ("cell", "d", "y", "vx", "vy", "s", "stuck", "from_surface")


def _serve(conn) -> None:
    """The worker: runs ("params" | "state" | "simulate", kwargs) calls and answers
    ("ok" | "refused" | "error", one-line text)."""
    from bbb import Numerics, Params, simulate
    from bbb.ensemble import InitialState

    while True:
        msg = conn.recv()
        if msg is None:
            return
        kind, kw = msg
        try:
            if kind == "params":
                Params(**kw)
            elif kind == "numerics":
                Numerics(**kw)
            elif kind == "state":
                InitialState(**kw)
            else:
                params = Params(**kw.pop("params"))
                state = kw.pop("state", None)
                if state is not None:
                    kw["initial"] = InitialState(**state)
                run = simulate(params, **kw)
                if run.counters["anomalies"].sum():
                    raise AssertionError(f"{run.counters['anomalies'].sum()} anomalies")
            conn.send(("ok", ""))
        except (ValueError, TypeError) as e:
            conn.send(("refused", f"{type(e).__name__}: {e}"))
        except BaseException as e:  # noqa: BLE001 - reported to the test, which fails
            conn.send(("error", f"{type(e).__name__}: {e}"))


class Worker:
    def __init__(self) -> None:
        self.proc = None
        self.conn = None

    def start(self) -> None:
        ctx = mp.get_context("spawn")
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_serve, args=(child,), daemon=True)
        self.proc.start()
        child.close()  # the worker's end: if the worker dies, this end sees EOF
        # load every compiled kernel (paper floor / conveyor, stick / contact models) untimed
        for extra in ({}, {"tilt": 2.0}, {"contact": "coulomb", "mu": 0.3},
                      {"contact": "slide", "throw": 60.0}):
            verdict = self.call("simulate", dict(params=VALID | extra, n_particles=2, t_max=0.05,
                                                 seed=0, initial="launched"), WARMUP)
            assert verdict == ("ok", ""), verdict

    def call(self, kind: str, kw: dict, timeout: float = WATCHDOG) -> tuple[str, str]:
        if self.proc is None or not self.proc.is_alive():
            self.start()
        self.conn.send((kind, kw))
        if not self.conn.poll(timeout):
            self.proc.kill()
            self.proc.join()
            self.proc = None
            pytest.fail(f"{kind}({kw!r}) did not return within {timeout:g} s")
        try:
            return self.conn.recv()
        except EOFError:
            self.proc.join()
            code, self.proc = self.proc.exitcode, None
            pytest.fail(f"{kind}({kw!r}): the worker died (exit code {code})")

    def stop(self) -> None:
        if self.proc is not None and self.proc.is_alive():
            self.conn.send(None)
            self.proc.join(10)


@pytest.fixture(scope="module")
def worker():
    w = Worker()
    w.start()
    yield w
    w.stop()


def returns_or_refuses(verdict: tuple[str, str]) -> None:
    what, text = verdict
    assert what in ("ok", "refused"), text
    assert "\n" not in text


# ---- strategies ---------------------------------------------------------------------------

def nasty(valid: float) -> st.SearchStrategy:
    """A field's value: valid (float or numpy scalar), adversarial float, or a wrong type."""
    return st.one_of(st.just(valid), st.sampled_from([np.float32(valid), np.int64(round(valid))
                                                      if valid == round(valid) else np.float64(valid)]),
                     st.sampled_from(NASTY_FLOATS), st.sampled_from(WRONG_TYPES),
                     st.floats(allow_nan=True, allow_infinity=True))


@st.composite
def params_kw(draw, n_bad: int = 3) -> dict:
    kw = dict(VALID)
    for name in draw(st.lists(st.sampled_from(sorted(VALID) + ["tilt", "throw", "mu"]),
                              max_size=n_bad, unique=True)):
        kw[name] = draw(nasty(VALID.get(name, 0.0)))
    kw["contact"] = draw(st.sampled_from(["stick", "stick", "slide", "coulomb", "bogus", None, 3]))
    return kw


def state_arrays(p, n: int, draw) -> dict:
    from bbb import Params
    from bbb.ensemble import initial_state, speed_cap

    family = draw(st.sampled_from(["rest", "dropped", "launched"]))
    q = Params(**p)
    cap = speed_cap(q)  # a valid start on every corner: within the caps there
    base = initial_state(q, n, np.random.SeedSequence(draw(st.integers(0, 99))), family,
                         drop_height=(0.0, min(2.0, 0.5 * cap**2 / (2 * q.g))),
                         launch_speed=(0.0, min(200.0, 0.5 * cap)))
    arrays = {k: getattr(base, k).copy() for k in FIELDS}
    for name in draw(st.lists(st.sampled_from(FIELDS), min_size=1, max_size=2, unique=True)):
        how = draw(st.sampled_from(["value", "value", "type", "shape"]))
        if how == "value":
            v = draw(st.one_of(st.sampled_from(NASTY_FLOATS), st.floats(-1e6, 1e6)))
            if arrays[name].dtype.kind == "f":
                arrays[name][draw(st.integers(0, n - 1))] = v
            else:
                arrays[name] = np.full(n, v)
        elif how == "type":
            arrays[name] = draw(st.sampled_from(WRONG_TYPES + [np.full(n, 1j), np.full(n, "a"),
                                                               np.zeros(n, bool)]))
        else:
            arrays[name] = draw(st.sampled_from([arrays[name][:1], arrays[name].reshape(n, 1),
                                                 np.concatenate([arrays[name]] * 2)]))
    return arrays


#: valid floors at the edges of bbb's ranges (none of them may hang either)
CORNERS = [VALID, VALID | dict(A=0.0), VALID | dict(f=1e5, A=3 * 9800.0 / (2e5 * math.pi) ** 2),
           VALID | dict(A=1000 * 9800.0 / (120 * math.pi) ** 2), VALID | dict(g=1.0, A=1e-4),
           VALID | dict(S=1e-6, R=1e-6), VALID | dict(R=1e15), VALID | dict(R=math.inf),
           VALID | dict(alpha=1.0, beta=1.0), VALID | dict(alpha=5e-324, beta=0.0),
           VALID | dict(f=1e-3), VALID | dict(tilt=30.0, throw=10.0, R=1.05),
           VALID | dict(contact="coulomb", mu=1e12), VALID | dict(contact="slide", R=1.05)]


@st.composite
def simulate_kw(draw) -> dict:
    p = draw(st.sampled_from(CORNERS))
    kw = dict(params=p, n_particles=2, t_max=draw(st.one_of(st.sampled_from([0.05, 0.01]),
                                                            nasty(0.05))), seed=0)
    if draw(st.booleans()):
        kw["state"] = state_arrays(p, 2, draw)
    else:
        kw["initial"] = draw(st.sampled_from(["rest", "dropped", "launched"]))
    for name, valid in (("n_particles", 2), ("seed", 0), ("record_collisions", 3),
                        ("record_from", 0.0)):
        if draw(st.integers(0, 5)) == 0:
            kw[name] = draw(nasty(valid))
    return kw


@st.composite
def numerics_kw(draw) -> dict:
    return {name: draw(nasty(valid)) for name, valid in (("tol_t", 1e-12), ("v_stick", 1e-3),
                                                          ("max_step", 0.25))}


# ---- the claims ---------------------------------------------------------------------------

fast = settings(max_examples=FAST, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
many = settings(max_examples=MANY, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@fast
@given(kw=params_kw())
def test_params_returns_or_refuses_in_one_line(worker, kw):
    returns_or_refuses(worker.call("params", kw))


@fast
@given(kw=numerics_kw())
def test_numerics_returns_or_refuses_in_one_line(worker, kw):
    returns_or_refuses(worker.call("numerics", kw))


@fast
@given(data=st.data())
def test_an_initial_state_returns_or_refuses_in_one_line(worker, data):
    returns_or_refuses(worker.call("state", state_arrays(VALID, 3, data.draw)))


def issue_state(**values) -> dict:
    """Two launched particles of the paper's floor at 60 Hz, one field of the first replaced."""
    from bbb import Params
    from bbb.ensemble import initial_state

    st = initial_state(Params(**VALID), 2, np.random.SeedSequence(1), "launched")
    arrays = {k: getattr(st, k).copy() for k in FIELDS}
    for k, v in values.items():
        arrays[k][0] = v
    return dict(params=VALID, n_particles=2, t_max=1.0, seed=0, state=arrays)


# the inputs that never returned before the checks and the search budget existed
@example(kw=issue_state(d=math.nan))
@example(kw=issue_state(vx=math.inf))
@example(kw=issue_state(vx=1e300))
@example(kw=issue_state(d=5.0, y=-3.0))
@example(kw=dict(params=VALID | dict(S=1e300, R=1e300), n_particles=1, t_max=1.0, seed=0))
@example(kw=dict(params=VALID | dict(f=1e300), n_particles=1, t_max=1.0, seed=0))
@fast
@given(kw=simulate_kw())
def test_simulate_returns_or_refuses_within_the_watchdog(worker, kw):
    returns_or_refuses(worker.call("simulate", kw))


@pytest.mark.slow
@many
@given(kw=params_kw(n_bad=7))
def test_params_returns_or_refuses_in_one_line_many(worker, kw):
    returns_or_refuses(worker.call("params", kw))


@pytest.mark.slow
@many
@given(kw=simulate_kw())
def test_simulate_returns_or_refuses_within_the_watchdog_many(worker, kw):
    returns_or_refuses(worker.call("simulate", kw))


def test_the_watchdog_fails_a_call_that_hangs(worker):
    # the harness itself can fail: a call the worker cannot answer in time (here: it sleeps)
    w = Worker()
    w.proc, w.conn = _sleeper()
    with pytest.raises(pytest.fail.Exception, match="did not return within 0.5 s"):
        w.call("sleep", {}, timeout=0.5)


def test_the_watchdog_fails_a_call_whose_worker_dies(worker):
    w = Worker()
    w.proc, w.conn = _sleeper(_exit_at_once)
    with pytest.raises(pytest.fail.Exception, match="the worker died"):
        w.call("exit", {}, timeout=WARMUP)


def _sleep_forever(conn) -> None:
    import time

    conn.recv()
    time.sleep(3600)


def _exit_at_once(conn) -> None:
    import os

    conn.recv()
    os._exit(3)


def _sleeper(target=_sleep_forever):
    ctx = mp.get_context("spawn")
    conn, child = ctx.Pipe()
    proc = ctx.Process(target=target, args=(child,), daemon=True)
    proc.start()
    child.close()
    return proc, conn
