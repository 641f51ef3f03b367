#!/usr/bin/env python3
"""A slab of parallel fibres against the path tracer: multiple scattering where the dense
scenes' geometry does not get in the way (not run by CI).

    slab.py [--out DIR] [--nbar 2,8] [--lights back,front] [--colour blond] [--fiber KEY=VALUE]
            [--tag TAG] [--size 400] [--spp 128] [--passes 8] [--wisp BIN] [--python PY]

The slab: vertical fibres of one fibre per strand, 80 mm wide (x) and 10 mm deep (z), at
uniformly random (seeded) positions of the cross-section, so a ray along z crosses NBAR
fibres on average (density NBAR / (2 r x 10 mm)). They hang from the underside of wisp's head
ellipsoid down to y = -0.2 m, so the groom import places them (`wisp export --hairstyle
slab.hair,style.json`); three short anchor strands at each side and at the top of the head
span its width and height, which makes the import's fit exactly scale 1 and no offset (the
anchors lie 0.1 m above the part of the slab in view and never meet the light that reaches
it). The camera looks along -z at the slab's centre (fov 10 degrees: only the slab's hanging
part); "back" light travels along +z (toward the camera, through the slab), "front" along -z,
"back45" and "front45" the same turned 45 degrees about the fibres (from the image's right).
No head, ambient 0, irradiance 1, the fibre of run_table.py's dense case of that colour.

Each case renders wisp's dual and single shading and Mitsuba's max_depth 64 and 2, and
compares the light sent from the central half of the image in each axis (compare.py --crop 0.5
--region all: a thin slab covers pixels only partly; light leaks around its side edges,
which are not what this measures). Besides the ratios of
run_table.py it reports "multi": wisp's dual - single over the path tracer's depth 64 - 2, the
multiply scattered light alone. Mitsuba renders are reused when present; --tag writes wisp's
renders beside them under another name (to compare an engine change or --fiber override with
the same references). Results: DIR/results.jsonl, DIR/table.md.
"""

import argparse
import json
import os
import struct
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import run_table as rt  # noqa: E402

WIDTH_M, DEPTH_M, BOTTOM_M, POINTS = 0.08, 0.01, -0.2, 31
LIGHTS = {"back": "0,0,1", "front": "0,0,-1", "back45": "-1,0,1", "front45": "-1,0,-1"}


def write_hair(path, strands, fibre_radius_m):
    """cyHair with one segment count for all strands and a points array (metres)."""
    pts = np.concatenate(strands).astype("<f4")
    header = b"HAIR" + struct.pack("<4I", len(strands), len(pts), 2, len(strands[0]) - 1)
    header += struct.pack("<5f", 2 * fibre_radius_m, 1.0, 0.5, 0.5, 0.5)
    open(path, "wb").write(header + b"\0" * (128 - len(header)) + pts.tobytes())


def slab_strands(nbar, style, seed=1):
    """The slab's strands plus 9 anchors under `style`'s head ellipsoid, for its fibre radius,
    their count a multiple of its wisps (so strands_per_wisp can make one fibre per strand)."""
    rx, ry, rz = style["head"]["radii_m"]
    wisps = style["wisps"]["count"]
    density = nbar / (2 * style["fiber"]["radius_m"] * DEPTH_M)
    n = int(round((density * WIDTH_M * DEPTH_M + 9) / wisps)) * wisps - 9
    rng = np.random.default_rng(seed)
    xs = rng.uniform(-WIDTH_M / 2, WIDTH_M / 2, n)
    zs = rng.uniform(-DEPTH_M / 2, DEPTH_M / 2, n)
    strands = []
    for x, z in zip(xs, zs):
        top = -ry * np.sqrt(max(1 - (x / rx) ** 2 - (z / rz) ** 2, 0.0)) - 1e-4
        y = np.linspace(top, BOTTOM_M, POINTS)
        strands.append(np.stack([np.full(POINTS, x), y, np.full(POINTS, z)], 1))
    for root, out in (((rx, 0, 0), (1, 0, 0)), ((-rx, 0, 0), (-1, 0, 0)), ((0, ry, 0), (0, 1, 0))):
        for k in range(3):
            r = np.array(root, float) * (1 + 1e-3) + np.array([0, 0, (k - 1) * 1e-3])
            strands.append(r + np.outer(np.linspace(0, 0.03, POINTS), out))
    return strands, n


def parse_fiber(items):
    out = {}
    for item in items:
        key, _, value = item.partition("=")
        if not key or not value:
            sys.exit(f"slab.py: --fiber {item!r}: expected KEY=VALUE")
        out[key] = json.loads(value)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="/tmp/wisp-slab")
    ap.add_argument("--nbar", default="2,8", help="mean crossings through the slab's depth")
    ap.add_argument("--lights", default="back,front")
    ap.add_argument("--colour", default="blond", choices=sorted(rt.COLOURS))
    ap.add_argument("--model", default="chiang")
    ap.add_argument("--fiber", action="append", default=[], help="override a fibre field, KEY=JSON")
    ap.add_argument("--tag", default="", help="wisp's renders go to <kind>-TAG (Mitsuba's are shared)")
    ap.add_argument("--kinds", default="dual,single", help="which shadings to run (multi needs both)")
    ap.add_argument("--wisp-arg", action="append", default=[],
                    help="an extra flag for wisp export, e.g. --wisp-arg=--contact-mm=40")
    ap.add_argument("--size", type=int, default=400)
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--wisp", default=os.path.join(rt.REPO, "target", "release", "wisp"))
    ap.add_argument("--python", default=sys.executable, help="the Python that has mitsuba")
    args = ap.parse_args()
    kinds = set(args.kinds.split(","))
    if not kinds <= {"dual", "single"}:
        ap.error(f"--kinds {args.kinds!r}: a comma-separated subset of dual,single")
    fiber = parse_fiber(args.fiber)
    os.makedirs(args.out, exist_ok=True)
    results = open(os.path.join(args.out, "results.jsonl"), "a")
    for nbar in [float(v) for v in args.nbar.split(",")]:
        style = rt.style_variant("smooth", f"slab-{args.colour}", sigma_a=rt.COLOURS[args.colour] * rt.EUMELANIN,
                                 model=args.model)
        style["fiber"].update(fiber)
        strands, n = slab_strands(nbar, style)
        style["wisps"]["strands_per_wisp"] = len(strands) // style["wisps"]["count"]
        case_dir = os.path.join(args.out, f"n{nbar:g}-{args.colour}")
        os.makedirs(case_dir, exist_ok=True)
        hair = os.path.join(case_dir, "slab.hair")
        write_hair(hair, strands, style["fiber"]["radius_m"])
        style_path = os.path.join(case_dir, f"style{('-' + args.tag) if args.tag else ''}.json")
        json.dump(style, open(style_path, "w"), indent=1)
        for light in args.lights.split(","):
            figs = {}
            for kind, depth in (("dual", 64), ("single", 2)):
                if kind not in kinds:
                    continue
                ref_dir = os.path.join(case_dir, f"{light}-{kind}")
                d = ref_dir + (f"-{args.tag}" if args.tag else "")
                rt.run([args.wisp, "export", "--quiet", "--hairstyle", f"{hair},{style_path}",
                        "--groom-turn-deg", "0", "--still", "--no-sim", "--no-solids",
                        "--ambient", "0", "--irradiance", "1", "--width", str(args.size),
                        "--height", str(args.size), "--camera-eye", "0,-0.15,0.5",
                        "--camera-target", "0,-0.15,0", "--fov-deg", "10",
                        "--light-dir", LIGHTS[light], "--shading", kind, "--out", d] + args.wisp_arg)
                ref = os.path.join(ref_dir, f"mitsuba_d{depth}.exr")
                if not os.path.exists(ref):
                    if d != ref_dir:
                        sys.exit(f"slab.py: {ref} missing: run without --tag first")
                    rt.run([args.python, os.path.join(HERE, "render.py"), ref_dir, "--spp",
                            str(args.spp), "--passes", str(args.passes), "--depth", str(depth)])
                if subprocess.run(["cmp", "-s", os.path.join(d, "hair.hair"),
                                   os.path.join(ref_dir, "hair.hair")]).returncode:
                    sys.exit(f"slab.py: {d}/hair.hair differs from the rendered {ref_dir}/hair.hair")
                fig_path = os.path.join(d, "compare.json")
                rt.run([args.python, os.path.join(HERE, "compare.py"), os.path.join(d, "wisp.exr"), ref,
                        "--crop", "0.5", "--region", "all", "--json", fig_path,
                        "--png", os.path.join(d, "compare.png"), "--label", f"slab {nbar:g} {light} {kind}"])
                figs[kind] = json.load(open(fig_path))
            f3 = lambda v: " / ".join(f"{x:.2f}" for x in v)
            if len(figs) < 2:
                for kind, fig in figs.items():
                    ratio = np.array(fig["wisp_mean"]) / np.array(fig["ref_mean"])
                    print(f"| {nbar:g} | {light} | {args.tag or '-'} | {kind} | {f3(ratio)} |", flush=True)
                continue
            dw, sw = np.array(figs["dual"]["wisp_mean"]), np.array(figs["single"]["wisp_mean"])
            dr, sr = np.array(figs["dual"]["ref_mean"]), np.array(figs["single"]["ref_mean"])
            row = dict(nbar=nbar, strands=n, colour=args.colour, light=light, tag=args.tag,
                       fiber=fiber, dual=(dw / dr).tolist(),
                       single=(sw / sr).tolist(), multi=((dw - sw) / (dr - sr)).tolist(),
                       pt_multi_share=((dr - sr) / dr).tolist(), pixels=figs["dual"]["pixels"])
            results.write(json.dumps(row) + "\n")
            results.flush()
            print(f"| {nbar:g} | {light} | {args.tag or '-'} | {f3(row['dual'])} | {f3(row['single'])} | "
                  f"{f3(row['multi'])} | {f3(row['pt_multi_share'])} |", flush=True)


if __name__ == "__main__":
    main()
