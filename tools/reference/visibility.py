#!/usr/bin/env python3
"""Where the light reaches the hair the camera sees, path traced (not run by CI).

    visibility.py SCENE_DIR [--spp 64] [--passes 4] [--decompose [--kernel point|piece]]
                  [--variant llvm_ad_rgb]

Single scattering is the fibre's BCSDF times the share of the seen fibre that the light reaches
through no fibre. This script measures that share alone, with no fibre model: camera rays
through each pixel's area (box filter, as render.py) hit the first fibre, and a shadow ray
toward the directional light is tested from the hit as `fibre_trace.py` tests it: leaving the
fibre from its surface (Mitsuba's own test, `sample_emitter_direction(..., test_visibility=True)`,
starts it 0.1 mm off, past the fibres touching this one, and read 5% more light side-lit
until 2026-12-06). Writes

    SCENE_DIR/visibility.exr         R = G = B = irradiance x mean visibility over the pixel's
                                     area, A = coverage
    SCENE_DIR/visibility_passes.npy  the passes, float32 [passes, H, W, 4]

Compare it with the EXR of `wisp export --shading visibility` (the shadows alone) with
compare.py. `--decompose` (SCENE_DIR must be such an export: it reads its vertex_rgb.f32 and
wisp.exr) splits wisp / path traced, over pixels covered >= 0.99, into three factors:

    along the fibre  exact shadow rays from the seen fibres, but taken as wisp takes light
                     along a fibre (`--kernel point`, contact shadows since 2026-12-05: at
                     the points, then linear between them; `--kernel piece`, before: each
                     point's piece, half a segment to each side, then linear), against the
                     seen point's own
    the light        wisp's per-point values on the fibres the path tracer sees, against
                     the exact rays averaged the same way (the map and contact shadows)
    the raster       wisp's image, against its per-point values on the fibres the path
                     tracer sees (which fibres wisp's compositing shows)
"""

import argparse
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fibre_trace  # noqa: E402
from fibre_trace import unit  # noqa: E402
import hairfile  # noqa: E402
from hairfile import Strands  # noqa: E402
from render import build_scene  # noqa: E402


def camera_hits(mi, dr, mscene, scene, strands, spp, seed):
    """`spp` camera rays through each pixel's area (box filter, as render.py), in pixel order,
    their first hits, an emitter sample at each and whether the light reaches it: a shadow ray
    leaving the fibre from its surface (fibre_trace.py; Mitsuba's own ray offset of about
    0.1 mm starts it past the fibres touching this one). Returns (ray, si, hit, ds, lit), hit
    and lit as numpy bool arrays."""
    w, h = scene["image"]["width"], scene["image"]["height"]
    n = w * h * spp
    sampler = mi.load_dict({"type": "independent"})
    sampler.seed(seed, n)
    pixel = dr.arange(mi.UInt32, n) // spp
    pos = mi.Point2f((mi.Float(pixel % w) + sampler.next_1d()) / w,
                     (mi.Float(pixel // w) + sampler.next_1d()) / h)
    ray, _ = mscene.sensors()[0].sample_ray(0.0, 0.0, pos, mi.Point2f(0.5, 0.5))
    si = mscene.ray_intersect(ray)
    hit = si.is_valid()
    ds, _ = mscene.sample_emitter_direction(si, sampler.next_2d(), False, hit)
    hit = np.array(hit, bool)
    lit = fibre_trace.lit_at_hits(mi, mscene, fibre_trace.Fibres(strands), si, hit, ds.d)
    return ray, si, hit, ds, lit


def seen_segment(strands, si, hit_np):
    """The polyline segment of each hit (render.py writes one curve per segment, in order) and
    where along it, from the hit point projected on its axis: (k, u, a, d) with a the
    segment's first point and d its vector."""
    prim = np.where(hit_np, np.array(si.prim_index, np.int64), 0)
    k = strands.seg_first[prim]
    a, b = strands.points[k], strands.points[k + 1]
    d = b - a
    p = np.array(si.p, np.float64).T
    u = np.clip(((p - a) * d).sum(1) / np.maximum((d * d).sum(1), 1e-30), 0.0, 1.0)
    return k, u, a, d


def lit_from_surface(mi, mscene, scene, q, tangent, active, rng):
    """Whether the light reaches the fibres through points `q` on their axes (unit `tangent`
    each) past every other fibre: a shadow ray from a point across the fibre's width as the
    light sees it (uniform, from `rng`), started on the fibre's lit surface."""
    to_light = -unit(np.array(scene["light"]["direction"], np.float64))
    across = unit(np.cross(to_light, tangent))
    lit_side = unit(to_light - (tangent @ to_light)[:, None] * tangent)
    r = scene["fiber_radius_m"]
    off = (2.0 * rng.random(len(q)) - 1.0) * r
    o = (q + off[:, None] * across
         + lit_side * (np.sqrt(np.maximum(r * r - off * off, 0.0)) * 1.02 + 1e-6)[:, None])
    o = o.astype(np.float32)
    shadow = mi.Ray3f(mi.Point3f(o[:, 0], o[:, 1], o[:, 2]),
                      mi.Vector3f(*(float(x) for x in to_light)))
    return ~np.array(mscene.ray_test(shadow, active), bool)


def one_pass(mi, dr, mscene, scene, strands, vertex_value, spp, seed, decompose, kernel="point"):
    """Per pixel: [seen-and-lit, coverage] and, with `decompose`, [exact light averaged as
    wisp averages it, wisp's point values on the seen fibres]."""
    w, h = scene["image"]["width"], scene["image"]["height"]
    n = w * h * spp
    _, si, hit_np, _, lit = camera_hits(mi, dr, mscene, scene, strands, spp, seed)
    hit = mi.Bool(hit_np)
    per_pixel = lambda x: np.asarray(x, np.float64).reshape(h, w, spp).mean(axis=2)
    out = [per_pixel(lit), per_pixel(hit_np)]
    if not decompose:
        return out
    rng = np.random.default_rng(1000 + seed)
    k, u, _, _ = seen_segment(strands, si, hit_np)
    # wisp's colour there: linear between the segment's two points.
    wisp_here = (1.0 - u) * vertex_value[k] + u * vertex_value[k + 1]
    # Exact light with wisp's averaging: point k or k+1 (weights 1-u, u), then that point
    # (`point`) or a point uniformly on its piece (`piece`: half a segment to one side or the
    # other), a ray from a point
    # across the fibre's width as the light sees it, started on the fibre's lit surface.
    v = k + (rng.random(n) < u)
    toward_prev = rng.random(n) < 0.5
    other = np.where(toward_prev, v - 1, v + 1)
    ok = np.where(toward_prev, v > strands.first[v], v < strands.last[v])
    other = np.where(ok, other, v)
    reach = 0.5 * rng.random(n) if kernel == "piece" else np.zeros(n)
    q = strands.points[v] + reach[:, None] * (strands.points[other] - strands.points[v])
    tangent = unit(strands.points[np.minimum(v + 1, strands.last[v])]
                   - strands.points[np.maximum(v - 1, strands.first[v])])
    out.append(per_pixel(hit_np & lit_from_surface(mi, mscene, scene, q, tangent, hit, rng)))
    out.append(per_pixel(np.where(hit_np, wisp_here, 0.0)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene_dir")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--passes", type=int, default=4)
    ap.add_argument("--decompose", action="store_true",
                    help="split wisp / path traced into along-the-fibre, light and raster factors")
    ap.add_argument("--kernel", choices=["point", "piece"], default="point",
                    help="how wisp's point values stand for the light along a fibre (--decompose)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--cache", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "wisp-reference-cache"))
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    d = args.scene_dir
    scene = json.load(open(os.path.join(d, "scene.json")))
    irradiance = float(scene["light"]["irradiance"][0])
    hair_path = os.path.join(d, scene["hair_file"])
    curves = hairfile.curve_file(hair_path, args.cache)
    # The polylines: where each hit's fibre lies, for the shadow ray leaving it.
    strands = Strands(hair_path)
    vertex_value = None
    if args.decompose:
        if scene.get("shading") != "Visibility":
            sys.exit(f"visibility.py: {d}/scene.json: --decompose needs an export made with "
                     f"--shading visibility (this one is {scene.get('shading')!r})")
        rgb = np.fromfile(os.path.join(d, "vertex_rgb.f32"), "<f4").reshape(-1, 3)
        if len(rgb) != len(strands.points):
            sys.exit(f"visibility.py: {d}/vertex_rgb.f32: {len(rgb)} points, "
                     f"{scene['hair_file']} has {len(strands.points)}")
        vertex_value = rgb[:, 0].astype(np.float64) / irradiance
    per_pass = max(1, args.spp // args.passes)
    mscene = build_scene(mi, scene, curves, per_pass, 2)
    t0 = time.time()
    passes = [one_pass(mi, dr, mscene, scene, strands, vertex_value, per_pass, s, args.decompose,
                       args.kernel)
              for s in range(args.passes)]
    seconds = time.time() - t0
    stack = np.stack([np.stack([irradiance * p[0]] * 3 + [p[1]], axis=-1) for p in passes])
    stack = stack.astype(np.float32)
    mean = stack.mean(axis=0)
    base = os.path.join(d, "visibility")
    mi.Bitmap(mean, mi.Bitmap.PixelFormat.RGBA).write(base + ".exr")
    np.save(base + "_passes.npy", stack)
    covered = mean[..., 3] > 0.99
    seen = np.mean([p[0][covered].mean() for p in passes])
    print(f"visibility.py: {d}: {per_pass * args.passes} rays per pixel in {seconds:.1f} s; "
          f"mean visibility over {covered.sum()} covered pixels {seen:.4f}", file=sys.stderr)
    if args.decompose:
        wisp = np.array(mi.Bitmap(os.path.join(d, scene["wisp_image"])), np.float64)
        both = covered & (wisp[..., 3] > 0.99)
        pt = np.mean([p[0][both].mean() for p in passes])
        kernel = np.mean([p[2][both].mean() for p in passes])
        values = np.mean([p[3][both].mean() for p in passes])
        image = wisp[..., 0][both].mean() / irradiance
        print(f"| pixels covered in both | wisp ÷ path traced | along the fibre | the light | the raster |\n"
              f"|---|---|---|---|---|\n"
              f"| {both.sum()} | {image / pt:.3f} | {kernel / pt:.3f} | {values / kernel:.3f} | "
              f"{image / values:.3f} |")


if __name__ == "__main__":
    main()
