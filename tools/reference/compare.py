#!/usr/bin/env python3
"""wisp's image against a path-traced one (not run by CI).

    compare.py WISP_EXR MITSUBA_EXR [--passes NPY] [--crop F] [--png OUT.png] [--label TEXT] [--json OUT]

Over the pixels fully covered in both images (alpha >= --coverage in each, default 0.99, so
both hold radiance of hair alone; with fewer than 500 such pixels, as for isolated fibres,
over the whole image: the ratio of the light each sends to the camera), reports per channel the ratio of mean linear radiance
wisp / path traced, its standard error (from the path tracer's independent passes, --passes;
wisp is deterministic), the ratio of the 10th-percentile luminance (the darkest hair) per
pixel, a bracket on the ratio of the darkest tenth's mean luminance over 4 x 4 and 8 x 8
blocks that the path tracer's noise cannot bias (darkest_tenth(); needs --passes), the share
of 8 x 8 px hair blocks (mean alpha >= --block-coverage, 0.5, in both) within 1.5x and 2x beside the path tracer's own block noise (its
halves against each other; block_shares(); needs --passes), the coverage ratio, and the
pixel count. Prints one Markdown table row, optionally writes the
figures as JSON and a side-by-side PNG: wisp | path traced (same exposure, sRGB) | log2(wisp / path traced) of
luminance summed over 8 x 8 blocks of compared pixels (blue: wisp darker, red: wisp
brighter, white: equal, +-2 stops full scale; grey where fewer than a quarter of a block's
pixels are compared, or where neither image has hair).
"""

import argparse
import json
import sys

import numpy as np

LUMA = np.array([0.2126, 0.7152, 0.0722])


def load_rgba(mi, path):
    a = np.array(mi.Bitmap(path), dtype=np.float64)
    if a.ndim != 3 or a.shape[2] != 4:
        raise SystemExit(f"compare.py: {path}: expected an RGBA image, got shape {a.shape}")
    return a


def block_sum(a, k):
    """Sums over k x k blocks (the image cropped to whole blocks)."""
    h, w = (a.shape[0] // k) * k, (a.shape[1] // k) * k
    a = a[:h, :w]
    return a.reshape(h // k, k, w // k, k, *a.shape[2:]).sum(axis=(1, 3))


# Block sizes (pixels) of the darkest-tenth bracket: 4 x 4 keeps the spatial scale of "the
# darkest hair"; 8 x 8 has less noise where the path tracer's light is rare.
DARK_BLOCKS = (4, 8)


def block_means(mask, k):
    """The k x k blocks at least half compared under `mask`, and a function giving an image's
    mean luminance over each such block's compared pixels (a flat array, one per block)."""
    cnt = block_sum(mask.astype(float), k)
    keep = cnt >= 0.5 * k * k
    m = mask[..., None]
    return keep, lambda img: block_sum(((img[..., :3] * m) @ LUMA), k)[keep] / cnt[keep]


def bracket_text(d):
    """One darkest-tenth bracket (a darkest_tenth() result) as "lo-hi", or ">= lo" when the
    path tracer's darkest tenth of the mean image is 0."""
    lo, hi = d["ratio"]
    return f"{lo:.2f}-{hi:.2f}" if np.isfinite(hi) else f">= {lo:.2f}"


def darkest_tenth(wisp, ref, passes, mask, k, tail=10.0):
    """The mean luminance of the darkest tenth of k x k blocks (each the mean over its compared
    pixels; blocks at least half compared), wisp's against a bracket on the path tracer's.

    At 128 spp a dark pixel of the path tracer is mostly noise (zeros next to fireflies), so
    its darkest tenth read from the image is biased low, and a percentile ratio against it
    measures the noise (the two halves of the passes gave p10 ratios of 0.43-0.50 and 0.00 on
    the dense side- and back-lit scenes). The tail mean brackets the converged value instead:
    - low: the darkest tenth of the mean image. The tail mean is a concave function of the
      image (a minimum over sets of blocks of their mean), so by Jensen its expectation over
      the noise is at most the converged value;
    - high: each pass held out in turn, the blocks darkest in the other passes' mean, measured
      in the held-out pass. The held-out pass is independent of the choice, so this is the
      converged mean over a set of blocks chosen without knowing it, at least the converged
      darkest tenth.
    The ratio wisp / converged path tracer then lies in [wisp / high, wisp / low] (each bound
    in expectation); `within_2x` is "yes" when the whole bracket lies in [0.5, 2], "no" when
    it lies outside, and "undecided" (more samples needed) otherwise."""
    keep, lum = block_means(mask, k)
    if keep.sum() < 50:
        return None
    w, r = lum(wisp), lum(ref)
    per_pass = np.array([lum(p) for p in passes])
    darkest = lambda v: v <= np.percentile(v, tail)
    w_dark, low = w[darkest(w)].mean(), r[darkest(r)].mean()
    held_out = []
    for i in range(len(per_pass)):
        rest = np.delete(per_pass, i, axis=0).mean(axis=0)
        held_out.append(per_pass[i][darkest(rest)].mean())
    high = float(np.mean(held_out))
    lo_ratio = w_dark / high if high > 0 else float("inf")
    hi_ratio = w_dark / low if low > 0 else float("inf")
    verdict = ("yes" if 0.5 <= lo_ratio and hi_ratio <= 2.0
               else "no" if hi_ratio < 0.5 or lo_ratio > 2.0 else "undecided")
    return {"blocks": int(keep.sum()), "wisp": float(w_dark), "ref_low": float(low),
            "ref_high": high, "ratio": [float(lo_ratio), float(hi_ratio)], "within_2x": verdict}


# The spatial measure: 8 x 8 px blocks of hair, each compared whole. A block counts when its
# mean alpha is >= SHARE_COVERAGE in both images: the silhouette's blocks, where light
# scattered many times shows first, count too, and the two renderers' coverage of a block
# agrees within 2% there (5th-95th percentile of wisp / path tracer 0.998-1.016 over the
# blocks >= 0.5 covered of dense blond back-lit at 256 px), so a block's ratio is its light's.
SHARE_BLOCK = 8
SHARE_FACTORS = (1.5, 2.0)
SHARE_COVERAGE = 0.5


def block_shares(wisp, ref, passes, k=SHARE_BLOCK, coverage=SHARE_COVERAGE, keep=None):
    """Where the two images agree: over the k x k blocks whose mean alpha is >= `coverage` in
    both images (hair blocks; `keep` optionally masks pixels out, e.g. a crop), the share whose
    luminance ratio wisp / path tracer lies within each factor of SHARE_FACTORS (a block's
    luminance is its summed premultiplied RGB, so a block is one sample of 64 pixels' light).

    Beside it, the path tracer's own block noise, from `passes` split into halves A (the first
    P/2) and B (the rest), both means of independent samples:
    - `noise_halves`: the same shares for A / B. Each half has twice the variance of the full
      mean, so this is what a perfect renderer would score against a reference of half the
      samples (the convergence test: >= 97% within 1.5 means the blocks are converged);
    - `noise_mean`: the shares of |ln(A / B)| / 2 within ln(factor). (ln A − ln B) / 2 has the
      variance of the full mean's ln (each half 2σ², the difference 4σ², halved: σ²), so this
      is what a perfect renderer would score against this reference (the noise ceiling);
    - `corrected`: min(1, share / noise_mean): the share of blocks within the factor once the
      reference's noise is divided out, assuming noise pushes a block out independently of
      wisp's own error and rarely pushes a wrong block in (both hold when the wrong blocks lie
      well outside the factor). An estimate, not a bound: it is the measure the noise does
      not count as wisp's error."""
    if passes is None or len(passes) < 2:
        return None
    k_cov = coverage * k * k
    full = np.ones(wisp.shape[:2]) if keep is None else keep.astype(float)
    hair = (block_sum(wisp[..., 3] * full, k) >= k_cov) & (block_sum(ref[..., 3] * full, k) >= k_cov)
    n = int(hair.sum())
    if n < 20:
        return None
    lum = lambda img: block_sum((img[..., :3] @ LUMA) * full, k)[hair]
    half = len(passes) // 2
    a, b = lum(passes[:half].mean(axis=0)), lum(passes[half:].mean(axis=0))
    with np.errstate(divide="ignore", invalid="ignore"):
        ln_w = np.abs(np.log(lum(wisp) / lum(ref)))
        ln_ab = np.abs(np.log(a / b))
    ln_w, ln_ab = np.nan_to_num(ln_w, nan=np.inf), np.nan_to_num(ln_ab, nan=np.inf)
    out = {"block": k, "blocks": n, "coverage": coverage, "factors": list(SHARE_FACTORS),
           "halves": [half, len(passes) - half]}
    share = lambda v, f: float((v <= np.log(f)).mean())
    out["within"] = [share(ln_w, f) for f in SHARE_FACTORS]
    out["noise_halves"] = [share(ln_ab, f) for f in SHARE_FACTORS]
    out["noise_mean"] = [share(ln_ab / 2, f) for f in SHARE_FACTORS]
    out["corrected"] = [min(1.0, w / m) if m > 0 else None
                        for w, m in zip(out["within"], out["noise_mean"])]
    return out


def share_cell(fig):
    """The block shares of a figure as one table cell: "86 / 97% (PT halves 95 / 99%, noise
    ceiling 99 / 100%)": wisp's share of 8 px blocks within 1.5x / 2x, then the path tracer's
    halves against each other and what an exact wisp would score against this reference."""
    b = fig.get("blocks8")
    if not b:
        return "-"
    pc = lambda v: " / ".join(f"{100 * x:.0f}" for x in v)
    return f"{pc(b['within'])}% (halves {pc(b['noise_halves'])}%, ceiling {pc(b['noise_mean'])}%)"


def dark_cell(fig):
    """The darkest-tenth brackets of a figure as one table cell, e.g. "4px 0.35-3.92, 8px
    1.24-1.80" (">= x" when the path tracer's darkest tenth of the mean image is 0)."""
    parts = []
    for k in DARK_BLOCKS:
        d = fig.get(f"dark10_block{k}")
        if d is not None:
            parts.append(f"{k}px {bracket_text(d)}")
    return ", ".join(parts)


def compare(wisp, ref, passes=None, coverage=0.99, region="auto", min_pixels=500, crop=1.0,
            block_coverage=SHARE_COVERAGE):
    """Figures over the compared region: "covered" (alpha >= coverage in both), "all" (every
    pixel: the ratio of the images' summed premultiplied RGB, i.e. of the light each renderer
    sends to the camera; what sparse hair such as isolated fibres needs, where no pixel is
    fully covered), or "auto" (covered if it has at least min_pixels pixels, else all).
    crop < 1 keeps only the central crop x crop of the image (a slab's edges, where light
    leaks around the side, stay out)."""
    if wisp.shape != ref.shape:
        raise SystemExit(f"compare.py: image sizes differ: {wisp.shape} vs {ref.shape}")
    keep = np.ones(wisp.shape[:2], bool)
    if crop < 1.0:
        h, w = keep.shape
        dy, dx = int(round(h * (1 - crop) / 2)), int(round(w * (1 - crop) / 2))
        keep[:] = False
        keep[dy : h - dy, dx : w - dx] = True
    mask = (wisp[..., 3] >= coverage) & (ref[..., 3] >= coverage) & keep
    if region == "all" or (region == "auto" and mask.sum() < min_pixels):
        region = "all"
        mask = keep
    else:
        region = "covered"
    n = int(mask.sum())
    out = {"pixels": n, "coverage_threshold": coverage, "region": region}
    if n == 0:
        return out, mask
    w = wisp[..., :3][mask].mean(axis=0)
    r = ref[..., :3][mask].mean(axis=0)
    ratio = w / r
    out.update(wisp_mean=w.tolist(), ref_mean=r.tolist(), ratio=ratio.tolist())
    if passes is not None and len(passes) >= 2:
        per_pass = np.array([p[..., :3][mask].mean(axis=0) for p in passes])
        se_ref = per_pass.std(axis=0, ddof=1) / np.sqrt(len(passes))
        out["ref_se"] = se_ref.tolist()
        out["ratio_se"] = (ratio * se_ref / r).tolist()
    out["coverage_ratio"] = float(wisp[..., 3].sum() / max(ref[..., 3].sum(), 1e-12))
    if region == "covered":
        lw = wisp[..., :3][mask] @ LUMA
        lr = ref[..., :3][mask] @ LUMA
        p10w, p10r = np.percentile(lw, 10), np.percentile(lr, 10)
        # At hard-shadowed pixels the path tracer's p10 can be exactly 0: no ratio then.
        out.update(p10_wisp=float(p10w), p10_ref=float(p10r),
                   p10_ratio=float(p10w / p10r) if p10r > 0 else None)
        if passes is not None and len(passes) >= 2:
            shares = block_shares(wisp, ref, passes, coverage=block_coverage, keep=keep)
            if shares is not None:
                out[f"blocks{SHARE_BLOCK}"] = shares
            for k in DARK_BLOCKS:
                d = darkest_tenth(wisp, ref, passes, mask, k)
                if d is not None:
                    out[f"dark10_block{k}"] = d
    return out, mask


def markdown_row(label, fig):
    if "ratio" not in fig:
        return f"| {label} | no pixel covered in both | | | | 0 |"
    ratio = " / ".join(f"{v:.2f}" for v in fig["ratio"])
    se = " / ".join(f"{v:.3f}" for v in fig.get("ratio_se", [float("nan")] * 3))
    p10 = "-" if "p10_wisp" not in fig else (
        f"{fig['p10_ratio']:.2f}" if fig["p10_ratio"] is not None else "PT p10 = 0")
    dark = dark_cell(fig)
    if dark:
        p10 += f"; darkest tenth {dark}"
    return (f"| {label} | {ratio} | {se} | {p10} | {share_cell(fig)} | "
            f"{fig['pixels']} {fig['region']} |")


def side_by_side(mi, wisp, ref, mask, path, block=8):
    lum = ref[..., :3] @ LUMA
    sel = ref[..., 3] > 0.5
    if sel.sum() < 500:
        sel = ref[..., 3] > 0
    # Exposure from the mean (robust to the path tracer's fireflies), the same for both.
    scale = 0.25 / max(lum[sel].mean(), 1e-9) if sel.any() else 1.0
    panels = [np.clip(wisp[..., :3] * scale, 0, 1), np.clip(ref[..., :3] * scale, 0, 1)]
    # Ratio of block sums over the compared pixels: per-pixel ratios are mostly the path
    # tracer's noise; 8 x 8 blocks show where wisp is too dark or too bright.
    m = mask[..., None].astype(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        lr = np.log2(block_sum((wisp[..., :3] * m) @ LUMA, block) / block_sum((ref[..., :3] * m) @ LUMA, block))
    t = np.clip(np.nan_to_num(lr, nan=0.0, posinf=1.0, neginf=-1.0) / 2.0, -1, 1)
    heat = np.ones(t.shape + (3,))
    heat[..., 0] = np.where(t < 0, 1 + t, 1)  # blue when wisp is darker
    heat[..., 1] = 1 - np.abs(t)
    heat[..., 2] = np.where(t > 0, 1 - t, 1)  # red when wisp is brighter
    empty = block_sum(wisp[..., 3] + ref[..., 3], block) <= 0
    heat[(block_sum(mask.astype(float), block) < 0.25 * block * block) | empty] = 0.25
    heat = np.repeat(np.repeat(heat, block, 0), block, 1)
    full = np.full(wisp.shape[:2] + (3,), 0.25)
    full[: heat.shape[0], : heat.shape[1]] = heat
    # The heat map is display-referred: undo the sRGB encoding applied below.
    panels.append(np.where(full <= 0.04045, full / 12.92, ((full + 0.055) / 1.055) ** 2.4))
    gap = np.ones((wisp.shape[0], 4, 3))
    img = np.concatenate([panels[0], gap, panels[1], gap, panels[2]], axis=1).astype(np.float32)
    bmp = mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB)
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("wisp_exr")
    ap.add_argument("ref_exr")
    ap.add_argument("--passes", help="the path tracer's passes (.npy [P, H, W, 4]) for errors")
    ap.add_argument("--coverage", type=float, default=0.99)
    ap.add_argument("--block-coverage", type=float, default=SHARE_COVERAGE,
                    help="a block of the spatial measure counts when its mean alpha is at least "
                    "this in both images")
    ap.add_argument("--region", choices=["auto", "covered", "all"], default="auto",
                    help="compared pixels (see compare()); auto falls back to all below 500 covered pixels")
    ap.add_argument("--crop", type=float, default=1.0,
                    help="compare only the central CROP x CROP of the image, in (0, 1] (default 1: all)")
    ap.add_argument("--png", help="side-by-side image to write")
    ap.add_argument("--label", default="")
    ap.add_argument("--json", help="write the figures here")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    wisp = load_rgba(mi, args.wisp_exr)
    ref = load_rgba(mi, args.ref_exr)
    passes = np.load(args.passes).astype(np.float64) if args.passes else None
    if not 0.0 < args.crop <= 1.0:
        raise SystemExit(f"compare.py: --crop {args.crop}: must lie in (0, 1]")
    fig, mask = compare(wisp, ref, passes, args.coverage, args.region, crop=args.crop,
                        block_coverage=args.block_coverage)
    fig["crop"] = args.crop
    fig["label"] = args.label
    if not np.isfinite(wisp).all():
        print("compare.py: warning: wisp's image has non-finite values", file=sys.stderr)
    if args.json:
        json.dump(fig, open(args.json, "w"), indent=1)
    if args.png:
        side_by_side(mi, wisp, ref, mask, args.png)
    print(markdown_row(args.label, fig))


if __name__ == "__main__":
    main()
