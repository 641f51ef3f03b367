#!/usr/bin/env python3
"""Stack path-traced renders of one scene made with different seeds into one longer render
(not run by CI). A darkest tenth that a 128-spp table leaves undecided needs more samples than
one sitting renders; render.py writes each run's passes, and this adds them up.

usage: stack.py OUT_SCENE_DIR SCENE_DIR [SCENE_DIR ...] [--depth 64]

Each SCENE_DIR holds mitsuba_dD_passes.npy and mitsuba_dD.json from render.py, all of the same
scene (the same scene.json and hair file: checked) and with seeds that do not overlap (checked:
first_seed .. first_seed + passes). OUT_SCENE_DIR gets the scene's files (copied from the
first), the mean of every pass as mitsuba_dD.exr, the passes stacked as
mitsuba_dD_passes.npy (so compare.py's standard errors count them all) and a json whose spp,
render_s and render_cpu_s are the sums. Example, dense brown back-lit at 1,664 spp (ACCURACY.md §2):

    render.py /tmp/bb --spp 1024 --passes 64 --depth 64 --first-seed 40
    stack.py /tmp/bb1664 TABLE/dense/brown-back-dual /tmp/bb256a /tmp/bb256b /tmp/bb
"""
import argparse
import filecmp
import json
import os
import shutil
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--depth", type=int, default=64)
    args = ap.parse_args()
    import numpy as np
    import mitsuba as mi
    mi.set_variant("scalar_rgb")

    base = f"mitsuba_d{args.depth}"
    first = args.dirs[0]
    stacks, infos, seeds = [], [], set()
    for d in args.dirs:
        for name in ("scene.json", "hair.hair"):
            if not filecmp.cmp(os.path.join(first, name), os.path.join(d, name), shallow=False):
                sys.exit(f"stack.py: {d}/{name} differs from {first}/{name}: not one scene")
        info = json.load(open(os.path.join(d, base + ".json")))
        mine = set(range(info["first_seed"], info["first_seed"] + info["passes"]))
        if info.get("seeds"):
            mine = set(info["seeds"])
        if seeds & mine:
            sys.exit(f"stack.py: {d} repeats seeds {sorted(seeds & mine)[:5]}...: "
                     "its passes would count twice")
        seeds |= mine
        stack = np.load(os.path.join(d, base + "_passes.npy"))
        if stacks and stack.shape[1:] != stacks[0].shape[1:]:
            sys.exit(f"stack.py: {d}'s passes are {stack.shape[1:]}, not {stacks[0].shape[1:]}")
        stacks.append(stack)
        infos.append(info)
    stack = np.concatenate(stacks)
    os.makedirs(args.out, exist_ok=True)
    for name in os.listdir(first):
        if not name.startswith("mitsuba_") and not name.startswith("compare"):
            src = os.path.join(first, name)
            if os.path.isfile(src):
                shutil.copy(src, os.path.join(args.out, name))
    mi.Bitmap(stack.mean(axis=0), mi.Bitmap.PixelFormat.RGBA).write(
        os.path.join(args.out, base + ".exr"))
    np.save(os.path.join(args.out, base + "_passes.npy"), stack)
    info = dict(infos[0])
    info.update({
        "spp": sum(i["spp"] for i in infos),
        "passes": int(stack.shape[0]),
        "render_s": sum(i["render_s"] for i in infos),
        "render_cpu_s": (sum(i["render_cpu_s"] for i in infos)
                         if all("render_cpu_s" in i for i in infos) else None),
        "seeds": sorted(seeds),
        "stacked_from": [os.path.abspath(d) for d in args.dirs],
    })
    json.dump(info, open(os.path.join(args.out, base + ".json"), "w"), indent=1)
    print(f"stack.py: {args.out}: {info['spp']} spp in {info['passes']} passes "
          f"({info['render_s']:.0f} s of rendering)", file=sys.stderr)


if __name__ == "__main__":
    main()
