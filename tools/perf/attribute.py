#!/usr/bin/env python3
"""Where a `perf record` of wisp spends its time, by wisp function, inlining undone.

`perf report` names the symbol a sample's address lies in. In a release build most of
wisp's parallel work is closures inlined into rayon's and core's generic functions, so
`perf report` shows `Map<I,F>::fold`, `FnMut::call_mut` or `ForEachConsumer::consume_iter`
at 10-20% each, several different closures under one name. This script resolves each
sampled address through the binary's debug information with `addr2line -i`, which lists
the inlined frames at that address, and charges the sample to:

- by function: the outermost frame that is wisp's own code (a closure's enclosing
  function, e.g. `SurfaceShadow::build::{{closure}}`), or, with `--innermost`, the
  innermost one;
- by line (`--lines FUNCTION`): the innermost wisp source line, among the samples whose
  outermost wisp frame's name contains FUNCTION.

Needs `perf` and binutils' `addr2line` and `readelf`, and a binary with debug information
(the profiling profile: `cargo build --profile profiling`, the release build with line tables,
binaries in `target/profiling/`; `Cargo.toml`). No frame pointers
or call graphs are needed: the inlining is read from the debug information, so plain
`perf record -F 2000` is enough.

    cargo build --profile profiling
    perf record -e cpu-clock -F 2000 -o /tmp/frame.data \\
        target/profiling/wisp bench --frames 40 --threads-list 2 --parts scaling
    python3 tools/perf/attribute.py /tmp/frame.data target/profiling/wisp
    python3 tools/perf/attribute.py /tmp/frame.data target/profiling/wisp --lines emit
"""

import argparse
import collections
import os
import re
import subprocess
import sys


def run(cmd):
    """A command's standard output; a missing tool or a failure is reported and exits."""
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, check=True)
    except FileNotFoundError:
        sys.exit(f"attribute.py: {cmd[0]} not found (install linux-perf / binutils)")
    except subprocess.CalledProcessError as e:
        sys.exit(f"attribute.py: {' '.join(cmd[:3])} failed: {e.stderr.strip()[:300]}")
    return done.stdout


def load_bias(data, binary):
    """What to add to a sampled address of `binary` to get its address in the file: from
    the recording's mmap of its executable segment and the segment's own header."""
    name = os.path.basename(binary)
    mapping = None
    for line in run(["perf", "script", "-i", data, "--show-mmap-events"]).splitlines():
        if "MMAP" in line and "r-xp" in line and line.rstrip().endswith("/" + name):
            m = re.search(r"\[0x([0-9a-f]+)\(0x[0-9a-f]+\) @ 0x([0-9a-f]+)", line)
            if m:
                mapping = (int(m.group(1), 16), int(m.group(2), 16))
                break
    if mapping is None:
        sys.exit(f"attribute.py: {data} has no executable mapping of {name}")
    for line in run(["readelf", "-lW", binary]).splitlines():
        f = line.split()
        if f and f[0] == "LOAD" and "E" in f[6:8]:
            # file address = runtime − map start + file offset + (vaddr − offset)
            return -mapping[0] + mapping[1] + int(f[2], 16) - int(f[1], 16)
    sys.exit(f"attribute.py: {binary} has no executable LOAD segment")


def check_build_id(data, binary):
    """Exits unless `binary` is the build `data` recorded: addresses of another build of
    the same name would be charged to the wrong code without any sign of it."""
    name = os.path.basename(binary)
    recorded = None
    for line in run(["perf", "buildid-list", "-i", data]).splitlines():
        f = line.split(maxsplit=1)
        if len(f) == 2 and f[1].endswith("/" + name):
            recorded = f[0]
    note = re.search(r"Build ID: ([0-9a-f]+)", run(["readelf", "-n", binary]))
    if recorded and note and note.group(1) != recorded:
        sys.exit(f"attribute.py: {binary} is not the build {data} recorded (build id "
                 f"{note.group(1)[:12]}… against {recorded[:12]}…): rebuilt since?")


def samples(data, binary):
    """Samples per file address in `binary`, and the recording's total sample count."""
    name = os.path.basename(binary)
    bias = load_bias(data, binary)
    counts = collections.Counter()
    total = 0
    for line in run(["perf", "script", "-i", data, "-F", "ip,dso"]).splitlines():
        f = line.split()
        if len(f) < 2:
            continue
        total += 1
        if f[1].strip("()").endswith("/" + name):
            counts[int(f[0], 16) + bias] += 1
    return counts, total


def inline_chains(binary, addresses):
    """Per address, its frames innermost first, as (function, file:line) pairs."""
    chains = {}
    addresses = list(addresses)
    for start in range(0, len(addresses), 2000):
        batch = addresses[start:start + 2000]
        out = run(["addr2line", "-a", "-i", "-f", "-C", "-e", binary] + [hex(a) for a in batch])
        current, lines = None, []
        for line in out.splitlines() + ["0x0"]:
            if re.fullmatch(r"0x[0-9a-f]+", line):
                if current is not None:
                    chains[current] = list(zip(lines[0::2], lines[1::2]))
                current, lines = int(line, 16), []
            else:
                lines.append(line)
    return chains


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("data", help="perf.data from `perf record`")
    ap.add_argument("binary", help="the profiled binary (with debug information)")
    ap.add_argument("--top", type=int, default=30, help="rows to print (default 30)")
    ap.add_argument("--innermost", action="store_true",
                    help="charge each sample to its innermost wisp function")
    ap.add_argument("--lines", metavar="FUNCTION",
                    help="per source line, within the functions whose name contains this")
    ap.add_argument("--src", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                  "..", "..", "src"),
                    help="wisp's source directory (default: this checkout's src)")
    args = ap.parse_args()
    if not os.path.isfile(args.data):
        sys.exit(f"attribute.py: {args.data}: no such file")
    if not os.path.isfile(args.binary):
        sys.exit(f"attribute.py: {args.binary}: no such file")
    src = os.path.realpath(args.src) + os.sep
    check_build_id(args.data, args.binary)
    counts, total = samples(args.data, args.binary)
    if total == 0:
        sys.exit(f"attribute.py: {args.data} holds no samples")
    chains = inline_chains(args.binary, counts)
    by = collections.Counter()
    for address, n in counts.items():
        frames = chains.get(address, [])
        own = [(fn, loc) for fn, loc in frames if loc.startswith(src)]
        if not own:
            if args.lines:
                continue
            outer = frames[-1][0] if frames else "??"
            by[f"(not wisp's) {outer[:70]}"] += n
            continue
        if args.lines:
            if args.lines in own[-1][0]:
                by[own[0][1].split(" ")[0][len(src):]] += n
            continue
        fn = own[0][0] if args.innermost else own[-1][0]
        by[fn] += n
    outside = total - sum(counts.values())
    if args.lines:
        chosen = sum(by.values())
        print(f"{chosen} of {total} samples in functions matching {args.lines!r}; share of those:")
        for key, n in by.most_common(args.top):
            print(f"{100 * n / max(chosen, 1):6.1f}%  {key}")
        return
    print(f"{total} samples; {outside} ({100 * outside / total:.1f}%) outside the binary "
          "(kernel, libm, libc); share of all samples:")
    for key, n in by.most_common(args.top):
        print(f"{100 * n / total:6.2f}%  {key}")


if __name__ == "__main__":
    main()
