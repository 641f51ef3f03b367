"""cyHair `.hair` reading (the layout in ../shared/data/README.md) and conversion of its
polylines to Mitsuba 3 `bsplinecurve` control points.

A polyline segment A->B is exactly straight as a uniform cubic B-spline with control points
A-d, A, B, B+d (d = B - A): the curve starts at (P0 + 4 P1 + P2)/6 = A and ends at
(P1 + 4 P2 + P3)/6 = B, and equally spaced collinear control points trace the line at uniform
speed. The fibre tangent then runs root to tip (../shared/reference/README.md). Each segment is
its own curve, so no smoothing changes the geometry wisp drew.
"""

import hashlib
import os
import struct

import numpy as np

HEADER_BYTES = 128


def read_hair(path):
    """Returns (segments[int], points[N,3] float32, thickness[N] float32)."""
    data = open(path, "rb").read()
    if len(data) < HEADER_BYTES or data[:4] != b"HAIR":
        raise ValueError(f"{path}: not a cyHair file")
    hair_count, point_count, arrays, d_segments = struct.unpack_from("<4I", data, 4)
    (d_thickness,) = struct.unpack_from("<f", data, 20)
    if not arrays & 2:
        raise ValueError(f"{path}: no points array")
    at = HEADER_BYTES
    if arrays & 1:
        segments = np.frombuffer(data, "<u2", hair_count, at).astype(np.int64)
        at += 2 * hair_count
    else:
        segments = np.full(hair_count, d_segments, np.int64)
    if int((segments + 1).sum()) != point_count:
        raise ValueError(f"{path}: segment counts do not add up to {point_count} points")
    points = np.frombuffer(data, "<f4", 3 * point_count, at).reshape(-1, 3)
    at += 12 * point_count
    if arrays & 4:
        thickness = np.frombuffer(data, "<f4", point_count, at)
    else:
        thickness = np.full(point_count, d_thickness, np.float32)
    return segments, points, thickness


def segment_control_points(segments, points, thickness):
    """Per polyline segment, the 4 control points (x, y, z, radius): array [S, 4, 4]."""
    starts = np.concatenate([[0], np.cumsum(segments + 1)[:-1]])
    # Index of every segment's first point: all points but each strand's last.
    idx = np.concatenate([s + np.arange(n) for s, n in zip(starts, segments)])
    a, b = points[idx].astype(np.float64), points[idx + 1].astype(np.float64)
    d = b - a
    radius = 0.5 * (thickness[idx].astype(np.float64) + thickness[idx + 1]) / 2.0
    cp = np.stack([a - d, a, b, b + d], axis=1)
    r = np.repeat(radius[:, None, None], 4, axis=1)
    return np.concatenate([cp, r], axis=2)


def curve_file(hair_path, cache_dir):
    """Writes (once per distinct .hair content) Mitsuba's text curve file — one control point
    `x y z radius` per line, a blank line between curves — and returns its path."""
    digest = hashlib.sha1(open(hair_path, "rb").read()).hexdigest()[:16]
    os.makedirs(cache_dir, exist_ok=True)
    out = os.path.join(cache_dir, f"curves_{digest}.txt")
    if os.path.exists(out):
        return out
    cp = segment_control_points(*read_hair(hair_path))
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        # 4 control-point lines then one empty line per curve.
        fmt = "%.9g %.9g %.9g %.9g\n" * 4 + "\n"
        chunk = 20000
        for i in range(0, len(cp), chunk):
            block = cp[i : i + chunk].reshape(-1, 16)
            f.write("".join(fmt % tuple(row) for row in block))
    os.replace(tmp, out)
    return out


def pieces_of(fine_path, coarse_path, tol_m=2e-6):
    """How many pieces each segment of `coarse_path`'s strands is cut into in `fine_path`
    (`wisp export --segment-pieces K` writes the same straight segments with K - 1 points added
    evenly along each): 1 if the files hold the same points, K if the fine file is the coarse
    one cut into K pieces (every K-th point the same, the others on their segment within
    `tol_m`), None if the two are other hair. The drawn geometry is then the same, so a path
    tracer's render of either compares with a wisp image of the other."""
    cs, cp, _ = read_hair(coarse_path)
    fs, fp, _ = read_hair(fine_path)
    if len(cs) != len(fs) or not np.all(cs > 0) or np.any(fs % cs):
        return None
    k = fs // cs
    if not np.all(k == k[0]):
        return None
    k = int(k[0])
    kept = np.concatenate([np.arange(c + 1) * k + s for c, s in
                           zip(cs, np.concatenate([[0], np.cumsum(fs + 1)[:-1]]))])
    if not np.array_equal(fp[kept], cp):
        return None
    # Every point on the chord of its coarse segment, at j / k of the way.
    starts = np.concatenate([[0], np.cumsum(fs + 1)[:-1]])
    for s, n in zip(starts, fs):
        strand = fp[s:s + n + 1].astype(np.float64)
        a = strand[:-1:k][:, None, :]
        b = strand[k::k][:, None, :]
        t = (np.arange(k) / k)[None, :, None]
        want = (a + (b - a) * t).reshape(-1, 3)
        if np.max(np.abs(strand[:-1] - want)) > tol_m:
            return None
    return k


class Strands:
    """The .hair polylines: every segment's first point, and each point's strand ends."""

    def __init__(self, path):
        segs, pts, _ = read_hair(path)
        starts = np.concatenate([[0], np.cumsum(segs + 1)[:-1]])
        self.points = pts.astype(np.float64)
        self.seg_first = np.concatenate([s + np.arange(n) for s, n in zip(starts, segs)])
        strand = np.repeat(np.arange(len(segs)), segs + 1)
        self.first = starts[strand]
        self.last = (starts + segs)[strand]
