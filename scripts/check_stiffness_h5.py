"""Reads a stiffness file with h5py and prints what another tool would see.

Usage: check_stiffness_h5.py FILE. Prints one JSON object: root attributes,
dataset shapes and units (the optional root-stress block's too, when the
file has it). Exits non-zero if a documented dataset or its `units`
attribute is missing.
"""
import json
import sys

import h5py

DATASETS = [
    "grid/xi", "grid/eta", "grid/position", "grid/normal", "grid/lever",
    "grid/depth_h", "teeth/solved", "teeth/offsets",
    "compliance/total", "compliance/local", "compliance/global",
]

with h5py.File(sys.argv[1], "r") as f:
    out = {"attrs": {}, "shapes": {}, "units": {}}
    for k, v in f.attrs.items():
        out["attrs"][k] = v.decode() if isinstance(v, bytes) else (v.item() if hasattr(v, "item") else v)
    for name in DATASETS:
        ds = f[name]
        out["shapes"][name] = list(ds.shape)
        if ds.dtype.kind == "f":
            out["units"][name] = ds.attrs["units"]
    if "root_stress" in f:
        for name in ["root_stress/offsets", "root_stress/xi", "root_stress/height", "root_stress/stress"]:
            ds = f[name]
            out["shapes"][name] = list(ds.shape)
            if ds.dtype.kind == "f":
                out["units"][name] = ds.attrs["units"]
    total = f["compliance/total"][...]
    out["total_sum"] = float(total.sum())
    print(json.dumps(out))
