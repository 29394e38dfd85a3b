"""What the store's checks cost -- the CRC-32C codec on every chunk file and the digest of each
done chunk's values -- in size and in read time, on stores made by `bbb run`.

    python -m benchmarks.perf.store_checks STORE [STORE ...]

Size: the store's chunk files (count, bytes, disk blocks of 4 KiB), the 4 bytes of CRC-32C
each carries, and the ``digest`` array's files.  The alternative to the digest for telling a
deleted chunk from an empty one, ``write_empty_chunks=True``, is measured by copying every
array into a scratch store with it (files and disk added).

Read: every done chunk of every data array, best of 5 -- chunk by chunk through Zarr from a
scratch copy without the CRC-32C codec (layout 3) and from the store (codec CRC); as
StudyStore.read_done read it before the digest (a call per array, point and family); as the
readers read it now (read_done: codec CRC and digest, a fresh handle: no digest cached); and
the whole-store check `bbb run` makes before it resumes (StudyStore.damage).  Rates are MB
of decoded values per s.
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import sys
import tempfile
import time

import numpy as np
import zarr
from zarr.codecs import ZstdCodec

from pipeline.store.study_store import StoreError, StudyStore

BLOCK = 4096


def files_of(path: str) -> tuple[int, int, int]:
    """(chunk files, their bytes, disk blocks in bytes) under ``path``, zarr.json excluded."""
    n = size = disk = 0
    for root, _, names in os.walk(path):
        for name in names:
            if name == "zarr.json":
                continue
            st = os.stat(os.path.join(root, name))
            n, size, disk = n + 1, size + st.st_size, disk + st.st_blocks * 512
    return n, size, disk


def copy(src: str, dst: str, *, crc: bool, write_empty: bool) -> None:
    g = zarr.open_group(src, mode="r")
    out = zarr.open_group(dst, mode="w", attributes=dict(g.attrs))
    for name, a in g.arrays():
        codecs = (ZstdCodec(level=0, checksum=False),) if not crc else a.metadata.codecs[1:]
        b = out.create_array(name, shape=a.shape, chunks=a.chunks, dtype=a.dtype,
                             fill_value=a.fill_value, compressors=codecs,
                             dimension_names=a.metadata.dimension_names,
                             attributes=dict(a.attrs), config={"write_empty_chunks": write_empty})
        b[...] = a[...]


def best(f, *args, n: int = 5) -> float:
    times = []
    for _ in range(n):
        t = time.perf_counter()
        f(*args)
        times.append(time.perf_counter() - t)
    return min(times)


def read_all(path: str, store: StudyStore, done: np.ndarray) -> None:
    g = zarr.open_group(path, mode="r")
    cs = store.study.accuracy.chunk_size
    for name in store.checked:
        a = g[name]
        for fi, mi in zip(*np.nonzero(done.any(axis=2)), strict=True):
            for ci in np.flatnonzero(done[fi, mi]):
                np.asarray(a[fi, mi, ci * cs:(ci + 1) * cs])


def read_as_before(store: StudyStore, done: np.ndarray) -> None:
    """read_done as it was before the checks (layout 3): the group opened per call, one read
    per run of done chunks, no digest."""
    from pipeline.store.integrity import runs

    cs = store.study.accuracy.chunk_size
    for name in store.checked:
        for fi, mi in zip(*np.nonzero(done.any(axis=2)), strict=True):
            arr = store.group()[name]
            for c0, c1 in runs(np.flatnonzero(done[fi, mi])):
                np.asarray(arr[fi, mi, c0 * cs: c1 * cs])


def read_checked(store: StudyStore, done: np.ndarray) -> None:
    for name in store.checked:
        for fi, mi in zip(*np.nonzero(done.any(axis=2)), strict=True):
            store.read_done(name, int(fi), int(mi), done[fi, mi])


def main(paths: list[str]) -> None:
    print(f"# bbb store checks  {time.strftime('%Y-%m-%d')}")
    print(f"# CPU: {platform.processor() or platform.machine()} ({os.cpu_count()} cores, shared "
          f"and loaded)  python {platform.python_version()}  zarr {zarr.__version__}")
    for path in paths:
        store = StudyStore.open(path)
        done = store.done()
        n, size, disk = files_of(path)
        dn, dsize, ddisk = files_of(os.path.join(path, "digest"))
        mb = sum(np.asarray(store.read_done(name, int(fi), int(mi), done[fi, mi])).nbytes
                 for name in store.checked
                 for fi, mi in zip(*np.nonzero(done.any(axis=2)), strict=True)) / 1e6
        with tempfile.TemporaryDirectory() as tmp:
            plain, empty = os.path.join(tmp, "plain.zarr"), os.path.join(tmp, "empty.zarr")
            copy(path, plain, crc=False, write_empty=False)
            copy(path, empty, crc=True, write_empty=True)
            en, esize, edisk = files_of(empty)
            t_plain = best(read_all, plain, store, done)
            t_crc = best(read_all, path, store, done)
            t_before = best(read_as_before, store, done)
            t_checked = best(read_checked, StudyStore.open(path), done)  # digests not cached
            t_scan = best(store.damage)
            shutil.rmtree(plain)
        print(f"\n## {store.study.name}: {os.path.basename(path)}")  # no machine paths
        print(f"{int(done.sum())} done chunks, {len(store.checked)} data arrays, {mb:.1f} MB of "
              "decoded data values")
        print("| size | chunk files | bytes | on disk |")
        print("| --- | --- | --- | --- |")
        print(f"| store (layout 4) | {n} | {size} | {disk} |")
        print(f"| of it: CRC-32C, 4 B a file | | {4 * n} ({400 * n / size:.2f} %) | 0 |")
        print(f"| of it: digest array | {dn} ({100 * dn / n:.1f} %) | {dsize} | {ddisk} "
              f"({100 * ddisk / disk:.1f} %) |")
        print(f"| write_empty_chunks=True instead (added) | {en - n} ({100 * (en - n) / n:.1f} %)"
              f" | {esize - size} | {edisk - disk} ({100 * (edisk - disk) / disk:.1f} %) |")
        print("| read of every done chunk | s | MB/s |")
        print("| --- | --- | --- |")
        for label, t in (("chunk by chunk, no CRC codec (layout 3)", t_plain),
                         ("chunk by chunk, CRC codec", t_crc),
                         ("as read_done before the digest: CRC codec", t_before),
                         ("read_done: CRC codec + digest", t_checked),
                         ("damage(): bbb run's check", t_scan)):
            print(f"| {label} | {t:.3f} | {mb / t:.0f} |")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("stores", nargs="+", metavar="STORE", help="stores made by bbb run")
    try:
        main(ap.parse_args().stores)
    except StoreError as exc:
        print(f"store_checks: {exc}", file=sys.stderr)
        sys.exit(2)
