#!/usr/bin/env python3
"""Is wisp's per-vertex light the exact light at its point? (not run by CI)

    axis_check.py CASE_DIR VIS_DIR [--vertices 400] [--seed 3] [--axis]

CASE_DIR is a case `run_table.py` rendered (scene.json, the .hair file); VIS_DIR a
`wisp export --shading visibility` of the same strands and camera with contact shadows on
(`--contact-mm 120`, as the tables take them; one fibre per strand). Among the vertices of the segments the camera's rays hit, it
draws `--vertices` at random and, for each, compares three lights (direct, lit or not):

    wisp        the export's per-vertex value (vertex_rgb.f32), lit when above 1/2;
    brute       a ray from the vertex's point toward the light against every segment of
                every strand as wisp's contact shadows take them: in the plane across the
                light, closer than the fibre radius to the segment's axis at a parameter in
                [0, 1), in front of the point; the vertex's own strand's segments k-2..k+1
                do not count;
    Mitsuba     a shadow ray from the same point, started where it leaves the fibre's own
                cylinder, against the path tracer's curves.

The point is the vertex's on the fibre's lit side, where wisp reads contact light since stop 44
(the axis point moved by r toward the light across the fibre, the tangent the chord between the
vertex's neighbours); `--axis` takes the axis point, as wisp did before.

and prints the three means and every disagreement. Agreement says wisp computes its own
definition exactly; what is left against the path tracer is the definition (one ray from one
point; the path tracer lights the fibre's surface), ACCURACY.md section 2, "Converged strands".
"""

import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hairfile  # noqa: E402
from render import build_scene  # noqa: E402
from hairfile import Strands  # noqa: E402
from visibility import camera_hits, seen_segment, unit  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case_dir")
    ap.add_argument("vis_dir")
    ap.add_argument("--vertices", type=int, default=400)
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--axis", action="store_true", help="rays from the axis point (wisp before stop 44)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--cache", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "wisp-reference-cache"))
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    scene = json.load(open(os.path.join(args.case_dir, "scene.json")))
    hair = os.path.join(args.case_dir, scene["hair_file"])
    segments, points, _ = hairfile.read_hair(hair)
    if len(set(segments.tolist())) != 1:
        sys.exit(f"axis_check.py: {hair}: strands of different lengths are not supported")
    n = int(segments[0]) + 1
    pts = points.astype(np.float64)
    vertex_v = np.fromfile(os.path.join(args.vis_dir, "vertex_rgb.f32"), "<f4").reshape(-1, 3)[:, 0]
    if len(vertex_v) != len(pts):
        sys.exit(f"axis_check.py: {args.vis_dir}/vertex_rgb.f32: {len(vertex_v)} points, "
                 f"the .hair has {len(pts)}")
    vertex_v = vertex_v.astype(np.float64) / float(scene["light"]["irradiance"][0])
    mscene = build_scene(mi, scene, hairfile.curve_file(hair, args.cache), 4, 2)
    r = scene["fiber_radius_m"]
    to_light = -unit(np.array(scene["light"]["direction"], np.float64))

    # The light's frame: depth along the light, (y, z) across it.
    helper = [0.0, 1.0, 0.0] if abs(to_light[1]) < 0.9 else [1.0, 0.0, 0.0]
    e1 = unit(np.cross(to_light, helper))
    e2 = np.cross(to_light, e1)
    depth, y, z = pts @ to_light, pts @ e1, pts @ e2
    strands = len(pts) // n
    a_idx = np.arange(len(pts)).reshape(strands, n)[:, :-1].ravel()
    b_idx = a_idx + 1
    strand_of, seg_of = a_idx // n, a_idx % n

    # Vertices of the segments the camera sees.
    polylines = Strands(hair)
    _, si, hit_np, _, _ = camera_hits(mi, dr, mscene, scene, polylines, 4, 0)
    k, u, _, _ = seen_segment(polylines, si, hit_np)
    seen = np.unique(np.where(u < 0.5, k, k + 1)[hit_np])
    rng = np.random.default_rng(args.seed)
    pick = rng.choice(seen, min(args.vertices, len(seen)), replace=False)

    first = (pick // n) * n
    tangent = unit(pts[np.minimum(pick + 1, first + n - 1)] - pts[np.maximum(pick - 1, first)])
    cos_t = tangent @ to_light
    sin_t = np.sqrt(np.maximum(1.0 - cos_t**2, 1e-6))
    if args.axis:
        origin = pts[pick]
    else:
        # The lit side: r along the part of the direction to the light across the fibre.
        across = to_light[None, :] - tangent * cos_t[:, None]
        across /= np.maximum(np.linalg.norm(across, axis=1), 1e-12)[:, None]
        origin = pts[pick] + r * across
    oy, oz, od = origin @ e1, origin @ e2, origin @ to_light

    dy, dz = y[b_idx] - y[a_idx], z[b_idx] - z[a_idx]
    len2 = dy * dy + dz * dz + 1e-30
    brute = np.empty(len(pick), bool)
    for i, v in enumerate(pick):
        t = ((oy[i] - y[a_idx]) * dy + (oz[i] - z[a_idx]) * dz) / len2
        across = np.abs((oy[i] - y[a_idx]) * dz - (oz[i] - z[a_idx]) * dy) / np.sqrt(len2)
        ahead = depth[a_idx] + (depth[b_idx] - depth[a_idx]) * t - od[i]
        own = (strand_of == v // n) & (seg_of >= v % n - 2) & (seg_of <= v % n + 1)
        brute[i] = not ((t >= 0) & (t < 1) & (across < r) & (ahead > 0) & ~own).any()

    # From the axis the ray leaves the fibre's own cylinder after r / sin of the light's angle
    # to the fibre; from the lit side at once (+2% and 1 µm keep it off the surface).
    leave = (r / sin_t * 1.02 + 1e-6) if args.axis else np.full(len(pick), 0.02 * r + 1e-6)
    o = (origin + to_light * leave[:, None]).astype(np.float32)
    ray = mi.Ray3f(mi.Point3f(o[:, 0], o[:, 1], o[:, 2]), mi.Vector3f(*(float(x) for x in to_light)))
    mitsuba = ~np.array(mscene.ray_test(ray, dr.ones(mi.Bool, len(pick))), bool)

    wisp = vertex_v[pick] > 0.5
    print(f"{len(pick)} seen vertices: lit by wisp {wisp.mean():.3f}, by brute force "
          f"{brute.mean():.3f}, by Mitsuba {mitsuba.mean():.3f}")
    print(f"disagreements: wisp vs brute force {(wisp != brute).sum()}, "
          f"brute force vs Mitsuba {(brute != mitsuba).sum()}")
    for i in np.nonzero((wisp != brute) | (brute != mitsuba))[0][:10]:
        v = pick[i]
        print(f"  vertex {v} (strand {v // n}, point {v % n}): wisp {vertex_v[v]:.3f}, "
              f"brute force {int(brute[i])}, Mitsuba {int(mitsuba[i])}")


if __name__ == "__main__":
    main()
