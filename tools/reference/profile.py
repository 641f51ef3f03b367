#!/usr/bin/env python3
"""Where in the image two renders disagree: each image's linear luminance averaged over a band
of rows, printed per column, side by side (not run by CI). ACCURACY.md section 2 reads the
darkest tenth's bands with it ("What the side-lit darkest tenth hides", "How many bounces light
the back-lit band").

usage: profile.py --rows R0,R1 --cols C0,C1[,STEP] NAME=IMAGE.exr [NAME=IMAGE.exr ...]
       profile.py --darkest-of NAME [--block K] NAME=IMAGE.exr [NAME=IMAGE.exr ...]

Rows R0..R1 and columns C0..C1 are half-open pixel ranges (row 0 at the top); every STEP-th
column is printed (default 1). A column's value is the mean over the band's rows of Rec. 709
luminance, uncovered pixels counting as 0; the mean coverage (alpha) of the first image is
printed beside it, so a silhouette shows where the band leaves the hair.
With --darkest-of, instead: the K x K blocks (default 8) at least half covered (alpha >= 0.99)
in every image, the darkest tenth of them by the named image's mean luminance, and each
image's mean luminance over those blocks and its share of the last image's (so with the
path tracer at depths 2, 3, 4 and 64 last, how much of the light there each order brings).
Example (dense blond back-lit: path tracer at all orders, wisp's export):

    profile.py --rows 140,220 --cols 220,262,2 pt=TABLE/dense/blond-back-dual/mitsuba_d64.exr \\
        wisp=OUT/dense-blond-back-dual/wisp.exr
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402


def pair(text, what):
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        sys.exit(f"profile.py: --{what} {text!r}: expected integers separated by commas")
    if len(values) not in (2, 3) or values[0] < 0 or values[1] <= values[0]:
        sys.exit(f"profile.py: --{what} {text!r}: expected START,END with 0 <= START < END")
    if len(values) == 3 and values[2] < 1:
        sys.exit(f"profile.py: --{what} {text!r}: STEP must be at least 1")
    return values


def band_profile(rgba, rows, cols):
    """Per column of cols[0]..cols[1]: mean luminance and mean alpha over rows[0]..rows[1]."""
    r0, r1 = rows
    c0, c1 = cols[:2]
    h, w = rgba.shape[:2]
    if r1 > h or c1 > w:
        sys.exit(f"profile.py: rows {r0},{r1} / columns {c0},{c1} outside the {w} x {h} image")
    band = rgba[r0:r1, c0:c1]
    return (band[..., :3] @ compare.LUMA).mean(0), band[..., 3].mean(0)


def darkest(images, of, k):
    """The darkest tenth of k x k blocks by image `of`: each image's mean luminance there."""
    names = [name for name, _ in images]
    if of not in names:
        sys.exit(f"profile.py: --darkest-of {of!r}: not one of the images ({', '.join(names)})")
    if k < 1:
        sys.exit(f"profile.py: --block {k}: must be at least 1")
    shapes = {rgba.shape for _, rgba in images}
    if len(shapes) != 1:
        sys.exit("profile.py: --darkest-of needs images of one size")
    mask = np.logical_and.reduce([rgba[..., 3] >= 0.99 for _, rgba in images])
    keep, blocks = compare.block_means(mask, k)
    if not keep.any():
        sys.exit(f"profile.py: no {k} x {k} block is half covered in every image")
    lum = {name: blocks(rgba) for name, rgba in images}
    chosen = lum[of] <= np.percentile(lum[of], 10)
    last = names[-1]
    whole = lum[last][chosen].mean()
    print(f"{chosen.sum()} of {keep.sum()} blocks of {k} px, the darkest tenth by {of}:")
    for name in names:
        mean = lum[name][chosen].mean()
        share = mean / whole if whole > 0 else float("nan")
        print(f"  {name:>9}  {mean:9.2e}  {share:6.3f} of {last}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows")
    ap.add_argument("--cols")
    ap.add_argument("--darkest-of", metavar="NAME")
    ap.add_argument("--block", type=int, default=8)
    ap.add_argument("images", nargs="+", metavar="NAME=IMAGE.exr")
    args = ap.parse_args()
    if args.darkest_of is None and (args.rows is None or args.cols is None):
        sys.exit("profile.py: give --rows and --cols, or --darkest-of NAME")
    named = []
    for item in args.images:
        name, sep, path = item.partition("=")
        if not sep or not name or not path:
            sys.exit(f"profile.py: {item!r}: expected NAME=IMAGE.exr")
        if not os.path.isfile(path):
            sys.exit(f"profile.py: {path}: no such file")
        named.append((name, path))
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    images = [(name, compare.load_rgba(mi, path)) for name, path in named]
    if args.darkest_of is not None:
        darkest(images, args.darkest_of, args.block)
        return
    rows = pair(args.rows, "rows")[:2]
    cols = pair(args.cols, "cols")
    step = cols[2] if len(cols) == 3 else 1
    profiles = [(name, band_profile(rgba, rows, cols)) for name, rgba in images]
    alpha = profiles[0][1][1]
    print("column  alpha  " + "  ".join(f"{name:>9}" for name, _ in profiles))
    for i in range(0, cols[1] - cols[0], step):
        values = "  ".join(f"{lum[i]:9.2e}" for _, (lum, _) in profiles)
        print(f"{cols[0] + i:6d}  {alpha[i]:5.2f}  {values}")


if __name__ == "__main__":
    main()
