#!/usr/bin/env python3
"""Regenerates issue 14's comparison table: wisp against Mitsuba 3 (not run by CI).

    run_table.py [--out DIR] [--size 400] [--spp 128] [--passes 8] [--only dense,isolated,curly]
                 [--colours blond,brown,red] [--lights front,side,back,point] [--depth 64]
                 [--kinds dual,single] [--set FIELD=VALUE ...]

For every case it writes hairstyle JSON generated from the presets into DIR/styles (no new
preset files), exports the frame with `wisp export` (dual and single shading), renders the
path-traced reference with render.py (max_depth 64 = all orders, 2 = single scattering with
hard shadows; --depth sets the first, 256 for the far side of dense hair) and compares with
compare.py. Cases:

- dense: the smooth preset with 12x the render strands (40,200 strands), 1 fibre each, still
  head, alpha_R = 0, eccentricity 1; blond and brown; front, side and back light;
- isolated: the smooth preset with 1 strand per wisp (134 strands), 1 fibre each, blond;
- curly: the curly preset with 4x the render strands (13,400), 1 fibre each, its own colour.

Every case: no head drawn, ambient 0, light irradiance 1, black background, the same fixed
camera for both renderers (the head-following framing of the first export, then fixed).
Lights are relative to that camera: front travels along the view direction, side across it
(from the image's right), back toward the camera; point (only with --lights point) is a point
light 0.5 m from the head's centre toward the camera + the image's right + half the camera's
up, of intensity
d² for the median distance d to the hair (irradiance 1 there; point_light()), written as the
scene file DIR/<case>/point_light.json. Blond and brown are pbrt's eumelanin
concentrations 0.3 and 1.3: sigma_a = c x (0.419, 0.697, 1.37) per unit radius.

Results go to DIR/results.jsonl (one line per comparison) and DIR/table.md; side-by-side
PNGs to DIR/<case>/compare_*.png. "coverage wisp / PT" is the ratio of the images' summed
alpha: how much of the image each renderer's hair covers (1 = physical coverage agrees). Re-running skips renders whose outputs exist
(--force to redo); --table-only rebuilds table.md from results.jsonl. `--set strands.points=241`
changes a field of every case's hairstyle (ACCURACY.md's curl-resolution table); use a new DIR
for it, since the path-traced renders are of that geometry.
"""

import argparse
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

import compare

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
EUMELANIN = np.array([0.419, 0.697, 1.37])
COLOURS = {"blond": 0.3, "brown": 1.3}
LIGHTS = ["front", "side", "back", "point"]
# The point light: this far from the still head's centre (wisp's world origin), beyond the
# smooth preset's reach of 0.465 m (0.34 m x 1.08 + the head's 0.098 m), which wisp requires of
# a point light (`scene::file::check_point_lights_outside`); from the camera's side, the
# image's right and a little above, so that it lights the hair obliquely.
POINT_DISTANCE_M = 0.5
POINT_LIGHT_FILE = "point_light.json"


def style_variant(preset, name, strand_factor=1, strands_per_wisp=None, sigma_a=None, model=None):
    s = json.load(open(os.path.join(REPO, "hairstyles", f"{preset}.json")))
    s["name"] = name
    if strands_per_wisp is not None:
        s["wisps"]["strands_per_wisp"] = strands_per_wisp
    else:
        s["wisps"]["strands_per_wisp"] *= strand_factor
    s["strands"]["fibers_per_strand"] = 1
    # One fibre per strand cannot thin toward its tip: the strand's own length (which the
    # preset varies) is its fibre's length, the same for both renderers.
    s["strands"]["tip_taper"] = 0.0
    s["fiber"]["alpha_r_deg"] = 0.0
    s["fiber"]["eccentricity"] = 1.0
    if sigma_a is not None:
        s["fiber"]["sigma_a"] = [round(float(v), 4) for v in sigma_a]
    if model is not None:
        s["fiber"]["model"] = model
    return s


def set_field(style, assignment):
    """`--set strands.points=241`: a dotted hairstyle field given a JSON value (a bare word is a
    string), applied to every hairstyle of the table after the variants are made."""
    key, sep, raw = assignment.partition("=")
    if not sep or not key:
        sys.exit(f"run_table.py: --set {assignment!r}: expected FIELD.PATH=VALUE")
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        value = raw
    node, parts = style, key.split(".")
    for part in parts[:-1]:
        if not isinstance(node.get(part), dict):
            sys.exit(f"run_table.py: --set {assignment!r}: the hairstyle has no section {part!r}")
        node = node[part]
    node[parts[-1]] = value


def cases(only, model):
    out = []
    if "dense" in only:
        for colour, c in COLOURS.items():
            style = style_variant("smooth", f"dense-{colour}", strand_factor=12,
                                  sigma_a=c * EUMELANIN, model=model)
            out += [("dense", colour, light, style) for light in LIGHTS]
    if "isolated" in only:
        style = style_variant("smooth", "isolated-blond", strands_per_wisp=1,
                              sigma_a=COLOURS["blond"] * EUMELANIN, model=model)
        out += [("isolated", "blond", light, style) for light in LIGHTS]
    if "curly" in only:
        style = style_variant("curly", "curly", strand_factor=4, model=model)
        out += [("curly", "red", light, style) for light in LIGHTS]
    return out


def light_dir(camera, which):
    f, right, _ = camera_frame(camera)
    return {"front": f, "side": -right, "back": -f}[which]


def camera_frame(camera):
    """The camera's forward, right and up unit vectors (world)."""
    eye, target, up = (np.array(camera[k], float) for k in ("eye", "target", "up"))
    f = target - eye
    f /= np.linalg.norm(f)
    right = np.cross(f, up)
    right /= np.linalg.norm(right)
    return f, right, np.cross(right, f)


def point_light(camera, hair_points):
    """The point light's position (metres) and intensity (W/sr, grey): POINT_DISTANCE_M from the
    head's centre along (toward the camera + right + up / 2), and bright enough that the median
    distance d to the hair's points receives irradiance 1 (I = d², rounded to 3 digits)."""
    f, right, up = camera_frame(camera)
    # Half up: from (-f + right + up) the crown shadowed all the lengths, which the path tracer
    # then lit by light scattered many times alone (half its blocks noise at 1,024 spp).
    way = -f + right + 0.5 * up
    pos = POINT_DISTANCE_M * way / np.linalg.norm(way)
    d = float(np.median(np.linalg.norm(hair_points - pos, axis=1)))
    return pos, float(f"{d * d:.3g}")


def light_flags(case_dir, camera, which, create=False):
    """wisp's flags for the light `which` (front, side, back: a directional light of irradiance
    1 relative to the camera; point: the scene file CASE_DIR/point_light.json, which `create`
    writes from the camera probe's strands in CASE_DIR/camera)."""
    if which != "point":
        return ["--irradiance", "1", "--light-dir", vec(light_dir(camera, which))]
    path = os.path.join(case_dir, POINT_LIGHT_FILE)
    if create and not os.path.exists(path):
        import hairfile
        pts = hairfile.Strands(os.path.join(case_dir, "camera", "hair.hair")).points
        pos, intensity = point_light(camera, pts)
        json.dump({"lights": [{"type": "point", "position_m": [round(float(x), 6) for x in pos],
                               "intensity": [intensity] * 3}]}, open(path, "w"), indent=1)
    if not os.path.exists(path):
        sys.exit(f"run_table.py: {path} missing: the point light's scene file (run_table.py "
                 "--lights point writes it)")
    return ["--scene", path]


def run(cmd, env=None):
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"run_table.py: failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    return p, time.time() - t0


def vec(v):
    return ",".join(f"{x:.6g}" for x in v)


def write_table(out_dir):
    rows = [json.loads(line) for line in open(os.path.join(out_dir, "results.jsonl"))]
    # Last result per key wins (re-runs append).
    by_key = {}
    for r in rows:
        by_key[(r["case"], r["colour"], r["light"], r["kind"])] = r
    lines = []
    info = next(iter(by_key.values()))
    lines.append(f"Image {info['size']}x{info['size']} px, Mitsuba {info['spp']} spp in "
                 f"{info['passes']} passes; ratios wisp / path traced of mean linear radiance "
                 f"(R / G / B) over pixels covered >= 0.99 in both (isolated fibres, which cover no pixel: summed over the whole image); +- one standard error of "
                 f"the path tracer's mean; p10 = ratio of 10th-percentile luminance per pixel ('PT 0': the "
                 f"path tracer's per-pixel p10 is 0), then the bracket on the ratio of the darkest tenth's "
                 f"mean luminance over 4 and 8 px blocks (compare.py darkest_tenth()); the share of 8 px "
                 f"hair blocks within 1.5x / 2x, then the path tracer's halves against each other "
                 f"and the share an exact wisp would score against this reference (compare.py "
                 f"block_shares()).\n")
    lines.append("| case | hair | light | dual / all orders | +- | p10 | 8 px blocks within 1.5 / 2x | single / single | +- | p10 | 8 px blocks within 1.5 / 2x | px | coverage wisp / PT | wisp ms (dual) | Mitsuba s (all / d2) |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    keys = sorted({k[:3] for k in by_key}, key=lambda k: (["dense", "isolated", "curly"].index(k[0]), k[1], LIGHTS.index(k[2])))
    f3 = lambda v: " / ".join(f"{x:.2f}" for x in v)
    se3 = lambda v: " / ".join(f"{x:.3f}" for x in v)
    for k in keys:
        d, s = by_key.get(k + ("dual",)), by_key.get(k + ("single",))
        cells = [k[0], k[1], k[2]]
        for r in (d, s):
            if r and "ratio" in r:
                dark = compare.dark_cell(r)
                p10 = "-" if "p10_wisp" not in r else (
                    (f"{r['p10_ratio']:.2f}" if r["p10_ratio"] not in (None, float("inf")) else "PT 0")
                    + (f"; {dark}" if dark else ""))
                cells += [f3(r["ratio"]), se3(r.get("ratio_se", [np.nan] * 3)), p10,
                          compare.share_cell(r)]
            else:
                cells += ["-", "-", "-", "-"]
        r = d or s or {}
        cells.append(f"{r.get('pixels', '-')}" + (" (whole image)" if r.get("region") == "all" else ""))
        cells.append(f"{r['coverage_ratio']:.3f}" if "coverage_ratio" in r else "-")
        cells.append(f"{d['wisp_ms']:.0f}" if d else "-")
        cells.append(f"{d['mitsuba_s']:.0f} / {s['mitsuba_s']:.0f}" if d and s else "-")
        lines.append("| " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    open(os.path.join(out_dir, "table.md"), "w").write(text)
    print(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="/tmp/wisp-reference-table")
    ap.add_argument("--size", type=int, default=400)
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--only", default="dense,isolated,curly")
    ap.add_argument("--colours", default="blond,brown,red",
                    help="which hair colours of the cases (dense: blond, brown; curly: red)")
    ap.add_argument("--depth", type=int, default=64,
                    help="the path tracer's max_depth for the all-orders column (256 reaches the "
                    "far side of dense hair: README, 'Depth')")
    ap.add_argument("--lights", default="front,side,back",
                    help="which of front,side,back,point (point: a point light POINT_DISTANCE_M "
                    "from the head, point_light())")
    ap.add_argument("--kinds", default="dual,single", help="which of dual,single (a single-only run takes minutes)")
    ap.add_argument("--model", help="set fiber.model in every hairstyle (e.g. chiang)")
    ap.add_argument("--dual-shading", default="dual", help="wisp --shading for the all-orders column")
    ap.add_argument("--single-shading", default="single", help="wisp --shading for the single column")
    ap.add_argument("--wisp", default=os.path.join(REPO, "target", "release", "wisp"))
    ap.add_argument("--python", default=sys.executable, help="the Python that has mitsuba")
    ap.add_argument("--integrator", choices=["fibre", "path"], default="fibre",
                    help="render.py's integrator: fibre (rays leave a fibre from its surface) or "
                    "Mitsuba's own path (its 0.1 mm ray offset; the tables before 2026-12-06)")
    ap.add_argument("--force", action="store_true")
    ap.add_argument("--table-only", action="store_true")
    ap.add_argument("--set", action="append", default=[], metavar="FIELD=VALUE",
                    help="set a hairstyle field in every case, e.g. strands.points=241 (repeatable)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.table_only:
        write_table(args.out)
        return
    styles_dir = os.path.join(args.out, "styles")
    os.makedirs(styles_dir, exist_ok=True)
    results = open(os.path.join(args.out, "results.jsonl"), "a")
    camera = {}
    lights, kinds = args.lights.split(","), args.kinds.split(",")
    for case, colour, light, style in cases(args.only.split(","), args.model):
        if light not in lights or colour not in args.colours.split(","):
            continue
        for assignment in args.set:
            set_field(style, assignment)
        style_path = os.path.join(styles_dir, f"{style['name']}.json")
        json.dump(style, open(style_path, "w"), indent=1)
        common = [args.wisp, "export", "--quiet", "--hairstyle", style_path, "--still",
                  "--no-solids", "--ambient", "0",
                  "--width", str(args.size), "--height", str(args.size)]
        if case not in camera:
            # The head-following framing of this hairstyle, then fixed for every light.
            probe = os.path.join(args.out, case, "camera")
            run(common + ["--irradiance", "1", "--out", probe])
            camera[case] = json.load(open(os.path.join(probe, "scene.json")))["camera"]
        cam = camera[case]
        view = ["--camera-eye", vec(cam["eye"]), "--camera-target", vec(cam["target"]),
                "--camera-up", vec(cam["up"]), "--fov-deg", f"{cam['fov_y_deg']:.6g}"]
        view += light_flags(os.path.join(args.out, case), cam, light, create=True)
        for kind, shading, depth in (("dual", args.dual_shading, args.depth), ("single", args.single_shading, 2)):
            if kind not in kinds:
                continue
            d = os.path.join(args.out, case, f"{colour}-{light}-{kind}")
            p, _ = run([c for c in common if c != "--quiet"] + view + ["--shading", shading, "--out", d])
            wisp_ms = float(re.search(r"frame ([0-9.]+) ms", p.stderr).group(1))
            ref = os.path.join(d, f"mitsuba_d{depth}.exr")
            if args.force or not os.path.exists(ref):
                run([args.python, os.path.join(HERE, "render.py"), d, "--spp", str(args.spp),
                     "--passes", str(args.passes), "--depth", str(depth),
                     "--integrator", args.integrator])
            minfo = json.load(open(os.path.join(d, f"mitsuba_d{depth}.json")))
            fig_path = os.path.join(d, "compare.json")
            png = os.path.join(args.out, case, f"compare_{colour}_{light}_{kind}.png")
            label = f"{case} {colour} {light} {kind}"
            p, _ = run([args.python, os.path.join(HERE, "compare.py"), os.path.join(d, "wisp.exr"),
                        ref, "--passes", os.path.join(d, f"mitsuba_d{depth}_passes.npy"),
                        "--png", png, "--json", fig_path, "--label", label])
            fig = json.load(open(fig_path))
            fig.update(case=case, colour=colour, light=light, kind=kind, size=args.size,
                       spp=minfo["spp"], passes=minfo["passes"], mitsuba_s=minfo["render_s"],
                       wisp_ms=wisp_ms, shading=shading, max_depth=depth)
            results.write(json.dumps(fig) + "\n")
            results.flush()
            print(p.stdout.strip(), f"(wisp {wisp_ms:.0f} ms, Mitsuba {minfo['render_s']:.0f} s)", flush=True)
    results.close()
    write_table(args.out)


if __name__ == "__main__":
    main()
