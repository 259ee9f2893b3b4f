"""Writes many_lights.obj and many_lights.mtl: a 32 x 32 grid of small emissive squares
(2048 emissive triangles) 1 m above the ground, facing down, in six colours whose
brightness varies over a decade. Deterministic: run it again to get the same files.

    python3 assets/many_lights/make_many_lights.py
"""

from pathlib import Path

GRID = 32
SPACING = 0.35  # metres between square centres
SIZE = 0.06  # side of each square
HEIGHT = 1.0
COLOURS = {
    "warm": (1.0, 0.55, 0.2),
    "red": (1.0, 0.15, 0.1),
    "green": (0.2, 1.0, 0.3),
    "blue": (0.2, 0.35, 1.0),
    "white": (1.0, 1.0, 1.0),
    "violet": (0.7, 0.2, 1.0),
}
LEVELS = (4.0, 12.0, 40.0)  # radiance scales


def main():
    here = Path(__file__).parent
    names = []
    with open(here / "many_lights.mtl", "w") as mtl:
        mtl.write("# Emissive materials of many_lights.obj (written by make_many_lights.py).\n")
        for colour, (r, g, b) in COLOURS.items():
            for level in LEVELS:
                name = f"{colour}_{int(level)}"
                names.append(name)
                mtl.write(f"\nnewmtl {name}\nKd 0 0 0\nKe {r * level:g} {g * level:g} {b * level:g}\n")
    lines = [
        "# A grid of small emissive squares, facing down (written by make_many_lights.py).",
        "mtllib many_lights.mtl",
    ]
    half = SIZE / 2
    origin = -(GRID - 1) * SPACING / 2
    faces = {}
    vertex = 0
    for i in range(GRID):
        for j in range(GRID):
            x, z = origin + i * SPACING, origin + j * SPACING
            for dx, dz in ((-half, -half), (half, -half), (half, half), (-half, half)):
                lines.append(f"v {x + dx:.4f} {HEIGHT} {z + dz:.4f}")
            # A hash of the cell picks its colour and level: no pattern for the eye.
            h = (i * 73856093 ^ j * 19349663) % 1000003
            name = names[h % len(names)]
            faces.setdefault(name, []).append(vertex)
            vertex += 4
    for name in names:
        lines.append(f"usemtl {name}")
        for v in faces.get(name, []):
            # Wound so that the normal points down, towards the ground.
            lines.append(f"f {v + 1} {v + 2} {v + 3} {v + 4}")
    (here / "many_lights.obj").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
