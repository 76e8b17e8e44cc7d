#!/usr/bin/env bash
# A compiler and linker launcher that measures: runs the command under /usr/bin/time and appends
# "<user+sys CPU seconds> <output file>" to $SPLINECAL_CPU_LOG. CPU seconds do not depend on what
# else the machine runs, unlike wall times (docs/reliability.md, "Where the time goes").
#   cmake ... -DCMAKE_CXX_COMPILER_LAUNCHER=$PWD/scripts/cpu_time_launcher.sh \
#             -DCMAKE_CXX_LINKER_LAUNCHER=$PWD/scripts/cpu_time_launcher.sh
#   SPLINECAL_CPU_LOG=/tmp/cpu.log CCACHE_DISABLE=1 cmake --build BUILD -j2
#   sort -rn /tmp/cpu.log | head
set -euo pipefail
log=${SPLINECAL_CPU_LOG:-/dev/null}
output=unknown
previous=
for arg in "$@"; do
  if [[ "$previous" == "-o" ]]; then output=$arg; fi
  previous=$arg
done
times=$(mktemp)
status=0
/usr/bin/time -f '%U %S' -o "$times" "$@" || status=$?
# One line per command; a short append is atomic, so two parallel jobs do not interleave.
tail -n 1 "$times" | awk -v out="$output" '{printf "%.2f %s\n", $1 + $2, out}' >>"$log"
rm -f "$times"
exit "$status"
