#!/usr/bin/env python3
"""Writes rt's sheen table (crates/rt/src/gpu/sheen_ltc.bin) from Cycles' source.

The table is Cycles' `table_sheen_ltc` (Blender 4.x/5.x, `intern/cycles/scene/shader.tables`,
Apache-2.0, Copyright Blender Foundation): the fit by Zeltner, Burley and Chiang
("Practical Multiple-Scattering Sheen Using Linearly Transformed Cosines", 2022) of their
volumetric microflake sheen by a linearly transformed cosine, as Cycles' Principled BSDF
reads it. Three planes of [32 roughness][32 cos(view)], each axis sampled at i / 31:

  a       the transform's diagonal (x and y)
  b       its shear of x by z
  albedo  the directional albedo of the sheen layer

    python3 scripts/make_sheen_table.py BLENDER/intern/cycles/scene/shader.tables

Output: little-endian f32, the three planes in that order, nothing else.
"""

import os
import re
import struct
import sys

SIZE = 3 * 32 * 32


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    text = open(sys.argv[1], encoding="utf-8").read()
    found = re.search(r"table_sheen_ltc\[(\d+)\]\s*=\s*\{([^}]*)\}", text)
    if found is None:
        sys.exit(f"{sys.argv[1]}: no table_sheen_ltc")
    values = [float(v.rstrip("f")) for v in found.group(2).replace(",", " ").split()]
    if int(found.group(1)) != SIZE or len(values) != SIZE:
        sys.exit(f"{sys.argv[1]}: table_sheen_ltc has {len(values)} values, expected {SIZE}")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "gpu", "sheen_ltc.bin")
    with open(out, "wb") as f:
        f.write(struct.pack(f"<{SIZE}f", *values))
    print(f"{out}: {SIZE} floats", file=sys.stderr)


if __name__ == "__main__":
    main()
