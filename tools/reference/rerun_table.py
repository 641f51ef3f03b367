#!/usr/bin/env python3
"""Re-run wisp on every case of a table that run_table.py made and check issue 14's targets
(not run by CI): a change to the engine measured against the cached path-traced renders in
minutes (about 11 on 2 cores for the dense and curly cases).

usage: rerun_table.py OUTDIR TABLEDIR [--cases dense,curly,isolated] [--kinds single,dual]
                      [-- wisp flags...]

Each case goes through rerun_case.py (WISP, in the environment, is the binary); then one
Markdown table (printed and written to OUTDIR/table.md; every row's compare.py figures in
OUTDIR/results.json) of wisp ÷ path traced per channel, the share of 8 px hair blocks within
1.5× and 2× beside the path tracer's own block noise (compare.py block_shares()), the mean
|ln ratio| per case and kind, and
the targets of issue 14 per row: dense single scattering within 5% and dual within 15% per
channel, isolated fibres within 10%, and the bracket on the darkest tenth (compare.py
darkest_tenth(), 8 px blocks; issue 14 asks for 2×). Example, the figures of ACCURACY.md §2
"Light along a segment":

    WISP=target/release/wisp tools/reference/rerun_table.py /tmp/rt TABLE -- \\
        --contact-mm 120 --segment-pieces 2
"""
import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare  # noqa: E402
COLOURS = {"dense": ["blond", "brown"], "curly": ["red"], "isolated": ["blond"]}
LIGHTS = ["front", "side", "back", "point"]
# Issue 14's targets: per-channel |ratio − 1| bounds, by (case, kind); curly has none.
TARGETS = {("dense", "single"): 0.05, ("dense", "dual"): 0.15,
           ("isolated", "single"): 0.10, ("isolated", "dual"): 0.10}


def main():
    argv = sys.argv[1:]
    flags = []
    if "--" in argv:
        at = argv.index("--")
        argv, flags = argv[:at], argv[at + 1:]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("table")
    ap.add_argument("--cases", default="dense,curly")
    ap.add_argument("--kinds", default="single,dual")
    args = ap.parse_args(argv)
    rows, logs = [], {}
    for kind in args.kinds.split(","):
        for case in args.cases.split(","):
            if case not in COLOURS:
                sys.exit(f"rerun_table.py: --cases: unknown case {case!r} (dense, curly, isolated)")
            for colour in COLOURS[case]:
                for light in LIGHTS:
                    if not os.path.isdir(os.path.join(args.table, case, f"{colour}-{light}-{kind}")):
                        if light != "point":  # a point light is rendered for few cases
                            print(f"skipped: {case} {colour} {light} {kind}: not in {args.table}",
                                  file=sys.stderr)
                        continue
                    p = subprocess.run([sys.executable, os.path.join(HERE, "rerun_case.py"),
                                        args.out, args.table, case, colour, light, kind] + flags,
                                       capture_output=True, text=True)
                    name = f"{case}-{colour}-{light}-{kind}"
                    fig_path = os.path.join(args.out, f"cmp-{name}.json")
                    if p.returncode or not os.path.exists(fig_path):
                        sys.exit(f"rerun_table.py: {name}: {p.stderr.strip() or p.stdout.strip()}")
                    fig = json.load(open(fig_path))
                    fig.update(case=case, colour=colour, light=light, kind=kind, flags=flags)
                    rows.append((case, colour, light, kind, fig["ratio"], fig.get("dark10_block8"),
                                 fig))
                    logs[name] = p.stderr.strip()
    lines = ["| scene | light | kind | wisp ÷ path traced (R / G / B) | target | darkest tenth, 8 px "
             "| 8 px blocks within 1.5 / 2× (path tracer's halves; ceiling) | ≈ corrected |",
             "|---|---|---|---|---|---|---|---|"]
    for case, colour, light, kind, ratio, dark, fig in rows:
        bound = TARGETS.get((case, kind))
        verdict = "" if bound is None else (
            "within" if all(abs(r - 1) <= bound for r in ratio) else "**out**") + \
            (f" ±{round(bound * 100)}%" if bound is not None else "")
        # The bracket of compare.py darkest_tenth(); issue 14 asks for the darkest tenth
        # within 2× (the verdict "no" in bold).
        dark_cell = "-" if dark is None else (
            compare.bracket_text(dark) + " "
            + ("**no**" if dark["within_2x"] == "no" else dark["within_2x"]))
        b = fig.get(f"blocks{compare.SHARE_BLOCK}")
        corrected = "-" if not b else " / ".join(
            "-" if c is None else f"{100 * c:.0f}" for c in b["corrected"]) + "%"
        lines.append(f"| {case} {colour} | {light} | {kind} | "
                     f"{' / '.join(f'{r:.2f}' for r in ratio)} | {verdict} | {dark_cell} | "
                     f"{compare.share_cell(fig)} | {corrected} |")
    lines.append("")
    for case in args.cases.split(","):
        for kind in args.kinds.split(","):
            lns = [abs(math.log(r)) for c, _, _, k, ratio, *_ in rows if c == case and k == kind
                   for r in ratio if r > 0]
            if lns:
                lines.append(f"{case} {kind}: mean |ln ratio| {sum(lns) / len(lns):.3f} "
                             f"over {len(lns)}")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    os.makedirs(args.out, exist_ok=True)
    open(os.path.join(args.out, "table.md"), "w").write(text)
    json.dump([r[-1] for r in rows], open(os.path.join(args.out, "results.json"), "w"), indent=1)
    for name, err in logs.items():
        if err:
            print(f"{name}: {err}", file=sys.stderr)


if __name__ == "__main__":
    main()
