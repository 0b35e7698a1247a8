#!/usr/bin/env python3
# SPDX-License-Identifier: MIT OR Apache-2.0
"""Builds the installable add-on zip: python3 blender/build_zip.py [OUT.zip]
(default: facebem_blender.zip in the current folder). Install it in Blender with
Edit > Preferences > Add-ons > Install..., then enable "facebem expressions"."""

import pathlib
import sys
import zipfile

here = pathlib.Path(__file__).resolve().parent
package = here / "facebem_blender"
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "facebem_blender.zip")
tmp = out.with_name(out.name + ".tmp")
with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
    for path in sorted(package.rglob("*.py")):
        # Fixed timestamps: the same sources give the same bytes.
        info = zipfile.ZipInfo(str(path.relative_to(here)), date_time=(2020, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        z.writestr(info, path.read_bytes())
tmp.replace(out)
print(out)
