"""Elastic workers: as many workers as there are chunks queued, between a minimum and a maximum.

The run knows its queue exactly -- the chunks it has submitted and not yet got back (a fixed-N
scene's remaining chunks, an adaptive one's open waves, which come and go as waves are decided)
-- and publishes that number in the scheduler's metadata (:class:`QueueGauge`, at most every
``PERIOD_S`` and whenever a wave is submitted).  :class:`WaveAdaptive` is Dask's ``Adaptive``
with its documented hook, ``target()``, overridden to read that number: one single-threaded
worker per queued chunk, clamped by Adaptive to ``[minimum, maximum]``; Adaptive then asks
the cluster to scale (dask-jobqueue submits or cancels jobs), scaling down only after
``wait_count`` consecutive lower targets (Dask's default 3) and retiring idle workers first.
"""

from __future__ import annotations

import time

from distributed.deploy.adaptive import Adaptive

__all__ = ["QUEUED_KEY", "PERIOD_S", "QueueGauge", "WaveAdaptive"]

#: the scheduler metadata key holding the chunks a run has queued
QUEUED_KEY = "bbb-queued-chunks"
#: the gauge publishes at most this often while results come in, s
PERIOD_S = 0.5


class QueueGauge:
    """Publishes a run's queued chunks to the scheduler (``client.set_metadata``)."""

    def __init__(self, client):
        self.client, self.last, self.sent = client, -1.0, None

    def publish(self, queued: int, force: bool = False) -> None:
        now = time.monotonic()
        if queued == self.sent or not (force or now - self.last >= PERIOD_S):
            return
        self.client.set_metadata(QUEUED_KEY, int(queued))
        self.last, self.sent = now, queued


class WaveAdaptive(Adaptive):
    """Adaptive scaling to the run's queued chunks (see the module); 0 before any is queued.

    ``retiring``: a set shared with pipeline.execute.cluster.JobKeeper, which replaces a job
    whose workers all left -- except the workers this scales down, whose names it adds to
    the set before retiring them (their jobs end on purpose)."""

    def __init__(self, *args, retiring: set | None = None, **kwargs):
        super().__init__(*args, **kwargs)
        self.retiring = set() if retiring is None else retiring

    async def target(self) -> int:
        queued = await self.scheduler.get_metadata(keys=[QUEUED_KEY], default=0)
        return int(queued or 0)

    async def scale_down(self, workers) -> None:
        self.retiring.update(str(w) for w in workers)
        await super().scale_down(workers)
