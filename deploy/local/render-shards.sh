#!/usr/bin/env bash
# Renders a wisp simulation cache as SHARDS contiguous blocks of frames, in parallel on this
# machine: the local counterpart of the Slurm array (deploy/slurm) and the Kubernetes Indexed
# Job (deploy/k8s). Each shard is one `wisp render --cache CACHE --shard I/SHARDS --out OUT`,
# so the folder ends up with the file names a single `wisp render` writes.
#
#   deploy/local/render-shards.sh SHARDS CACHE OUT [render flags...]
#   deploy/local/render-shards.sh 4 run.wcache frames --light-dir 1,-0.5,-0.3 --width 1920
#
# Environment:
#   WISP         the wisp binary (default: `wisp` on PATH)
#   WISP_RUNNER  parallel | xargs (default: GNU parallel when installed, else xargs -P)
#   WISP_JOBS    shards run at once (default: SHARDS, at most the number of cores)
#   WISP_THREADS worker threads per shard (default: cores / jobs, at least 1); pass threads
#                here, not as --threads among the render flags
# Exit status: 0 when every shard succeeded, 1 when one failed (its message is printed), 2 for
# bad arguments.
set -euo pipefail

usage() {
    echo "usage: $0 SHARDS CACHE OUT [render flags...]" >&2
    exit 2
}
# A whole number >= 1, or exit 2 naming the setting.
whole() {
    case "$2" in
        '' | *[!0-9]* | 0*) echo "$0: $1 must be a whole number >= 1 (got '$2')" >&2; exit 2 ;;
    esac
}
[ "$#" -ge 3 ] || usage
shards=$1
cache=$2
out=$3
shift 3
whole SHARDS "$shards"
wisp=${WISP:-wisp}
if ! command -v "$wisp" >/dev/null 2>&1; then
    echo "$0: cannot run '$wisp' (set WISP to the wisp binary)" >&2
    exit 2
fi
cores=$(nproc 2>/dev/null || echo 1)
jobs=${WISP_JOBS:-$(( shards < cores ? shards : cores ))}
whole WISP_JOBS "$jobs"
threads=${WISP_THREADS:-$(( cores / jobs > 0 ? cores / jobs : 1 ))}
whole WISP_THREADS "$threads"
runner=${WISP_RUNNER:-}
if [ -z "$runner" ]; then
    if command -v parallel >/dev/null 2>&1 && parallel --version 2>/dev/null | grep -q 'GNU parallel'; then
        runner="parallel"
    else
        runner="xargs"
    fi
fi

echo "render-shards: $shards shards of $cache into $out, $jobs at once with $threads threads each ($runner)" >&2
status=0
case "$runner" in
    parallel)
        # -q quotes every argument (flags with spaces survive); the first failure stops the rest.
        seq 1 "$shards" | parallel --will-cite --halt now,fail=1 -j "$jobs" -q \
            "$wisp" --threads "$threads" render --cache "$cache" --out "$out" \
            --shard "{}/$shards" "$@" || status=$?
        ;;
    xargs)
        # xargs runs the command without a shell, so the arguments keep their quoting.
        seq 1 "$shards" | xargs -P "$jobs" -I '{}' \
            "$wisp" --threads "$threads" render --cache "$cache" --out "$out" \
            --shard "{}/$shards" "$@" || status=$?
        ;;
    *)
        echo "$0: WISP_RUNNER must be parallel or xargs (got '$runner')" >&2
        exit 2
        ;;
esac
if [ "$status" -ne 0 ]; then
    echo "render-shards: a shard failed (exit $status from $runner; its message is above)" >&2
    exit 1
fi
echo "render-shards: all $shards shards done" >&2
