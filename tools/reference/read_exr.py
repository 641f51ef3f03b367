#!/usr/bin/env python3
"""Open an EXR that wisp wrote with a reader that is not wisp's, and print what it holds.

Reads with the OpenEXR Python bindings when they are installed, else with Mitsuba 3's Bitmap
(the venv of this folder's README). Prints the size, the channel names and, per channel, the
min / mean / max, and checks what wisp promises: finite values, alpha in [0, 1], colour
premultiplied (exactly 0 wherever alpha is 0).

    /work/venv-mitsuba/bin/python tools/reference/read_exr.py frames/frame_00000.exr
Exit code 0 when the checks pass, 1 otherwise.
"""
import sys

import numpy as np


def read(path):
    try:
        import OpenEXR  # noqa: F401  (the bindings, when present)
        import Imath

        f = OpenEXR.InputFile(path)
        header = f.header()
        dw = header["dataWindow"]
        w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
        names = sorted(header["channels"].keys())
        pt = Imath.PixelType(Imath.PixelType.FLOAT)
        chans = {n: np.frombuffer(f.channel(n, pt), dtype=np.float32).reshape(h, w) for n in names}
        return "OpenEXR", chans
    except ImportError:
        pass
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    bmp = mi.Bitmap(path)
    arr = np.array(bmp, dtype=np.float32)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    return "mitsuba.Bitmap", {n: arr[..., i] for i, n in enumerate(names)}


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    reader, chans = read(sys.argv[1])
    any_chan = next(iter(chans.values()))
    print(f"{sys.argv[1]}: read by {reader}, {any_chan.shape[1]} x {any_chan.shape[0]}, channels {list(chans)}")
    ok = True
    for n, c in chans.items():
        finite = np.isfinite(c).all()
        ok &= bool(finite)
        print(f"  {n}: min {c.min():.6g}  mean {c.mean():.6g}  max {c.max():.6g}  finite {finite}")
    alpha = chans.get("A")
    if alpha is not None:
        in_range = bool(((alpha >= 0) & (alpha <= 1)).all())
        ok &= in_range
        colours = [chans[k] for k in ("R", "G", "B") if k in chans]
        empty = alpha == 0
        premult = all(bool((c[empty] == 0).all()) for c in colours)
        covered = float((alpha > 0).mean())
        print(f"  alpha in [0, 1]: {in_range}; colour 0 where alpha is 0 (premultiplied): {premult}; pixels with coverage: {covered:.3f}")
        ok &= premult
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
