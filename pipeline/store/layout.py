"""The layout of a study store: which arrays a workflow's store holds, their dimensions,
units, dtypes and chunks, created once when the store is made (:mod:`pipeline.store.study_store` opens,
resumes, reads and writes it; ``bbb verify`` rebuilds this layout to compare).

Layout (``F`` frequencies, ``M`` families, ``N`` particles per (frequency, family) split into
``C = N / chunk_size`` chunks, ``T`` sample times, ``K`` recorded collisions per particle):

=============  ==========================================  ======  ===========================
array          dims                                        dtype   chunks
=============  ==========================================  ======  ===========================
frequency      (frequency,)                 Hz             f8      whole
family         (family,)                    name           str     whole
initial        (family,)                    rest|dropped|..str     whole
particle       (particle,)                  index          i8      whole
chunk          (chunk,)                     index          i8      whole
time           (time,)                      s              f8      whole    [positions]
collision      (collision,)                 index          i8      whole    [collisions]
field          (field,)          bbb.record.COLLISION_FIELDS  str  whole    [collisions]
positions      (frequency, family, particle, time)  x, mm  f8      (1, 1, chunk_size, T)
collisions     (frequency, family, particle, collision, field)  f8  (1, 1, chunk_size, K, n_fields)
n_recorded     (frequency, family, particle)  valid rows   i8      (1, 1, chunk_size) [coll.]
n_<counter>    (frequency, family, particle)  bbb counters  i8  (1, 1, chunk_size)
held_time, sliding_time  (frequency, family, particle)  s  f8  (1, 1, chunk_size)  [contact]
digest         (frequency, family, chunk, array)  CRC-32C  i8      (1, 1, 1, A)
done           (frequency, family, chunk)   bool           b1      (1, 1, 1)
chunk_seconds  (frequency, family, chunk)   simulate, s    f8      (1, 1, 1)   not reproducible
n_chunks_used  (frequency, family)          chunks         i8      (1, 1)      [target_ci]
stop_reason    (frequency, family)          STOP_LEGEND    i1      (1, 1)      [target_ci]
refined        (frequency,)                 added by refine b1     like frequency  [refine]
period         (period,)                    index          i8      whole    [jumps]
jumps          (frequency, family, particle, period)  Δx, mm  f4  (1, 1, chunk_size, P)  [jumps]
lyapunov       (frequency, family, particle)  λ, 1/s       f8      (1, 1, chunk_size)  [lyapunov]
lyapunov_per_collision  (frequency, family, particle)  λ per collision  f8  [lyapunov]
lyapunov_x_range  (frequency, family, particle)  mm          f8      (1, 1, chunk_size)  [lyapunov]
collision_jump  (collision_jump,)           index          i8      whole    [x_jumps]
collision_dx   (frequency, family, particle, collision_jump)  mm  f4  (1, 1, chunk_size, J)  [x_jumps]
collision_dt   (frequency, family, particle, collision_jump)  s   f4  (1, 1, chunk_size, J)  [x_jumps]
=============  ==========================================  ======  ===========================

The coordinates and data arrays marked [positions], [collisions], [contact], [jumps],
[lyapunov] and [x_jumps] (and the ``n_<counter>`` ones) are those the scene's observables
declare (:mod:`pipeline.workflow.observables`), created in the registry's order; this module
lays out the rest (points, families, particles, chunks, digests, done markers, stops).

Every array's chunks end in a CRC-32C checksum of their stored bytes (the ``crc32c``
codec: Zarr refuses to decode a chunk whose bytes changed).  The ``A`` arrays with a
``particle`` dimension (``array``, the coordinate of ``digest``, names them in this order) are
the chunks' data: ``digest[..., a]`` is the CRC-32C of the values a task wrote into its chunk
of array ``a`` (:func:`chunk_digest`), written before ``done``, so that a done chunk whose
file was deleted (read back as fill values) or rewritten is told from the one written.

``jumps[..., n]`` = x((n+1)/f) − x(n/f) for n < floor(t_max f) (P: its largest value over the
frequencies; NaN beyond).  ``lyapunov*`` hold the first ``[observables.lyapunov] particles``
particles of each (frequency, family) (NaN beyond; −inf where the separation collapsed);
``lyapunov_x_range`` is how far each of them moved (max − min of x at the period ends of λ's
window).  ``collision_dx[..., n]``, ``collision_dt[..., n]`` = x and t of recorded collision
n + 1 minus those of collision n (``[observables.collisions] x_jumps`` = J; NaN beyond a
particle's n_recorded − 1; the collisions array keeps its first ``record`` rows of the same
recording).

With ``target_ci`` the chunk axis is sized by the cap (max_particles); a (frequency, family)
uses the first ``n_chunks_used`` chunks, and ``stop_reason`` says why it stopped
(:data:`STOP_LEGEND`, also the array's ``legend`` attribute; 0 = not decided yet: the codes
are stored values, so they live here; :mod:`pipeline.execute.adaptive` decides them).  With
``refine`` the store grows along the frequency axis (:meth:`StudyStore.add_frequencies`):
refined frequencies follow the workflow's own, ``refined`` marks them, and no chunk written
before is rewritten.
"""

from __future__ import annotations

import os

import google_crc32c
import numpy as np
import zarr
from zarr.codecs import Crc32cCodec, ZstdCodec

from ..workflow.identity import f_key
from ..workflow.keys import PARAM_LONG_NAMES, PARAM_UNITS
from ..workflow.observables.registry import selected
from ..workflow.study import Study

__all__ = ["CODECS", "chunk_digest", "DIGEST_NONE", "default_store_path", "create_layout",
           "OPEN", "TARGET", "ZERO", "CAP", "STOP_LEGEND"]

OPEN, TARGET, ZERO, CAP = 0, 1, 2, 3
#: stop_reason codes as stored (the store's ``stop_reason`` array and its ``legend``), each named
#: by what :func:`pipeline.execute.adaptive.decide` tested: "target met", D > 0 and the CI's
#: half-width <= target_ci * D; "resolved to ±d_resolved", the half-width <= d_resolved (D known
#: to ± d_resolved, whatever its size: not a claim that D is zero); "cap", max_particles reached
STOP_LEGEND = {OPEN: "open", TARGET: "target met", ZERO: "resolved to ±d_resolved", CAP: "cap"}

#: the bytes-to-bytes codecs of every array: zstd, then a CRC-32C of the compressed bytes
CODECS = (ZstdCodec(level=0, checksum=False), Crc32cCodec())
#: ``digest`` of a chunk whose data were never completely written
DIGEST_NONE = -1


def default_store_path(name: str) -> str:
    """The store of the study ``name`` when none is given: ``runs/<name>.zarr`` relative to
    the current directory (``bbb run``, :func:`pipeline.api.run_study`)."""
    return os.path.join("runs", f"{name}.zarr")


def create_layout(g: zarr.Group, study: Study) -> None:
    """Create every array of ``study``'s store in the empty group ``g`` (no data written)."""
    acc = study.accuracy
    F, M, N, C = len(study.points), len(study.families), acc.n_particles, acc.n_chunks
    cs = acc.chunk_size
    P0 = study.point_dim  # "frequency", or "point" for a grid
    # chunked by the workflow's own grid, so that refinement (which appends) keeps the chunks
    n_base = max(1, len(study.base_frequencies) if not study.grid else len(study.points))
    checked: list[str] = []  # the arrays of the chunks' data, in creation order (``digest``)

    def coord(name, values, dtype, units, long_name, dim=None, chunk=None):
        arr = g.create_array(name, shape=(len(values),), dtype=dtype,
                             chunks=(chunk or max(1, len(values)),),
                             dimension_names=[dim or name], compressors=CODECS,
                             attributes={"units": units, "long_name": long_name})
        arr[:] = np.asarray(values, dtype=dtype if dtype is not str else None)

    def data(name, dims, shape, chunks, dtype, fill, units, long_name, **extra):
        attrs = {"units": units, "long_name": long_name, **extra}
        if "family" in dims:  # CF convention: xarray then shows `initial` as a coordinate
            attrs["coordinates"] = "initial"
        g.create_array(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill,
                       dimension_names=list(dims), attributes=attrs, compressors=CODECS)
        if dims[2:3] == ("particle",):
            checked.append(name)

    if study.grid:
        coord("point", np.arange(F), "int64", "", "point of the grid, in store order",
              chunk=n_base)
        coord("frequency", [p.f for p in study.points], "float64", "Hz", "floor frequency f",
              dim="point", chunk=n_base)
        for a, values in study.grid:
            kind = str if isinstance(values[0], str) else "float64"
            coord(a, [dict(p.grid)[a] for p in study.points], kind, PARAM_UNITS[a],
                  PARAM_LONG_NAMES[a], dim="point", chunk=n_base)
    else:
        coord("frequency", list(study.frequencies), "float64", "Hz", "floor frequency f",
              chunk=n_base)
    if study.refine is not None:
        added = {f_key(f) for f in study.refined}
        coord("refined", [f_key(f) in added for f in study.frequencies], "bool", "",
              "frequency added by adaptive refinement", dim="frequency", chunk=n_base)
    coord("family", [f.name for f in study.families], str, "", "initial-condition family")
    coord("initial", [f.initial for f in study.families], str, "", "initial condition kind",
          dim="family")
    coord("particle", np.arange(N), "int64", "", "particle index within the family")
    coord("chunk", np.arange(C), "int64", "", f"ensemble chunk of {cs} particles")
    for o in selected(study):  # each observable's coordinates, then its data arrays
        for c in o.coords(study):
            coord(c.name, c.values, c.dtype, c.units, c.long_name, dim=c.dim)
        for a in o.arrays(study):
            data(a.name, (P0, "family", "particle", *(d for d, _ in a.trailing)),
                 (F, M, N, *(n for _, n in a.trailing)), (1, 1, cs, *(n for _, n in a.trailing)),
                 a.dtype, a.fill, a.units, a.long_name, **a.extra)
    coord("array", checked, str, "", "data array whose chunk a digest covers")
    data("digest", (P0, "family", "chunk", "array"), (F, M, C, len(checked)),
         (1, 1, 1, len(checked)), "int64", DIGEST_NONE, "",
         "CRC-32C of the values written into the chunk of each data array (-1: none)",
         algorithm="crc32c of the chunk's values, little-endian, C order, trailing fill "
                   "along the period axis left out")
    data("done", (P0, "family", "chunk"), (F, M, C), (1, 1, 1), "bool", False, "",
         "chunk completely written")
    data("chunk_seconds", (P0, "family", "chunk"), (F, M, C), (1, 1, 1), "float64",
         np.nan, "s", "wall time of the chunk's simulation (not reproducible)")
    if acc.adaptive:
        legend = "; ".join(f"{k} {v}" for k, v in STOP_LEGEND.items())
        data("n_chunks_used", (P0, "family"), (F, M), (1, 1), "int64", 0, "",
             "chunks used: the first n_chunks_used chunks (0: not decided yet)")
        data("stop_reason", (P0, "family"), (F, M), (1, 1), "int8", 0, "",
             f"why sampling stopped ({legend})", legend=legend)


def chunk_digest(values: np.ndarray, fill, trim: bool = False) -> int:
    """CRC-32C of one task's chunk of a data array: ``values`` (particle, ...) as stored
    (the array's dtype, little-endian, C order); ``trim``: leave out the trailing slices along
    the last axis that hold only ``fill`` (the ``period`` axis, which a grown map lengthens
    with fill), so the digest of a chunk does not change when its array grows."""
    a = np.asarray(values)
    if trim and a.ndim > 1 and a.shape[-1]:
        fill_at = np.isnan(a) if np.isnan(fill) else (a == fill)
        keep = np.flatnonzero(~fill_at.reshape(-1, a.shape[-1]).all(axis=0))
        a = a[..., : keep[-1] + 1 if keep.size else 0]
    a = np.ascontiguousarray(a, dtype=a.dtype.newbyteorder("<"))
    # the shape too: an all-fill chunk trimmed to nothing is not the empty chunk of another
    return google_crc32c.extend(google_crc32c.value(a.tobytes()), repr(a.shape).encode())
