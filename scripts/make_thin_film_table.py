#!/usr/bin/env python3
"""Writes rt's thin-film table (crates/rt/src/gpu/thin_film_table.bin) from Cycles' source.

Cycles 5.0 (`intern/cycles/scene/shader.cpp`, `ShaderManager::compute_thin_film_table`) turns
its precomputed `table_thin_film_cmf` (`intern/cycles/scene/shader.tables`, Apache-2.0,
Copyright Blender Foundation: the Fourier transform of the CIE 1931 colour matching
functions resampled by frequency, 512 complex values over optical path differences of
0 to 60 µm) into the working space's RGB and normalises each channel by its DC term; the
kernel reads it for the Airy summation of Belcour & Barla's thin film
(`kernel/closure/bsdf_util.h`). This script does the same with the XYZ-to-RGB matrix
that Cycles derives under Blender 5.0's colour configuration (scene linear is Linear
Rec.709; XYZ is reached through its `aces_interchange` role and Cycles'
ACES-AP0-to-XYZ-D65 matrix), computed with Blender's own OpenColorIO as:

    processor("aces_interchange" -> "scene_linear") x inverse(ACES_AP0_to_XYZ_D65)

    python3 scripts/make_thin_film_table.py BLENDER/intern/cycles/scene/shader.tables

Output: little-endian f32, six planes of 512: the real parts of R, G, B, then the
imaginary parts of R, G, B; nothing else.
"""

import os
import re
import struct
import sys

SIZE = 512
XYZ_TO_RGB = [
    [3.24096995, -1.5373844, -0.49861142],
    [-0.96924345, 1.87596694, 0.04155468],
    [0.05562988, -0.20397649, 1.05697116],
]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    text = open(sys.argv[1], encoding="utf-8").read()
    found = re.search(r"table_thin_film_cmf\[(\d+)\]\[6\]\s*=\s*\{(.*?)\};", text, re.S)
    if found is None:
        sys.exit(f"{sys.argv[1]}: no table_thin_film_cmf")
    values = [float(v.rstrip("f")) for v in re.findall(r"[-+0-9.eE]+f", found.group(2))]
    if int(found.group(1)) != SIZE or len(values) != 6 * SIZE:
        sys.exit(f"{sys.argv[1]}: table_thin_film_cmf has {len(values)} values, expected {6 * SIZE}")
    rows = [values[6 * i:6 * i + 6] for i in range(SIZE)]
    rgb = lambda xyz: [sum(m * v for m, v in zip(row, xyz)) for row in XYZ_TO_RGB]  # noqa: E731
    real = [rgb(r[0:3]) for r in rows]
    imag = [rgb(r[3:6]) for r in rows]
    # The DC term (real, first entry) normalises each channel's matching function to area 1.
    norm = [1.0 / c for c in real[0]]
    planes = [[real[i][c] * norm[c] for i in range(SIZE)] for c in range(3)]
    planes += [[imag[i][c] * norm[c] for i in range(SIZE)] for c in range(3)]
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "gpu", "thin_film_table.bin")
    with open(out, "wb") as f:
        for plane in planes:
            f.write(struct.pack(f"<{SIZE}f", *plane))
    print(f"{out}: {6 * SIZE} floats", file=sys.stderr)


if __name__ == "__main__":
    main()
