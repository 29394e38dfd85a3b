"""A study store's root attributes: what they hold (the resolved workflow, its TOML, the
parameters, numerics, accuracy, the seeding rule, the package version, the kernel), how the
nested ones are kept netCDF-safe (JSON strings, :data:`JSON_ATTRS`), and the fingerprint of
everything that determines the stored numbers (:func:`store_fingerprint`).
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
from importlib import metadata
from typing import Any

import zarr

from bbb.provenance import kernel_identity

from ..workflow.identity import SEEDING
from ..workflow.schema import as_dict
from ..workflow.study import Study

__all__ = ["LAYOUT_VERSION", "OLDER_LAYOUTS", "JSON_ATTRS", "KERNEL_ATTRS", "package_version",
           "root_attrs", "store_fingerprint", "read_attrs", "json_attr", "jsonable",
           "fingerprint_difference"]

# 4: every chunk carries a CRC-32C (crc32c codec) and every done chunk the digest of its values
#    (``digest``); 3: root attributes record the kernel (KERNEL_ATTRS) and are netCDF-safe
#    (JSON_ATTRS are JSON strings); 2: collisions carry bbb.record.COLLISION_FIELDS (t, x, y, vx, vy, phase);
#    1 had no phase
LAYOUT_VERSION = 4
OLDER_LAYOUTS = {3: "its chunks carry no checksums, so a damaged chunk cannot be told from "
                     "data",
                 2: "it records no kernel hash, so whether its chunks were computed by this "
                     "kernel cannot be known",
                 1: "its collisions have no floor phase"}
#: root attributes held as JSON strings (nested dicts, which netCDF attributes cannot hold)
JSON_ATTRS = ("workflow", "params", "numerics", "accuracy")
#: root attributes naming the kernel that computed the chunks (bbb.provenance.kernel_identity)
KERNEL_ATTRS = ("kernel_hash", "numba_version", "numpy_version")


def package_version() -> str:
    try:
        return metadata.version("bbb")
    except metadata.PackageNotFoundError:  # running from a source tree without install
        return "unknown"


def root_attrs(study: Study) -> dict[str, Any]:
    kernel = kernel_identity()
    return {
        "bbb_store_layout": LAYOUT_VERSION,
        "bbb_version": package_version(),
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "workflow": json_attr(study.to_dict()),
        "workflow_toml": study.text,
        "params": json_attr(study.base_params),
        "numerics": json_attr(study.accuracy.numerics().as_dict()),
        "accuracy": json_attr(as_dict(study.accuracy)),
        "seeding": SEEDING,
        **kernel,
        "workflow_fingerprint": study.fingerprint(),
        "fingerprint": store_fingerprint(study.fingerprint(), kernel),
    }


def store_fingerprint(workflow_fingerprint: str, kernel: dict[str, str]) -> str:
    """sha256 over the workflow's data fingerprint and the kernel identity (KERNEL_ATTRS):
    two stores with the same fingerprint hold the same numbers, chunk for chunk."""
    blob = json.dumps({"workflow": workflow_fingerprint, **{k: kernel[k] for k in KERNEL_ATTRS}},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()


def read_attrs(group: zarr.Group) -> dict[str, Any]:
    """A store's root attributes with the JSON strings of :data:`JSON_ATTRS` decoded (a store
    of layout <= 2 holds them as nested dicts already: returned as they are)."""
    attrs = dict(group.attrs)
    for key in JSON_ATTRS:
        if isinstance(attrs.get(key), str):
            try:
                attrs[key] = json.loads(attrs[key])
            except ValueError:
                pass  # left as it is: bbb verify reports an unreadable attribute
    return attrs


def json_attr(o: Any) -> str:
    return json.dumps(jsonable(o), sort_keys=True)


def jsonable(o: Any) -> Any:
    if isinstance(o, dict):
        return {k: jsonable(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [jsonable(v) for v in o]
    return o


def fingerprint_difference(old: Study, new: Study) -> str:
    """Name the first data-determining key that differs, e.g. 'params.alpha: 0.7 -> 0.5'."""
    a, b = old.data_identity(), new.data_identity()
    for k in a:
        if a[k] != b[k]:
            if isinstance(a[k], dict):
                for kk in sorted(set(a[k]) | set(b[k])):
                    if a[k].get(kk) != b[k].get(kk):
                        return f"{k}.{kk}: store {a[k].get(kk)!r}, workflow {b[k].get(kk)!r}"
            return f"{k}: store {a[k]!r}, workflow {b[k]!r}"
    return "fingerprints differ"
