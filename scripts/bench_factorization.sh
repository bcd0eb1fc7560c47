#!/usr/bin/env bash
# Runs `relume bench-factor` (the paper's solver comparison: exact LP in both forms, Huber QP,
# IRLS, on planted low-rank + sparse matrices) and writes its tables into docs/factorization.md
# between the bench-factor markers, together with the command line and the machine it ran on.
#
# Usage: scripts/bench_factorization.sh [RELUME_BINARY] [more bench-factor options...]
#   RELUME_BINARY defaults to build/apps/relume; the JSON records go to $BENCH_JSON
#   (default build/bench_factorization.json).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
relume="${1:-$root/build/apps/relume}"
shift $(( $# > 0 ? 1 : 0 ))
doc="$root/docs/factorization.md"
json="${BENCH_JSON:-$root/build/bench_factorization.json}"
[ -x "$relume" ] || { echo "bench_factorization.sh: no relume binary at $relume" >&2; exit 1; }
grep -q '<!-- bench-factor:begin -->' "$doc" || { echo "bench_factorization.sh: $doc has no bench-factor markers" >&2; exit 1; }

command=(bench-factor --json "$json" "$@")
load_before="$(cut -d' ' -f1-3 /proc/loadavg)"
echo "running: relume ${command[*]}" >&2
tables="$(RELUME_QUIET=1 "$relume" "${command[@]}")"

section="$(mktemp)"
trap 'rm -f "$section" "$doc.tmp"' EXIT
{
  echo '<!-- bench-factor:begin -->'
  echo "Made by \`scripts/bench_factorization.sh\`, which ran \`relume ${command[*]}\`"
  echo "on $(date -u +%Y-%m-%d), $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'))," \
       "load average before the run: $load_before, after: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "$tables"
  echo '<!-- bench-factor:end -->'
} > "$section"
awk -v section="$section" '
  /<!-- bench-factor:begin -->/ { while ((getline line < section) > 0) print line; skipping = 1; next }
  /<!-- bench-factor:end -->/ { skipping = 0; next }
  !skipping { print }
' "$doc" > "$doc.tmp"
mv "$doc.tmp" "$doc"
echo "wrote the tables into $doc and the records into $json" >&2
