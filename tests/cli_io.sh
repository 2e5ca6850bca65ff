#!/bin/sh
# End-to-end checks of the outputs' guarantees (docs/robustness.md, "Outputs"):
# nothing but a regular file is replaced, an input is never overwritten, two
# runs writing one path do not mix, a full disk is an error, and a signal
# leaves no temporary behind; a long run off a terminal still reports.
# Runnable from any directory.
set -u
BIN=${1:-./sphlab}
case $BIN in /*) ;; *) BIN=$(pwd)/$BIN ;; esac
ROOT=$(cd "$(dirname "$0")/.." && pwd)
pass=0; fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# every sphlab call is bounded: a refusal that does not happen must not hang the suite
run() { timeout 120 "$BIN" "$@"; }
scene="$tmp/scene.ini"
cp "$ROOT/lessons/scenes/dam-break-2d.ini" "$scene"
cp "$scene" "$tmp/scene.orig"
leftovers() { find "$1" -name '*.tmp' | head -1; }

# A FIFO and (as root) a private character device: refused, left as they were.
# Checked on private nodes first, so that /dev/null is only tried once they pass.
mkfifo "$tmp/fifo"
nodes_ok=1
for node in fifo dev; do
    if [ "$node" = dev ]; then
        [ "$(id -u)" -eq 0 ] && mknod "$tmp/dev" c 1 3 2>/dev/null || continue
    fi
    kind=$(stat -c %F "$tmp/$node")
    run run "$scene" --steps 2 --quiet --stats "$tmp/$node" > "$tmp/out.txt" 2>&1
    rc=$?
    if [ $rc -eq 1 ] && grep -q "$tmp/$node: .*not a regular file" "$tmp/out.txt" && [ "$(stat -c %F "$tmp/$node")" = "$kind" ]
    then ok; else bad "--stats on a $kind: want exit 1, the reason, the node intact (exit $rc, now $(stat -c %F "$tmp/$node"))"; cat "$tmp/out.txt"; nodes_ok=0; fi
done
if [ $nodes_ok -eq 1 ]; then
    run run "$scene" --steps 2 --quiet --dump /dev/null > "$tmp/out.txt" 2>&1
    rc=$?
    [ $rc -eq 1 ] && [ "$(stat -c %F /dev/null)" = "character special file" ] && ok ||
        { bad "--dump /dev/null: want exit 1 and /dev/null intact (exit $rc, $(stat -c %F /dev/null))"; cat "$tmp/out.txt"; }
fi
[ -z "$(leftovers "$tmp")" ] && ok || bad "refusals left $(leftovers "$tmp")"

# An output that is the scene itself, under the same or another spelling: refused, the scene unchanged.
for spelling in "$scene" "$tmp/./scene.ini"; do
    run run "$scene" --steps 2 --quiet --stats "$spelling" > "$tmp/out.txt" 2>&1
    rc=$?
    [ $rc -eq 1 ] && grep -q "input" "$tmp/out.txt" && cmp -s "$scene" "$tmp/scene.orig" && ok ||
        { bad "--stats $spelling (the scene): want exit 1 and the scene unchanged (exit $rc)"; cat "$tmp/out.txt"; cp "$tmp/scene.orig" "$scene"; }
done
(cd "$tmp" && run run scene.ini --steps 2 --quiet --dump ./scene.ini) > "$tmp/out.txt" 2>&1
rc=$?
[ $rc -eq 1 ] && cmp -s "$scene" "$tmp/scene.orig" && ok ||
    { bad "--dump ./scene.ini from the scene's folder: want exit 1 and the scene unchanged (exit $rc)"; cat "$tmp/out.txt"; cp "$tmp/scene.orig" "$scene"; }

# Two runs writing one --stats path at once: each has its own temporary, so
# the file that stays is one run's, whole (header, then steps 1, 2, ... in order).
run run "$scene" --steps 400 --threads 1 --quiet --stats "$tmp/same.csv" 2> "$tmp/a.txt" & a=$!
run run "$scene" --steps 300 --threads 1 --quiet --stats "$tmp/same.csv" 2> "$tmp/b.txt" & b=$!
wait $a; ra=$?
wait $b; rb=$?
if [ $ra -eq 0 ] && [ $rb -eq 0 ] &&
   awk -F, 'NR == 1 { if ($1 != "step") exit 1; next } { if ($1 != NR - 1 || NF != n && n) exit 1; n = NF }
            END { exit !(NR == 301 || NR == 401) }' "$tmp/same.csv"; then ok
else bad "two runs on one --stats path: exits $ra $rb, the file mixed ($(wc -l < "$tmp/same.csv") lines)"; cat "$tmp/a.txt" "$tmp/b.txt"; fi
[ -z "$(leftovers "$tmp")" ] && ok || bad "two runs left $(leftovers "$tmp")"

# A full disk (a file size limit of 1 block, SIGXFSZ ignored so writes fail
# with EFBIG): render exits non-zero and leaves no empty or partial PNG.
(ulimit -f 1; trap '' XFSZ; run render "$scene" --steps 2 --every 1 --size 200x150 --quiet --out "$tmp/full") > "$tmp/out.txt" 2>&1
rc=$?
bad_png=$(find "$tmp/full" -name '*.png' 2>/dev/null | head -1)
[ $rc -ne 0 ] && [ -z "$bad_png" ] && grep -q "frame_00000.png" "$tmp/out.txt" && ok ||
    { bad "render on a full disk: want a non-zero exit naming the frame and no PNG left (exit $rc, left '$bad_png')"; cat "$tmp/out.txt"; }
(ulimit -f 1; trap '' XFSZ; run run "$scene" --steps 50 --quiet --stats "$tmp/full.csv") > "$tmp/out.txt" 2>&1
rc=$?
[ $rc -eq 1 ] && [ ! -e "$tmp/full.csv" ] && ok || { bad "--stats on a full disk: want exit 1, no file (exit $rc)"; cat "$tmp/out.txt"; }
[ -z "$(leftovers "$tmp")" ] && ok || bad "full disk left $(leftovers "$tmp")"

# SIGTERM during a run: the temporaries are removed, the run says so and dies by the signal.
"$BIN" run "$scene" --steps 2000000000 --threads 1 --quiet --stats "$tmp/term.csv" --dump "$tmp/term-d.csv" 2> "$tmp/term.txt" & pid=$!
i=0
while [ $i -lt 100 ] && [ -z "$(leftovers "$tmp")" ]; do sleep 0.1; i=$((i + 1)); done
kill -TERM $pid 2>/dev/null
wait $pid 2>/dev/null; rc=$?
left=$(leftovers "$tmp")
[ $i -lt 100 ] && [ -z "$left" ] && [ ! -e "$tmp/term.csv" ] && grep -q "interrupted; partial outputs removed" "$tmp/term.txt" && ok ||
    { bad "SIGTERM: want the temporaries removed and a message (exit $rc, left '$left')"; cat "$tmp/term.txt"; }

# Off a terminal a long run still reports: a progress line at a steady rate
# (SPHLAB_PROGRESS_MS shortens the 10 s between lines for the test).
# The run is stopped once two lines have come (or after 60 s): a slow or busy
# machine takes longer to start, it does not fail the check.
SPHLAB_PROGRESS_MS=200 timeout 60 "$BIN" run "$scene" --steps 2000000000 --threads 1 > /dev/null 2> "$tmp/prog.txt" &
pid=$!
for i in $(seq 1 600); do
    n=$(grep -c '^sphlab run: step [0-9][0-9]*, t = .* s' "$tmp/prog.txt")
    [ "$n" -ge 2 ] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
done
kill -TERM $pid 2>/dev/null
wait $pid 2>/dev/null
n=$(grep -c '^sphlab run: step [0-9][0-9]*, t = .* s' "$tmp/prog.txt")
[ "$n" -ge 2 ] && ok || { bad "run off a terminal: want progress lines, got $n"; cat "$tmp/prog.txt"; }
# A run that needs an absurd number of steps says so at once.
timeout 5 "$BIN" run "$scene" --time 1e6 --set time.dt=1e-7 --threads 1 --quiet > /dev/null 2> "$tmp/many.txt"
grep -q 'takes about [0-9.e+]* steps' "$tmp/many.txt" && ok || { bad "--time 1e6 with dt 1e-7: want 'takes about N steps' at once"; cat "$tmp/many.txt"; }

echo "cli_io.sh: $pass passed, $fail failed"
[ $fail -eq 0 ]
