"""The exporter's command line (see rt_blender/rt_export.py, the exporter itself, part of
the rt_blender extension):

  python blender/rt_export.py FILE.blend --out assets/ [--scene scenes/NAME.toml]
      (with the `bpy` module from PyPI, bpy==5.0.1 on Python 3.11)
  blender -b FILE.blend -P blender/rt_export.py -- --out assets/ [--scene ...]

Imported (a script beside it doing `import rt_export`), it is the extension's exporter
module itself.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from rt_blender import rt_export as _exporter  # noqa: E402

if __name__ == "__main__":
    _exporter.main()
else:
    sys.modules[__name__] = _exporter
