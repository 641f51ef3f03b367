#!/usr/bin/env python3
"""Single evaluations of wisp's Chiang fibre model against Mitsuba 3's `hair` BSDF (not run by CI).

    chiang_eval_check.py [--wisp target/release/wisp] [--h-samples 2000]

Mitsuba's `hair` (Chiang et al. 2016) is a near-field model: its `eval` gives f*cos for a camera
ray that hits the fibre at offset h = sin(gamma). A pixel covering the fibre's width averages h
uniformly, so the far field that wisp tabulates is the mean of `eval` over h in [-1, 1]. This
script computes that mean with Mitsuba (scalar_rgb, midpoint rule in h) and compares it with
`wisp fiber eval` (whose S times cos(theta_i) is the same quantity, radiance per unit
irradiance) for a few fibres and direction pairs, then prints a Markdown table of the ratios.

Mapping (../shared/reference/MAPPING.md): sigma_a per unit radius as is; int_ior = eta,
ext_ior = 1; scale_tilt = alpha_r_deg; azimuthal_roughness as is; longitudinal_roughness b
solves 0.726 b + 0.812 b^2 + 3.7 b^20 = 2 beta_R (radians), which is what wisp's v0 = (2 beta_R)^2
means. Angles: wisp's light direction (theta_i, phi_i) is Mitsuba's `wo`, the camera (theta_o,
phi_o) is Mitsuba's `si.wi`; Mitsuba's local frame has y = tangent and z = the normal at the hit.

Needs Python 3 with mitsuba==3.9.1 and numpy (see ../shared/reference/README.md; /work/venv-mitsuba
has them) and a release build of wisp (`cargo build --release`).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import mitsuba as mi

mi.set_variant("scalar_rgb")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

FIBRES = {
    "brown, tilt 0": dict(sigma_a=[0.545, 0.906, 1.78], alpha_r_deg=0.0),
    "brown, tilt -7.5": dict(sigma_a=[0.545, 0.906, 1.78], alpha_r_deg=-7.5),
    "blond, tilt 0, beta_n 0.6": dict(
        sigma_a=[0.15, 0.2, 0.3], alpha_r_deg=0.0, azimuthal_roughness=0.6
    ),
    "white, beta_R 3": dict(sigma_a=[0.0, 0.0, 0.0], alpha_r_deg=0.0, beta_r_deg=3.0),
}

# (theta_i, phi_i, theta_o, phi_o) in degrees: light and camera, wisp's naming.
PAIRS = [
    (0, 0, 0, 180),  # back light, TT
    (0, 0, 0, 0),  # front light, R and TRT
    (20, 0, -20, 10),  # near the specular cone, small phi
    (30, 0, -25, 120),
    (45, 0, -40, 170),
    (-35, 0, 30, 60),
    (60, 0, -55, 150),
    (10, 0, 40, 90),  # off the cone
    (75, 0, -70, 20),  # grazing
]


def roughness_for_std(std_rad):
    lo, hi = 0.0, 1.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if 0.726 * mid + 0.812 * mid * mid + 3.7 * mid**20 < std_rad:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def mitsuba_far_field(params, ti, phi_i, to, phi_o, n_h):
    """Mean over h of Mitsuba's eval (f*cos) for light (ti, phi_i) and camera (to, phi_o), degrees."""
    b = roughness_for_std(2.0 * math.radians(params["beta_r_deg"]))
    bsdf = mi.load_dict(
        {
            "type": "hair",
            "sigma_a": {"type": "rgb", "value": params["sigma_a"]},
            "int_ior": params["eta"],
            "ext_ior": 1.0,
            "longitudinal_roughness": b,
            "azimuthal_roughness": params["azimuthal_roughness"],
            "scale_tilt": params["alpha_r_deg"],
        }
    )
    ctx = mi.BSDFContext()
    ti, to = math.radians(ti), math.radians(to)
    dphi = math.radians(phi_i - phi_o)  # light azimuth relative to the camera's
    acc = [0.0, 0.0, 0.0]
    for k in range(n_h):
        h = -1.0 + (k + 0.5) * 2.0 / n_h
        g = math.asin(h)
        # Camera in the hit's local frame: gamma(wi) = g (Mitsuba's sign convention).
        cam = mi.Vector3f(-math.cos(to) * math.sin(g), math.sin(to), math.cos(to) * math.cos(g))
        phi_cam = math.atan2(cam.z, cam.x)
        phi_l = phi_cam + dphi
        light = mi.Vector3f(math.cos(ti) * math.cos(phi_l), math.sin(ti), math.cos(ti) * math.sin(phi_l))
        si = mi.SurfaceInteraction3f()
        si.wi = cam
        v = bsdf.eval(ctx, si, light)
        for c in range(3):
            acc[c] += float(v[c]) / n_h
    return acc


def wisp_far_field(exe, hairstyle, ti, phi_i, to, phi_o):
    out = subprocess.run(
        [
            exe, "fiber", "eval", "--hairstyle", hairstyle,
            "--theta-i-deg", str(ti), "--phi-i-deg", str(phi_i),
            "--theta-o-deg", str(to), "--phi-o-deg", str(phi_o),
        ],
        check=True, capture_output=True, text=True,
    ).stdout
    s = json.loads(out)["S"]
    cos_i = math.cos(math.radians(ti))
    return [x * cos_i for x in s]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--wisp", default=os.path.join(ROOT, "target", "release", "wisp"))
    ap.add_argument("--h-samples", type=int, default=2000)
    args = ap.parse_args()
    if not os.path.exists(args.wisp):
        sys.exit(f"{args.wisp} not found: run `cargo build --release` first")
    with open(os.path.join(ROOT, "hairstyles", "smooth.json")) as f:
        style = json.load(f)
    print("| fibre | theta_i, phi_i, theta_o, phi_o (deg) | Mitsuba f*cos (R, G, B) | wisp / Mitsuba |")
    print("|---|---|---|---|")
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, over in FIBRES.items():
            fibre = dict(
                model="chiang", eta=1.55, beta_r_deg=7.5, azimuthal_roughness=0.3,
                eccentricity=1.0, radius_m=4e-5,
            )
            fibre.update(over)
            style["fiber"] = fibre
            path = os.path.join(tmp, "style.json")
            with open(path, "w") as f:
                json.dump(style, f)
            for pair in PAIRS:
                m = mitsuba_far_field(fibre, *pair, args.h_samples)
                w = wisp_far_field(args.wisp, path, *pair)
                ratio = [wc / mc if mc > 1e-12 else float("nan") for wc, mc in zip(w, m)]
                if max(m) > 1e-4:
                    worst = max(worst, max(abs(r - 1.0) for r in ratio if r == r))
                print(
                    f"| {name} | {pair} | {m[0]:.5g}, {m[1]:.5g}, {m[2]:.5g} "
                    f"| {ratio[0]:.4f}, {ratio[1]:.4f}, {ratio[2]:.4f} |"
                )
    print(f"\nlargest |wisp/Mitsuba - 1| where Mitsuba > 1e-4: {worst:.4f}")


if __name__ == "__main__":
    main()
