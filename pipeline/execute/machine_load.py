"""What this machine gives a run now: the share of a core a process of ours gets and the
plan's wall time at that share (the last line of ``bbb plan``).  The cost model itself, for
cores that are ours, is :mod:`pipeline.execute.plan`; the share is measured by
:func:`pipeline.execute.pilot.machine_share`."""

from __future__ import annotations

from dataclasses import dataclass

from .plan import Plan

__all__ = ["MachineShare", "UNCONTENDED", "loaded_wall"]


@dataclass(frozen=True)
class MachineShare:
    """This machine now, as a run would find it (:func:`pipeline.execute.pilot.machine_share`).

    share   -- the share of a core one process of ours gets (CPU time / wall time), <= 1
    load    -- the 1-minute load average (None where the OS has none)
    grouped -- the kernel shares the CPU fairly between sessions first, then between the
               processes of a session (Linux's autogroup): a run's workers, all in the
               session of `bbb run`, then share that session's part
    """

    share: float
    load: float | None
    grouped: bool


#: a share of a core above this says only that fewer processes than cores compete
UNCONTENDED = 0.95


def loaded_wall(plan: Plan, machine: MachineShare, cores: int) -> str:
    """The plan's wall time on this machine as shared now, as a line.  One process of ours got
    s = ``machine.share`` of a core.  Sessions shared fairly (``grouped``): a session with one
    runnable process gets s cores, and so does the run's session, whose W workers and client
    then take start_up / s + W x makespan / s.  Processes shared fairly: s = cores / (others
    + 1) counts the others, and each worker gets g = min(1, cores / (others + W)) of a core,
    every part of the run 1 / g as long.  s above UNCONTENDED says only that the others are
    fewer than the cores: the 1-minute load average less this process counts them then (at
    most cores - 1), per process.  A load that changes during the run is not foreseen."""
    w, s = plan.workers, machine.share
    if s <= UNCONTENDED and machine.grouped:
        wall = plan.overheads.start_up / s + w * plan.makespan / s
        how = (f"one process of ours gets {s:.2f} of a core; the CPU is shared between "
               f"sessions (autogroup): the run's {w} workers share {s:.2f} of a core")
    else:
        if s <= UNCONTENDED:
            others = cores / s - 1
        elif machine.load is not None:
            others = min(max(0.0, machine.load - 1), cores - 1.0)
        else:
            return "at this machine's load: unknown (no load average on this system)"
        g = min(1.0, cores / (others + w))
        wall = plan.wall_s / g
        how = (f"{others:.1f} runnable processes of others on {cores} cores: each of the "
               f"{w} workers gets {g:.2f} of a core")
    return f"at this machine's load now ({how}) -> wall {wall:.0f} s ({wall / 60:.1f} min)"
