#!/usr/bin/env python3
"""Path-traced reference of a `wisp export` scene with Mitsuba 3 (not run by CI).

    render.py SCENE_DIR [--spp 64] [--passes 4] [--depth 64 2] [--variant llvm_ad_rgb]
              [--integrator fibre|path|fibre-mitsuba-offset] [--ray-offset-m 1e-6]

Reads SCENE_DIR/scene.json and its .hair file, builds the same scene for Mitsuba 3.9.1 — the
render strands as `bsplinecurve` fibres (one per polyline segment, exactly straight, radius
from the .hair thickness), the `hair` BSDF with the parameters wisp mapped in
`scene.json:mitsuba_hair_bsdf` (../shared/reference/MAPPING.md), the scene's one light (a
`directional` emitter with its irradiance, or a `point` emitter with its position and
intensity), a `perspective` sensor with `fov_axis = "y"` and a box pixel filter,
a black background — and renders it for each `max_depth` (2 = single scattering with hard
shadows, 64 = all orders) in `passes` independent passes of spp/passes samples (seeds 0, 1,
..., or from --first-seed on: passes to add to a finished render). The integrator is `fibre_trace.py`'s by default (`fibre`): Mitsuba's path tracing with rays
leaving a fibre from its surface instead of Mitsuba's offset of about 0.1 mm, which at 40 µm
fibres starts every shadow ray past the fibres touching it (ACCURACY.md section 2, "The path
tracer's ray offset"); `--integrator path` is Mitsuba's own `path` integrator, as the tables
before 2026-12-06 were rendered, and `--integrator fibre-mitsuba-offset` is fibre_trace.py
starting its rays where Mitsuba does (it reproduces `path` within the noise: the check that
the two differ only by the offset). Writes, per depth D:

    SCENE_DIR/mitsuba_dD.exr         mean of the passes, linear RGBA (alpha = coverage)
    SCENE_DIR/mitsuba_dD_passes.npy  the passes, float32 [passes, H, W, 4] (standard errors)
    SCENE_DIR/mitsuba_dD.json        spp, passes, seconds (wall, and CPU over all threads),
                                     variant, version, integrator

Set DRJIT_LIBLLVM_PATH for the llvm variants (see tools/reference/README.md).
"""

import argparse
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hairfile  # noqa: E402
import fibre_trace  # noqa: E402


def emitter(light):
    """scene.json's light as a Mitsuba emitter: `directional` with its irradiance, or `point`
    with its radiant intensity (W/sr in wisp's units; Mitsuba's `point` emitter gives I / d²
    on a surface facing it at distance d, as wisp does)."""
    if "position_m" in light:
        return {"type": "point", "position": light["position_m"],
                "intensity": {"type": "rgb", "value": light["intensity"]}}
    return {"type": "directional", "direction": light["direction"],
            "irradiance": {"type": "rgb", "value": light["irradiance"]}}


def build_scene(mi, scene, curves_path, spp_per_pass, max_depth):
    cam = scene["camera"]
    light = scene["light"]
    bsdf = dict(scene["mitsuba_hair_bsdf"])
    bsdf["sigma_a"] = {"type": "rgb", "value": bsdf["sigma_a"]}
    return mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "path", "max_depth": max_depth},
            "sensor": {
                "type": "perspective",
                "fov": cam["fov_y_deg"],
                "fov_axis": "y",
                "near_clip": 1e-3,
                "to_world": mi.ScalarTransform4f().look_at(
                    origin=cam["eye"], target=cam["target"], up=cam["up"]
                ),
                "film": {
                    "type": "hdrfilm",
                    "width": scene["image"]["width"],
                    "height": scene["image"]["height"],
                    "rfilter": {"type": "box"},
                    "pixel_format": "rgba",
                },
                "sampler": {"type": "independent", "sample_count": spp_per_pass},
            },
            "light": emitter(light),
            "hair": {"type": "bsplinecurve", "filename": curves_path, "bsdf": bsdf},
        }
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene_dir")
    ap.add_argument("--spp", type=int, default=64, help="samples per pixel in all passes")
    ap.add_argument("--passes", type=int, default=4, help="independent passes (>= 2 for errors)")
    ap.add_argument("--depth", type=int, nargs="+", default=[64, 2], help="max_depth values")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--integrator", choices=["fibre", "path", "fibre-mitsuba-offset"],
                    default="fibre",
                    help="fibre: fibre_trace.py, rays leave a fibre from its surface (default); "
                    "path: Mitsuba's own path integrator and ray offset; fibre-mitsuba-offset: "
                    "fibre_trace.py starting rays where Mitsuba does (checks that the two "
                    "integrators agree but for the offset)")
    ap.add_argument("--ray-offset-m", type=float, default=1e-6,
                    help="fibre integrator: how far off the fibre's surface a ray starts, metres")
    ap.add_argument("--cache", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "wisp-reference-cache"),
                    help="where converted curve files are kept (keyed by the .hair content)")
    ap.add_argument("--first-seed", type=int, default=0,
                    help="seed of the first pass (passes use seeds FIRST..FIRST+PASSES-1): more "
                         "samples for a finished render, independent of its passes")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant(args.variant)
    scene = json.load(open(os.path.join(args.scene_dir, "scene.json")))
    if scene.get("fibers_per_strand", 1) != 1:
        print(f"render.py: warning: wisp's strands stand for {scene['fibers_per_strand']} fibres "
              "each; Mitsuba draws one fibre per strand, so the two images show different hair",
              file=sys.stderr)
    if scene.get("draw_solids", False):
        print("render.py: warning: wisp drew the head and body; this scene has hair only",
              file=sys.stderr)
    if any(scene.get("ambient", [0, 0, 0])):
        print("render.py: warning: wisp has an ambient term; this scene has none", file=sys.stderr)
    t0 = time.time()
    curves = hairfile.curve_file(os.path.join(args.scene_dir, scene["hair_file"]), args.cache)
    convert_s = time.time() - t0
    per_pass = max(1, args.spp // args.passes)
    strands = None
    if args.integrator != "path":
        strands = hairfile.Strands(os.path.join(args.scene_dir, scene["hair_file"]))
    for depth in args.depth:
        t0 = time.time()
        mscene = build_scene(mi, scene, curves, per_pass, depth)
        load_s = time.time() - t0
        passes = []
        t0, cpu0 = time.time(), time.process_time()
        for seed in range(args.first_seed, args.first_seed + args.passes):
            if strands is None:
                img = np.array(mi.render(mscene, seed=seed, spp=per_pass))
            else:
                spawn = "mitsuba" if args.integrator == "fibre-mitsuba-offset" else "fibre"
                img = fibre_trace.render(mi, mscene, scene, strands, per_pass, seed, depth,
                                         spawn, args.ray_offset_m)
            passes.append(np.asarray(img, dtype=np.float32))
        render_s, render_cpu_s = time.time() - t0, time.process_time() - cpu0
        stack = np.stack(passes)
        mean = stack.mean(axis=0)
        base = os.path.join(args.scene_dir, f"mitsuba_d{depth}")
        mi.Bitmap(mean, mi.Bitmap.PixelFormat.RGBA).write(base + ".exr")
        np.save(base + "_passes.npy", stack)
        info = {
            "max_depth": depth,
            "spp": per_pass * args.passes,
            "passes": args.passes,
            "first_seed": args.first_seed,
            "render_s": render_s,
            "render_cpu_s": render_cpu_s,
            "load_s": load_s,
            "curve_convert_s": convert_s,
            "variant": args.variant,
            "integrator": args.integrator,
            "ray_offset_m": args.ray_offset_m if args.integrator == "fibre" else "mitsuba",
            "mitsuba": mi.__version__,
        }
        json.dump(info, open(base + ".json", "w"), indent=1)
        print(f"render.py: {args.scene_dir} max_depth {depth}: {per_pass * args.passes} spp in "
              f"{args.passes} passes, {render_s:.1f} s (+ {load_s:.1f} s load)", file=sys.stderr)


if __name__ == "__main__":
    main()
