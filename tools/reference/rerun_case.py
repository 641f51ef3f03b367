#!/usr/bin/env python3
"""Re-run only wisp on one case of a table that run_table.py made, and compare it with the
path tracer's renders cached there (the same exported strands and camera), so a change to the
shading is measured in seconds instead of re-rendering with Mitsuba.

usage: rerun_case.py OUTDIR TABLEDIR case colour light kind [wisp flags...]
  case: dense | isolated | curly; colour: blond | brown | red; light: front | side | back |
  point (the table's TABLEDIR/<case>/point_light.json);
  kind: dual | single. TABLEDIR/styles/*.json are the table's hairstyles (edit a copy to try
  other fibre parameters). REF_DEPTH (environment) picks the path tracer's render that dual
  is compared with, mitsuba_d<REF_DEPTH>.exr (default 64; 256 reaches the far side of dense
  hair, ACCURACY.md section 2). The image size is the rendered scene's. WISP (environment) is the wisp binary (default target/release/wisp);
  it must export the same strands as the binary that made the table. DUAL_SHADING (environment)
  is wisp's --shading for the all-orders kind (default dual; `volume` for light paths through
  the volume); the single kind is always `single`. REUSE_WISP=1 (environment) compares
  again without re-running wisp when OUTDIR holds this case's export made with the same
  command (a reference stacked with more samples). Writes OUTDIR/<case>-
  <colour>-<light>-<kind>/ (wisp's export) and OUTDIR/cmp-<same>.png and .json (compare.py's).
"""
import json, os, subprocess, sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hairfile
import run_table as rt
out, table, case, colour, light, kind = sys.argv[1:7]
extra = sys.argv[7:]
ref_depth = os.environ.get("REF_DEPTH", "64")
if not ref_depth.isdigit() or int(ref_depth) < 3:
    sys.exit(f"rerun_case.py: REF_DEPTH must be a whole number of at least 3 (a max depth of all orders), not {ref_depth!r}")
depth = int(ref_depth) if kind == "dual" else 2
ref_dir = os.path.join(table, case, f"{colour}-{light}-{kind}")
ref = os.path.join(ref_dir, f"mitsuba_d{depth}.exr")
if not os.path.exists(ref):
    sys.exit(f"rerun_case.py: {ref} missing: render it with render.py {ref_dir} --depth {depth}")
wisp = os.environ.get("WISP", "target/release/wisp")
style = os.path.join(table, "styles", f"{'dense-'+colour if case=='dense' else ('isolated-blond' if case=='isolated' else 'curly')}.json")
cam = json.load(open(os.path.join(table, case, "camera", "scene.json")))["camera"]
# The image size the path tracer rendered (run_table.py --size).
image = json.load(open(os.path.join(ref_dir, "scene.json")))["image"]
common = [wisp, "export", "--hairstyle", style, "--still", "--no-solids", "--ambient", "0", "--width", str(image["width"]), "--height", str(image["height"])]
view = ["--camera-eye", rt.vec(cam["eye"]), "--camera-target", rt.vec(cam["target"]), "--camera-up", rt.vec(cam["up"]), "--fov-deg", f"{cam['fov_y_deg']:.6g}"]
view += rt.light_flags(os.path.join(table, case), cam, light)
shading = os.environ.get("DUAL_SHADING", "dual") if kind == "dual" else "single"
d = os.path.join(out, f"{case}-{colour}-{light}-{kind}")
cmd = common + view + ["--shading", shading, "--out", d] + extra
# REUSE_WISP=1 keeps an export this script made with the very same command (binary, flags)
# and only compares again: against a reference stacked with more samples, say.
stamp = os.path.join(d, "rerun_case.json")
if not (os.environ.get("REUSE_WISP") == "1" and os.path.exists(stamp)
        and json.load(open(stamp)).get("cmd") == cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode: sys.exit(p.stderr)
    json.dump({"cmd": cmd}, open(stamp, "w"), indent=1)
# The comparison means something only for the strands the path tracer rendered: a binary or a
# hairstyle that settles the hair differently compares other hair (back light, whose radiance
# is the silhouette's fringe, moved 12% that way once).
# The same strands cut into pieces (`--segment-pieces`) are the same drawn hair.
if hairfile.pieces_of(os.path.join(d, "hair.hair"), os.path.join(ref_dir, "hair.hair")) is None:
    print(f"warning: {d}/hair.hair differs from the rendered {ref_dir}/hair.hair: "
          "this compares different strands", file=sys.stderr)
p = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "compare.py"), os.path.join(d, "wisp.exr"), ref, "--passes", os.path.join(ref_dir, f"mitsuba_d{depth}_passes.npy"), "--png", os.path.join(out, f"cmp-{case}-{colour}-{light}-{kind}.png"), "--json", os.path.join(out, f"cmp-{case}-{colour}-{light}-{kind}.json"), "--label", f"{case} {colour} {light} {kind} {' '.join(extra)}"], capture_output=True, text=True)
print(p.stdout.strip() or p.stderr)
