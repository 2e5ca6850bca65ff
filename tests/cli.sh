#!/bin/sh
# End-to-end checks of the sphlab command line: every shipped scene checks and
# runs, and the CSV outputs have the documented columns.
set -u
BIN=${1:-./sphlab}
pass=0; fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for scene in lessons/scenes/*.ini; do
    if "$BIN" check "$scene" > "$tmp/check.txt" 2>&1 && grep -q '^ok$' "$tmp/check.txt"; then ok; else bad "check $scene"; cat "$tmp/check.txt"; fi
    if "$BIN" run "$scene" --steps 3 --quiet --stats "$tmp/s.csv" --dump "$tmp/d.csv" 2> "$tmp/err.txt"; then
        lines=$(wc -l < "$tmp/s.csv")
        [ "$lines" -eq 4 ] && ok || bad "$scene: --stats has $lines lines, want header + 3"
        head -1 "$tmp/s.csv" | grep -q '^step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed,external_ms' && ok || bad "$scene: stats header"
        head -1 "$tmp/d.csv" | grep -qx 'id,x,y,z,vx,vy,vz,rho,p' && ok || bad "$scene: dump header"
        n=$("$BIN" check "$scene" | sed -n 's/.* \([0-9][0-9]*\) particles.*/\1/p')
        [ "$(($(wc -l < "$tmp/d.csv") - 1))" -eq "$n" ] && ok || bad "$scene: dump rows != $n particles"
    else
        bad "run $scene"; cat "$tmp/err.txt"
    fi
done

# The hard cases: every verdict must be "pass" (they run headless, a few seconds).
if "$BIN" hardcases --quick > "$tmp/hard.txt" 2>&1; then ok; else bad "hardcases"; cat "$tmp/hard.txt"; fi
grep -q '^hardcases: [0-9]* passed, 0 failed$' "$tmp/hard.txt" && ok || bad "hardcases summary line"

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
