#!/usr/bin/env python3
"""Reads a curves file of `wisp render --curves FILE.usda` with Pixar's USD library and checks
it: the stage opens, its BasisCurves prim has linear curves whose vertex counts sum to the
points of every time sample, the samples are one per time code from startTimeCode to
endTimeCode, every point is finite and inside its sample's extent, and the widths and colours
have one value per point. Prints the counts, the time range and the bounds; exits 1 on any
mismatch, 2 when the file cannot be opened.

    python3 -m pip install usd-core        # Pixar's USD for Python, about 150 MB installed
    python3 tools/usd/check_usda.py FILE.usda [--frames N] [--fps F]

`--frames` and `--fps` also check the number of samples and the time codes per second.
"""

import argparse
import math
import sys

try:
    from pxr import Usd, UsdGeom
except ImportError:
    sys.exit("check_usda.py: needs Pixar's USD for Python: python3 -m pip install usd-core")


def bounds(points):
    """Smallest and largest x, y, z of `points`."""
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return lo, hi


def fmt(v):
    return "(" + ", ".join(f"{x:.4f}" for x in v) + ")"


def check_stage(stage, args, errors):
    """Checks the layer's metadata; returns (start, end, per_second)."""
    if UsdGeom.GetStageMetersPerUnit(stage) != 1.0:
        errors.append(f"metersPerUnit is {UsdGeom.GetStageMetersPerUnit(stage)}, not 1")
    if UsdGeom.GetStageUpAxis(stage) != UsdGeom.Tokens.y:
        errors.append(f"upAxis is {UsdGeom.GetStageUpAxis(stage)}, not Y")
    start, end = stage.GetStartTimeCode(), stage.GetEndTimeCode()
    per_second = stage.GetTimeCodesPerSecond()
    if args.fps is not None and abs(per_second - args.fps) > 1e-9 * args.fps:
        errors.append(f"timeCodesPerSecond is {per_second}, expected {args.fps}")
    if stage.GetFramesPerSecond() != per_second:
        errors.append(
            f"framesPerSecond {stage.GetFramesPerSecond()} differs from timeCodesPerSecond {per_second}"
        )
    return start, end, per_second


def check_samples(curves, start, end, args, errors):
    """Checks every time sample of the points; returns (times, total points, overall bounds)."""
    counts = list(curves.GetCurveVertexCountsAttr().Get())
    total = sum(counts)
    if any(c < 2 for c in counts):
        errors.append("a curve has fewer than 2 points")
    points_attr = curves.GetPointsAttr()
    times = points_attr.GetTimeSamples()
    expected = [start + k for k in range(int(round(end - start)) + 1)]
    if times != expected:
        errors.append(f"time samples {times[:3]}…{times[-3:]} are not one per time code from {start} to {end}")
    if args.frames is not None and len(times) != args.frames:
        errors.append(f"{len(times)} time samples, expected {args.frames}")
    extent_attr = curves.GetExtentAttr()
    lo_all, hi_all = [math.inf] * 3, [-math.inf] * 3
    for t in times:
        points = points_attr.Get(t)
        if len(points) != total:
            errors.append(f"time {t}: {len(points)} points, the vertex counts sum to {total}")
            continue
        if not all(math.isfinite(x) for p in points for x in p):
            errors.append(f"time {t}: a point is not finite")
            continue
        lo, hi = bounds(points)
        extent = extent_attr.Get(t)
        if extent is None or any(lo[k] < extent[0][k] or hi[k] > extent[1][k] for k in range(3)):
            errors.append(f"time {t}: the points' bounds {fmt(lo)}–{fmt(hi)} are not inside the extent {extent}")
        lo_all = [min(a, b) for a, b in zip(lo_all, lo)]
        hi_all = [max(a, b) for a, b in zip(hi_all, hi)]
    return counts, times, total, (lo_all, hi_all)


def check_look(curves, total, errors):
    """Checks the widths and the display colours: one finite value per point."""
    widths = curves.GetWidthsAttr().Get()
    if widths is None or len(widths) != total:
        errors.append(f"{0 if widths is None else len(widths)} widths for {total} points")
    elif not all(math.isfinite(w) and w >= 0 for w in widths):
        errors.append("a width is negative or not finite")
    elif curves.GetWidthsInterpolation() != UsdGeom.Tokens.vertex:
        errors.append(f"widths interpolation is {curves.GetWidthsInterpolation()}, not vertex")
    color = UsdGeom.PrimvarsAPI(curves.GetPrim()).GetPrimvar("displayColor")
    colors = color.Get() if color else None
    if colors is not None and len(colors) != total:
        errors.append(f"{len(colors)} display colours for {total} points")
    return widths, colors


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("file")
    parser.add_argument("--frames", type=int, help="expected number of time samples")
    parser.add_argument("--fps", type=float, help="expected time codes per second")
    args = parser.parse_args()
    stage = Usd.Stage.Open(args.file)
    if stage is None:
        print(f"{args.file}: USD cannot open it", file=sys.stderr)
        return 2
    errors = []
    start, end, per_second = check_stage(stage, args, errors)
    prims = [p for p in stage.Traverse() if p.IsA(UsdGeom.BasisCurves)]
    if len(prims) != 1:
        print(f"{args.file}: {len(prims)} BasisCurves prims, expected 1", file=sys.stderr)
        return 1
    curves = UsdGeom.BasisCurves(prims[0])
    if curves.GetTypeAttr().Get() != UsdGeom.Tokens.linear:
        errors.append(f"curve type is {curves.GetTypeAttr().Get()}, not linear")
    counts, times, total, (lo, hi) = check_samples(curves, start, end, args, errors)
    widths, colors = check_look(curves, total, errors)
    print(f"{args.file}: BasisCurves {prims[0].GetPath()}, {len(counts)} curves, "
          f"{min(counts)} to {max(counts)} points each, {total} points a sample")
    print(f"time codes {start:g} to {end:g} at {per_second:g} a second: {len(times)} samples, "
          f"{(end - start) / per_second:.3f} s")
    print(f"bounds over every sample (m): {fmt(lo)} to {fmt(hi)}")
    if widths:
        print(f"widths {min(widths) * 1e3:.4f} to {max(widths) * 1e3:.4f} mm; "
              f"display colours: {'none' if colors is None else len(colors)}")
    for e in errors:
        print(f"{args.file}: {e}", file=sys.stderr)
    print("ok" if not errors else f"{len(errors)} mismatches")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
