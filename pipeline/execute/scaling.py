"""Scaling on paper: a run's wall time on N workers, simulated task by task (``bbb plan
--workers 2,8,64,256``).

What is simulated is what :mod:`pipeline.execute.run` and :mod:`pipeline.execute.waves` do:

* **Start-up.**  On this machine (``local``): the client lays out the store and loads the
  kernel (``base`` + ``warm``, or ``cold`` if numba's cache is empty), starts N worker
  processes at once (``worker_start`` CPU-s each, sharing the cores), loads the kernel in one
  worker, then in all the others at once (``warm`` each, sharing the cores); the first task
  is submitted when every worker is ready.  On SLURM (``slurm``): the jobs start
  ``job_wait`` after submission, the processes of a job start at once, then load the kernel
  one after another (WarmNumba's per-host lock), the first from numba's cache on the shared
  filesystem (``warm``) or compiling it (``cold``); each worker takes tasks as soon as it
  is ready, the first task is submitted when the first worker is.
* **The client** submits each task (``submit`` s), handles each result (``result`` s)
  and, when the last task of a (point, family)'s wave is done, decides on the next wave from
  the chunks done so far (``decide_fixed + decide x chunks`` s: the bootstrap of D), then
  submits it.  An adaptive unit's wave k + 1 starts only after wave k and its decision are
  complete (waves.py); a fixed-N scene is one wave per unit.
* **The scheduler** gives a worker with a free slot the queued task of highest priority (the
  lowest point index, then the earliest submitted: run.py and waves.py submit with priority
  -fi), ``sched`` s per task.  A worker holds ``slots`` tasks (Dask's worker-saturation: the
  running one and one waiting), so a task submitted now waits behind the one a busy worker
  already holds.
* **One serial timeline for both**: the scheduler runs inside ``bbb run``'s process (a
  LocalCluster's, and dask-jobqueue's), on the same interpreter lock as the client, so every
  submit, result, decision and dispatch takes its turn on one timeline: 1 / (sched + submit
  + result) tasks per second is the most a run sustains.
* **The workers**: a task takes its CPU-s (the plan's chunk CPU + per-task overhead) on a
  core of its own; workers that outnumber their host's cores share them (processor
  sharing: k busy workers on c < k cores each run at c / k of a core), so 8 workers on 2
  cores are simulated as such, not as 8 cores.

The result, :class:`Timeline`, has the wall time and the lower bounds that show what bounds
it: the start-up, the work over the cores as they become ready, the longest chain of waves of
one unit (its tasks, dispatches and decisions one after another), and the serial time of
client and scheduler.
Not simulated: network latency (hidden by Dask's prefetch of one more task per worker),
work stealing, jobs pending in a busy queue beyond ``job_wait``, workers lost mid-run, and
the points refinement adds (the plan does not price them).
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass, field
from itertools import accumulate

__all__ = ["Unit", "Costs", "Deployment", "Timeline", "simulate", "ready_times"]

_EPS = 1e-9


@dataclass(frozen=True)
class Unit:
    """One (point, family): ``waves`` tasks of ``task_s`` CPU-s each (on a core of its own),
    wave k + 1 submitted once wave k is done and decided; ``key``: its priority, lower first."""

    key: int
    task_s: float
    waves: tuple[int, ...]


@dataclass(frozen=True)
class Costs:
    """The overheads of a run, s; defaults measured on this machine (docs/cluster.md,
    benchmarks/results/scaling-*.txt).  Zero everywhere: the pure list-scheduling model."""

    base: float = 0.0          # client: store laid out, lock, cluster object, before workers
    worker_start: float = 0.0  # CPU-s to start one worker process (interpreter, dask, bbb)
    warm: float = 0.0          # one process loads the kernel from numba's cache
    cold: float = 0.0          # one process compiles the kernel (no cache it can read)
    sched: float = 0.0         # scheduler time per task (1 / the tasks per second it sustains)
    submit: float = 0.0        # client time per task submitted
    result: float = 0.0        # client time per result handled
    decide_fixed: float = 0.0  # client time per wave decision ...
    decide: float = 0.0        # ... plus this per chunk it reads (the bootstrap of D)
    end: float = 0.0           # cluster closed, store consolidated
    job_wait: float = 0.0      # slurm: sbatch to the job running


@dataclass(frozen=True)
class Deployment:
    """``workers`` single-threaded workers: ``local`` (one host of ``cores`` cores: this
    machine) or ``slurm`` (jobs of ``per_host`` workers on ``per_host`` cores each);
    ``cold``: numba's cache is empty (local) or not readable by the nodes (slurm)."""

    kind: str
    workers: int
    cores: int
    per_host: int = 1
    cold: bool = False
    #: tasks a worker holds at once, running or waiting: Dask's worker-saturation (1.1) on one
    #: thread gives 2, so a task submitted now waits behind one more task of a busy worker
    slots: int = 2

    def hosts(self) -> list[tuple[int, int]]:
        """(workers, cores) of each host."""
        if self.kind == "local":
            return [(self.workers, self.cores)]
        full, rest = divmod(self.workers, self.per_host)
        return [(self.per_host, self.per_host)] * full + ([(rest, rest)] if rest else [])


@dataclass
class Timeline:
    """The simulated run: ``wall`` s in all, the first task submitted at ``compute_start``;
    ``bounds``: lower bounds of the wall time by cause (s); ``busy``: worker-seconds in tasks."""

    wall: float
    compute_start: float
    tasks: int
    busy: float
    bounds: dict[str, float] = field(default_factory=dict)

    @property
    def bound(self) -> str:
        """What bounds the wall time: the largest lower bound ("tail" where the wall exceeds
        every bound by more than 15 %: the packing of the last tasks)."""
        name, value = max(self.bounds.items(), key=lambda kv: kv[1])
        return "tail" if self.wall > 1.15 * value else name


def ready_times(dep: Deployment, costs: Costs) -> tuple[float, list[tuple[float, int]]]:
    """(when the client submits the first task, [(when worker w is ready, its host)])."""
    client = costs.base + (costs.cold if dep.cold else costs.warm)
    out = []
    if dep.kind == "local":
        n, c = dep.workers, dep.cores
        t = client + costs.worker_start * max(1.0, n / c) + costs.warm
        if n > 1:
            t += costs.warm * max(1.0, (n - 1) / c)
        return t, [(t, 0)] * n
    for h, (n, c) in enumerate(dep.hosts()):
        t = costs.job_wait + costs.worker_start * max(1.0, n / c)
        for j in range(n):  # the processes of a host load the kernel one after another
            t += costs.cold if (dep.cold and j == 0) else costs.warm
            out.append((t, h))
    return max(client, min(t for t, _ in out)), out


class _Host:
    """The running tasks of one host, sharing its cores: virtual time V advances at
    min(1, cores / running) per second; a task ends when V reaches its start V + its CPU-s."""

    def __init__(self, cores: int):
        self.cores, self.v, self.t, self.version = cores, 0.0, 0.0, 0
        self.running: list[tuple[float, int, int]] = []  # (V at its end, seq, worker)

    def rate(self) -> float:
        return min(1.0, self.cores / len(self.running)) if self.running else 1.0

    def advance(self, t: float) -> None:
        self.v += (t - self.t) * self.rate()
        self.t = t

    def next_end(self) -> float:
        return self.t + max(0.0, self.running[0][0] - self.v) / self.rate()


def simulate(units: list[Unit], dep: Deployment, costs: Costs = Costs()) -> Timeline:
    """The run of ``units`` on the deployment ``dep``, event by event (see the module)."""
    t0, workers = ready_times(dep, costs)
    hosts = [_Host(c) for _, c in dep.hosts()]
    events: list[tuple] = []  # (time, seq, kind, a, b)
    seq = 0

    def push(t, kind, a=0, b=0):
        nonlocal seq
        seq += 1
        heapq.heappush(events, (t, seq, kind, a, b))

    for w, (t, _) in enumerate(workers):
        push(t, "ready", w)
    client = t0
    wave = [0] * len(units)         # current wave of each unit
    outstanding = [0] * len(units)  # its tasks not yet done
    chunks = [0] * len(units)       # its chunks submitted so far

    def submit_wave(u: int) -> None:
        nonlocal client
        n = units[u].waves[wave[u]]
        outstanding[u], chunks[u] = n, chunks[u] + n
        for _ in range(n):
            client += costs.submit
            push(client, "arrive", u)

    for u in sorted(range(len(units)), key=lambda i: units[i].key):
        if units[u].waves:
            submit_wave(u)
    queue: list[tuple] = []   # (key, arrival, seq, unit): tasks the scheduler holds
    load = [0] * len(workers)  # tasks given to each worker (running, held, on their way)
    levels: list[list[int]] = [[] for _ in range(dep.slots)]  # ready workers by load (lazy)
    held: list[list[tuple]] = [[] for _ in workers]  # tasks a busy worker holds, by priority
    running: dict[int, int] = {}  # worker -> unit
    last, busy, n_tasks = t0, 0.0, 0

    def dispatch(t: float) -> None:
        nonlocal client
        while queue:
            lv = next((i for i, level in enumerate(levels) if level), None)
            if lv is None:
                return
            w = heapq.heappop(levels[lv])
            if load[w] != lv:
                continue  # a stale entry: the worker's load changed since
            key, _, _, u = heapq.heappop(queue)
            client = max(t, client) + costs.sched
            load[w] += 1
            if load[w] < dep.slots:
                heapq.heappush(levels[load[w]], w)
            push(client, "deliver", w, (key, u))

    def start(t: float, w: int, u: int) -> None:
        running[w] = u
        hi = workers[w][1]
        h = hosts[hi]
        h.advance(t)
        heapq.heappush(h.running, (h.v + units[u].task_s, w, w))
        reschedule(hi)

    def reschedule(hi: int) -> None:
        h = hosts[hi]
        h.version += 1
        if h.running:
            push(h.next_end(), "host", hi, h.version)

    while events:
        t, s, kind, a, b = heapq.heappop(events)
        if kind == "ready":
            heapq.heappush(levels[0], a)
        elif kind == "arrive":
            heapq.heappush(queue, (units[a].key, t, s, a))
        elif kind == "deliver":
            if a in running:
                heapq.heappush(held[a], (b[0], s, b[1]))
            else:
                start(t, a, b[1])
        elif kind == "host":
            h = hosts[a]
            if b != h.version:
                continue  # the host's running set changed since this end was foreseen
            h.advance(t)
            while h.running and h.running[0][0] <= h.v + _EPS:
                _, _, w = heapq.heappop(h.running)
                u = running.pop(w)
                busy += units[u].task_s
                n_tasks += 1
                last = t
                load[w] -= 1
                heapq.heappush(levels[load[w]], w)
                if held[w]:
                    start(t, w, heapq.heappop(held[w])[2])
                client = max(client, t) + costs.result
                outstanding[u] -= 1
                if outstanding[u] == 0:  # its wave is complete: decide
                    client += costs.decide_fixed + costs.decide * chunks[u]
                    if wave[u] + 1 < len(units[u].waves):
                        wave[u] += 1
                        submit_wave(u)
            reschedule(a)
        if not events or events[0][0] > t:
            dispatch(t)  # once everything of this instant has happened
    wall = max(last, client) + costs.end
    return Timeline(wall, t0, n_tasks, busy, _bounds(units, dep, costs, t0, workers))


def _work_done_by(work: float, ready: list[tuple[float, float]], t0: float) -> float:
    """The earliest time workers ready at their (time, share of a core) can have done
    ``work`` CPU-s, none before t0: the work bound with the workers' staggered start-up."""
    rate, done, t = 0.0, 0.0, t0
    for r, share in sorted((max(r, t0), share) for r, share in ready):
        if rate > 0 and done + rate * (r - t) >= work:
            break
        done, t, rate = done + rate * (r - t), r, rate + share
    return t + (work - done) / rate if rate > 0 else t


def _bounds(units: list[Unit], dep: Deployment, costs: Costs, t0: float,
            workers: list[tuple[float, int]]) -> dict[str, float]:
    """Lower bounds of the wall time, s, by cause."""
    hosts = dep.hosts()
    share = [min(1.0, c / n) for n, c in hosts]  # of a core, per worker of each host
    tasks = sum(sum(u.waves) for u in units)
    work = sum(u.task_s * sum(u.waves) for u in units)
    decisions = sum(len(u.waves) for u in units)
    read = sum(sum(accumulate(u.waves)) for u in units)

    def chain(u: Unit) -> float:
        return sum(u.task_s + costs.sched + costs.result + costs.submit + costs.decide_fixed
                   + costs.decide * n for n in accumulate(u.waves))

    return {
        "start-up": t0 + costs.end,
        "work": _work_done_by(work, [(r, share[h]) for r, h in workers], t0) + costs.end,
        "waves": t0 + max((chain(u) for u in units), default=0.0) + costs.end,
        "serial": t0 + tasks * (costs.sched + costs.submit + costs.result)
                  + decisions * costs.decide_fixed + read * costs.decide + costs.end,
    }

