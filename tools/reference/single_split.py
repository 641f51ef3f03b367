#!/usr/bin/env python3
"""Where single scattering's error lies: the fibre model, the shadows, or their product (not run
by CI).

    single_split.py CASE_DIR VIS_DIR [--wisp-single DIR] [--spp 16] [--passes 2]
                    [--bands 0] [--variant llvm_ad_rgb]

CASE_DIR is a single-scattering case that `run_table.py` rendered (its scene.json carries the
Mitsuba `hair` BSDF, its mitsuba_d2.exr the path-traced single scattering). VIS_DIR is a
`wisp export --shading visibility` of the same strands and camera (`visibility.py` says how);
the two .hair files must be byte-identical (or VIS_DIR's the case's cut into pieces by
`--segment-pieces`, the same drawn hair).

Mitsuba's single scattering is the mean over a pixel's camera rays of f(h) V(x): the near-field
BSDF at the offset h where the ray meets the fibre, times the shadow ray from that surface
point x. wisp takes the far field (f averaged over h) times the light on the fibre's lit side, and
composites per-vertex products. Per pixel this script traces the same rays and reports, as
ratios to the path tracer's own sum of f(h) V(x) over pixels covered >= 0.99 in both:

    far field, exact light  f(h) times a shadow ray from a point across the fibre's lit side
                            (as wisp's exact reference takes it), independent of h: what a
                            far-field renderer with exact shadows would read. Below 1 where
                            the BSDF's share of h is lit more often than the fibre as a whole
                            (the lit surface facing the half vector reflects R side-lit).
    wisp's shadows          the path tracer's per-pixel mean of f times wisp's visibility
                            image: wisp's single scattering if its fibre model and its
                            compositing of products were exact.
    wisp, Mitsuba's fibres  wisp's per-vertex single scattering (vertex_rgb.f32, linear along
                            each segment) on the fibres the path tracer's camera rays hit:
                            wisp's image if its raster showed exactly the fibres seen.
    wisp's single           wisp's own single-scattering image.

The wisp single-scattering export is CASE_DIR's own, or a re-run by `rerun_case.py` passed as
`--wisp-single OUT/dense-brown-side-single` (same strands: checked).

`--bands N` prints the last two per band of N image rows as well: the error of the shadows is
spatial (too dark in one band, too bright in the next) even where their mean is right.

Then "wisp, Mitsuba's fibres" is split in two on the same hits, with wisp's per-vertex light
from VIS_DIR's vertex_rgb.f32 (V) and its fibre term as the single-scattering value over it
(f = single / V, where V > 0.001 at both ends of the hit's segment: "lit hits"):

    fibre term              wisp's f against the path tracer's f(h) at the lit hits, weighted
                            by wisp's light, and by the exact light (the shadow ray from the
                            lit side): 1 if wisp's far field, evaluated per vertex and linear
                            along each segment, were the path tracer's fibre.
    light                   wisp's V against the exact light, weighted by the path tracer's
                            f(h), over every hit: 1 if wisp's shadows were exact at the fibres
                            the camera sees.

The light is split once more, along the segment, with the exact light (the same shadow ray from
the lit side) also taken at each hit's two vertices:

    at the vertex           wisp's V at the hit's nearer vertex against the exact light there:
                            1 if wisp's per-vertex light were exact.
    along the segment       the exact vertex values interpolated linearly to the hit against
                            the exact light at the hit: 1 if linear interpolation between
                            vertices gave the light on the parts of the fibre the camera sees.
                            Not 1 where being seen and being lit are correlated along a
                            segment (back light: the seen parts face the camera, away from
                            the light); it shrinks as segments shorten.
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
from visibility import camera_hits, lit_from_surface, seen_segment, unit  # noqa: E402


# Columns of one_pass, three each but coverage.
COLUMNS = ["fv_hit", "fv_side", "f", "wisp", "cover", "f_vw", "fw_vside_lit", "f_vside_lit",
           "fw_vw_lit", "f_vw_lit", "f_vw_near", "f_vside_near", "f_vside_lin"]


def one_pass(mi, dr, mscene, scene, strands, vertex_rgb, vertex_v, spp, seed):
    """Per pixel, the means over its camera rays of COLUMNS: f·V(hit), f·V(lit side), f,
    wisp's vertex values at the hit, coverage; then with wisp's vertex light V_w and fibre term
    f_w = value / V_w at the hit: f·V_w, and over the lit hits f_w·V(lit side), f·V(lit side),
    f_w·V_w, f·V_w; then f times wisp's V and the exact V at the hit's nearer vertex, and f
    times the exact vertex values interpolated linearly to the hit."""
    w, h = scene["image"]["width"], scene["image"]["height"]
    ray, si, hit_np, ds, lit = camera_hits(mi, dr, mscene, scene, strands, spp, seed)
    hit = mi.Bool(hit_np)
    f = si.bsdf(ray).eval(mi.BSDFContext(), si, si.to_local(ds.d), hit)
    f = np.where(hit_np[:, None], np.array(f, np.float64).T, 0.0)
    v_hit = lit.astype(np.float64)
    # The same cross-section of the fibre, a shadow ray from a point across its lit side
    # (uniform across the width as the light sees it), as visibility.py's exact reference.
    rng = np.random.default_rng(2000 + seed)
    k, u, a, d = seen_segment(strands, si, hit_np)
    t = unit(d)
    v_side = hit_np & lit_from_surface(mi, mscene, scene, a + u[:, None] * d, t, hit, rng)
    wisp_here = (1.0 - u)[:, None] * vertex_rgb[k] + u[:, None] * vertex_rgb[k + 1]
    wisp_here[~hit_np] = 0.0
    # wisp's light and fibre term at the hit, linear along the segment as its colour is.
    lit_vertex = vertex_v > 1e-3
    f_vertex = np.where(lit_vertex[:, None],
                        vertex_rgb / np.maximum(vertex_v, 1e-3)[:, None], 0.0)
    v_w = np.where(hit_np, (1.0 - u) * vertex_v[k] + u * vertex_v[k + 1], 0.0)
    lit = (hit_np & lit_vertex[k] & lit_vertex[k + 1])[:, None].astype(np.float64)
    f_w = ((1.0 - u)[:, None] * f_vertex[k] + u[:, None] * f_vertex[k + 1]) * lit
    side = v_side[:, None].astype(np.float64)
    # The light split along the segment: the exact light at its two vertices (the same
    # shadow ray from the lit side), wisp's and the exact at the nearer one, and the exact
    # vertex values interpolated linearly to the hit as wisp interpolates its own.
    e0 = hit_np & lit_from_surface(mi, mscene, scene, a, t, hit, rng)
    e1 = hit_np & lit_from_surface(mi, mscene, scene, a + d, t, hit, rng)
    near = u < 0.5
    v_near = np.where(hit_np, np.where(near, vertex_v[k], vertex_v[k + 1]), 0.0)
    e_near = np.where(near, e0, e1).astype(np.float64)
    e_lin = (1.0 - u) * e0 + u * e1
    cols = np.concatenate([f * v_hit[:, None], f * side, f, wisp_here,
                           hit_np[:, None].astype(np.float64),
                           f * v_w[:, None], f_w * side, f * side * lit,
                           f_w * v_w[:, None], f * v_w[:, None] * lit,
                           f * v_near[:, None], f * e_near[:, None],
                           f * e_lin[:, None]], axis=1)
    return cols.reshape(h, w, spp, cols.shape[1]).mean(axis=2)


def ratio(num, den):
    return " / ".join(f"{x:.3f}" for x in num / np.maximum(den, 1e-30))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case_dir")
    ap.add_argument("vis_dir")
    ap.add_argument("--wisp-single", help="a wisp single-scattering export of the same strands "
                    "(default CASE_DIR)")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--passes", type=int, default=2)
    ap.add_argument("--bands", type=int, default=0)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--cache", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "wisp-reference-cache"))
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    scene = json.load(open(os.path.join(args.case_dir, "scene.json")))
    vis_scene = json.load(open(os.path.join(args.vis_dir, "scene.json")))
    if vis_scene.get("shading") != "Visibility":
        sys.exit(f"single_split.py: {args.vis_dir}/scene.json: needs an export made with "
                 f"--shading visibility (this one is {vis_scene.get('shading')!r})")
    single_dir = args.wisp_single or args.case_dir
    single_scene = json.load(open(os.path.join(single_dir, "scene.json")))
    if single_scene.get("shading") != "SingleScattering":
        sys.exit(f"single_split.py: {single_dir}/scene.json: needs an export made with "
                 f"--shading single (this one is {single_scene.get('shading')!r})")
    hair = [os.path.join(x, s["hair_file"]) for x, s in
            ((args.case_dir, scene), (args.vis_dir, vis_scene), (single_dir, single_scene))]
    # wisp's exports may cut the case's segments into pieces (`--segment-pieces`): the same
    # drawn hair, whose points (and per-point values) are then the exports'.
    if hairfile.pieces_of(hair[1], hair[0]) is None:
        sys.exit(f"single_split.py: {hair[1]} differs from {hair[0]}: not the same strands")
    with open(hair[1], "rb") as x, open(hair[2], "rb") as y:
        if x.read() != y.read():
            sys.exit(f"single_split.py: {hair[2]} differs from {hair[1]}: not the same strands")
    hair = hair[1:]
    strands = Strands(hair[0])
    vertex_rgb = np.fromfile(os.path.join(single_dir, "vertex_rgb.f32"), "<f4").reshape(-1, 3)
    if len(vertex_rgb) != len(strands.points):
        sys.exit(f"single_split.py: {single_dir}/vertex_rgb.f32: {len(vertex_rgb)} points, "
                 f"the .hair has {len(strands.points)}")
    irradiance = float(scene["light"]["irradiance"][0])
    vertex_rgb = vertex_rgb.astype(np.float64) / irradiance
    vertex_v = np.fromfile(os.path.join(args.vis_dir, "vertex_rgb.f32"), "<f4").reshape(-1, 3)
    if len(vertex_v) != len(strands.points):
        sys.exit(f"single_split.py: {args.vis_dir}/vertex_rgb.f32: {len(vertex_v)} points, "
                 f"the .hair has {len(strands.points)}")
    vertex_v = vertex_v[:, 0].astype(np.float64) / irradiance
    curves = hairfile.curve_file(hair[0], args.cache)
    mscene = build_scene(mi, scene, curves, args.spp, 2)
    acc = np.mean([one_pass(mi, dr, mscene, scene, strands, vertex_rgb, vertex_v, args.spp, s)
                   for s in range(args.passes)], axis=0)
    col, at = {}, 0
    for name in COLUMNS:
        width = 1 if name == "cover" else 3
        col[name] = acc[..., at] if width == 1 else acc[..., at:at + width]
        at += width
    fv_hit, fv_side, f = col["fv_hit"], col["fv_side"], col["f"]
    seen, cover = col["wisp"] * irradiance, col["cover"]
    vis = np.array(mi.Bitmap(os.path.join(args.vis_dir, vis_scene["wisp_image"])), np.float64)
    single = np.array(mi.Bitmap(os.path.join(single_dir, single_scene["wisp_image"])), np.float64)
    both = (cover > 0.99) & (vis[..., 3] > 0.99) & (single[..., 3] > 0.99)
    pt = fv_hit[both].sum(0)
    shadows = f * (vis[..., :1] / irradiance)
    print(f"| pixels | far field, exact light | wisp's shadows | wisp, Mitsuba's fibres "
          f"| wisp's single |\n|---|---|---|---|---|\n"
          f"| {both.sum()} | {ratio(fv_side[both].sum(0), pt)} | {ratio(shadows[both].sum(0), pt)} "
          f"| {ratio(seen[both].sum(0) / irradiance, pt)} "
          f"| {ratio(single[both, :3].sum(0) / irradiance, pt)} |")
    total = lambda name: col[name][both].sum(0)
    print(f"\n| wisp, Mitsuba's fibres, split | R / G / B |\n|---|---|\n"
          f"| fibre term, under wisp's light (lit hits) | {ratio(total('fw_vw_lit'), total('f_vw_lit'))} |\n"
          f"| fibre term, under the exact light (lit hits) | {ratio(total('fw_vside_lit'), total('f_vside_lit'))} |\n"
          f"| light, under the path tracer's f (every hit) | {ratio(total('f_vw'), fv_side[both].sum(0))} |\n"
          f"| share of the exactly lit f(h) on lit hits | {ratio(total('f_vside_lit'), fv_side[both].sum(0))} |")
    print(f"\n| the light, split along the segment | R / G / B |\n|---|---|\n"
          f"| at the vertex: wisp's ÷ exact, at the nearer vertex of each hit | {ratio(total('f_vw_near'), total('f_vside_near'))} |\n"
          f"| along the segment: exact at the vertices, linear ÷ exact at the hit | {ratio(total('f_vside_lin'), fv_side[both].sum(0))} |")
    if args.bands > 0:
        print("\n| rows | pixels | share of the light | wisp's shadows | wisp, Mitsuba's fibres "
              "| wisp's single |\n|---|---|---|---|---|---|")
        h = both.shape[0]
        for y0 in range(0, h, args.bands):
            band = both.copy()
            band[:y0] = False
            band[y0 + args.bands:] = False
            if band.sum() < 50:
                continue
            ref = fv_hit[band].sum(0)
            print(f"| {y0}–{min(y0 + args.bands, h) - 1} | {band.sum()} | "
                  f"{ref.sum() / pt.sum():.3f} | {ratio(shadows[band].sum(0), ref)} | "
                  f"{ratio(seen[band].sum(0) / irradiance, ref)} | "
                  f"{ratio(single[band, :3].sum(0) / irradiance, ref)} |")


if __name__ == "__main__":
    main()
