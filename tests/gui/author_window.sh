#!/bin/sh
# `tactile author` in a real window under Xvfb, driven by real input events (xdotool through the
# XTEST extension: key presses and a mouse click as a person's): pin A, change the method, switch
# A and B by key and by mouse, audition into the emulated device, save, close; then the saved
# experiment, run by `tactile experiment`, must give the saved movies byte for byte (both with
# the same SOURCE_DATE_EPOCH, the files' only time). Also --screenshot and bad command lines.
# Usage: author_window.sh TACTILE WORK_DIR
set -eu
tactile=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export SOURCE_DATE_EPOCH=1700000000

fail() {
  echo "FAIL: $*"
  [ -f run.log ] && sed 's/^/  run.log: /' run.log
  exit 1
}
# Waits up to 60 s for $2 lines of run.log matching $1.
wait_count() {
  i=0
  until [ "$(grep -Ec "$1" run.log)" -ge "$2" ]; do
    i=$((i + 1))
    [ $i -gt 600 ] && fail "fewer than $2 lines matching '$1' within 60 s"
    kill -0 "$pid" 2>/dev/null || fail "the window closed before $2 lines matching '$1'"
    sleep 0.1
  done
}
# Waits up to 60 s for a line of run.log matching the extended regular expression $1.
wait_for() {
  wait_count "$1" 1
}

# Waits for the window of the program started last ($pid) and gives it the keyboard's focus.
# A window is found by its name as soon as it exists, before it is mapped, and focusing an
# unmapped window is an X error (BadMatch): wait until it is visible, and try again a while.
focus_window() {
  wid=$(timeout 30 xdotool search --sync --onlyvisible --name "tactile author" | head -1)
  [ -n "$wid" ] || fail "no visible window named 'tactile author'"
  for _ in $(seq 50); do
    timeout 2 xdotool windowfocus --sync "$wid" 2>/dev/null && return 0
    sleep 0.1
  done
  fail "the window $wid did not take the keyboard's focus in 5 s"
}

"$tactile" demo --headless --frames 60 --out demo >demo.log 2>&1 || fail "demo failed"

# Bad command lines: usage errors (exit 2) naming the problem, before any window.
set +e
timeout 20 "$tactile" author demo/strain.h5 --method sideways >bad.log 2>&1
[ $? -eq 2 ] && grep -q "sideways" bad.log || fail "an unknown method is not a usage error"
timeout 20 "$tactile" author demo/strain.h5 --gain 0 >bad.log 2>&1
[ $? -eq 2 ] && grep -q "gain" bad.log || fail "gain 0 is not a usage error"
timeout 20 "$tactile" author demo/strain.h5 --name "../x" >bad.log 2>&1
[ $? -eq 2 ] && grep -q "plain name" bad.log || fail "a name with a path is not refused"
timeout 20 "$tactile" author demo/strain.h5 --out demo/strain.h5 >bad.log 2>&1
[ $? -ne 0 ] && grep -q "would write over the input" bad.log || fail "saving into the input was not refused"
timeout 20 "$tactile" author demo/nothing.h5 >bad.log 2>&1
[ $? -eq 2 ] || fail "a missing strain file is not a usage error"
set -e

# --screenshot: the window drawn once the mapping is made.
"$tactile" author demo/strain.h5 --screenshot shot.png --out shots >shot.log 2>&1 ||
  fail "--screenshot failed: $(cat shot.log)"
grep -q "mapped #1 (stress integrated" shot.log || fail "the screenshot's mapping is not reported"
[ -s shot.png ] || fail "no screenshot"
[ ! -e shots ] || fail "a screenshot saved a mapping nobody asked to save"
# What it must show, read with Debian's matplotlib (setup.sh): at the default 1400 x 860, the
# strain field's pane (x 340-870) mostly its dark blue background with edges over it, the array's
# pane (x 870-1400) grey with white contactors (the demo's strain is small: few are coloured).
/usr/bin/python3 - shot.png <<'PY' || fail "the screenshot does not show the panes"
import sys
import matplotlib.image as image
import numpy as np
img = (image.imread(sys.argv[1])[:, :, :3] * 255).round().astype(int)
assert img.shape == (860, 1400, 3), img.shape
field, array = img[28:686, 340:870], img[28:686, 870:1400]
background = np.all(field == [20, 40, 70], axis=2).mean()
edges = np.all(field > 100, axis=2).mean()
white = np.all(array > 240, axis=2).mean()
assert 0.5 < background < 0.99 and edges > 0.005, (background, edges)
assert white > 0.02, white
PY

"$tactile" author demo/strain.h5 --out saved --name ab >run.log 2>&1 &
pid=$!
focus_window
wait_for "mapped #1 \(stress integrated"
xdotool key p
wait_for "pinned A: stress integrated"
xdotool key m
wait_for "mapped #2 \(stress proportional"
xdotool key Tab
wait_for "showing A"
# The mouse: the panel's "Show B (Tab)" button, where the default window size puts it.
xdotool mousemove --window "$wid" 150 384 click 1
wait_for "showing B"
xdotool key Return
wait_for "audition of B"
wait_count "outputs ended at most" 1
# A's audition: the emulated device's output must differ from B's (another method). The
# switches are counted: each waits for its own line, not an earlier one.
xdotool key Tab
wait_count "showing A" 2
xdotool key Return
wait_for "audition of A"
wait_count "outputs ended at most" 2
# A switch and an audition in one burst (both keys can land in one frame): the audition must
# play what the switch chose, B, and so give B's output again.
xdotool key --delay 0 Tab Return
wait_count "showing B" 2
wait_count "audition of B" 2
wait_count "outputs ended at most" 3
xdotool key s
wait_for "saved saved/ab.json"
xdotool key q
wait "$pid" || fail "the window exited with an error"

grep -Eq "audition 1: played on the emulated device \(headless\): [1-9][0-9]* frames played, 0 underruns" run.log ||
  fail "the audition did not play whole on the emulated device"
grep -Eq "audition 2: played on the emulated device \(headless\): [1-9][0-9]* frames played, 0 underruns" run.log ||
  fail "A's audition did not play whole"
outputs=$(grep "audition: deflection  peak" run.log | sort -u | wc -l)
[ "$outputs" -eq 2 ] || fail "A's and B's auditions gave the same device output (or none)"
[ "$(grep "audition: deflection  peak" run.log | sed -n 1p)" = "$(grep "audition: deflection  peak" run.log | sed -n 3p)" ] ||
  fail "the audition after a switch to B in the same burst did not play B"
[ "$(ls saved/movies/*.h5 | wc -l)" -eq 2 ] || fail "not two movies saved (A and B)"
ls saved/movies/*proportional*.h5 >/dev/null || fail "B's movie (proportional) not saved"
[ -s saved/movies/$(basename "$(ls saved/movies/*proportional*.h5)" .h5).hjif ] ||
  fail "B's HJIF not saved"

"$tactile" experiment saved/ab.json --out rerun >rerun.log 2>&1 || fail "the saved experiment does not run: $(cat rerun.log)"
for movie in saved/movies/*.h5; do
  cmp "$movie" "rerun/movies/$(basename "$movie")" ||
    fail "$(basename "$movie"): the experiment's movie differs from the window's"
done
# --experiment: the saved file opens on its mappings again (A integrated, current proportional).
"$tactile" author demo/strain.h5 --experiment saved/ab.json --screenshot reopened.png --out reopened >reopen.log 2>&1 ||
  fail "--experiment failed: $(cat reopen.log)"
grep -q "A mapped (stress integrated" reopen.log || fail "--experiment did not restore A: $(cat reopen.log)"
grep -q "mapped #1 (stress proportional" reopen.log || fail "--experiment did not restore B: $(cat reopen.log)"

# Audition on a Latero: the emulated Latero of `tactile emulate` on a free loopback port.
mv run.log run-ab.log
"$tactile" emulate --latero --port 0 --seconds 60 >latero.log 2>&1 &
lpid=$!
i=0
until grep -q "answering on 127.0.0.1:" latero.log; do
  i=$((i + 1))
  [ $i -gt 100 ] && fail "the emulated Latero did not start: $(cat latero.log)"
  sleep 0.1
done
address=$(sed -n 's/.*answering on \(127\.0\.0\.1:[0-9]*\).*/\1/p' latero.log | head -1)
"$tactile" author demo/strain.h5 --layout latero --latero "$address" --blade-centre-raw 100 \
  --out lat >run.log 2>&1 &
pid=$!
focus_window
wait_for "mapped #1 \(latero integrated"
xdotool key Return
wait_for "audition of B"
wait_for "audition: play: .*Latero"
wait_for "audition: .*missed"
# Looped (a Latero plays in real time: 100 loops last minutes), stopped by Enter again: the
# blades ramp back to rest.
xdotool key o Return
wait_for "audition of B from .*, looped"
sleep 1
xdotool key Return
wait_count "audition: .*missed" 2
xdotool key q
wait "$pid" || fail "the window (Latero) exited with an error"
# SIGTERM: a job started with & in a script ignores SIGINT. The emulator prints its counters.
kill -TERM "$lpid"
wait "$lpid" || true
grep -Eq "audition 1: played on a Latero" run.log || fail "the audition did not play on the Latero"
grep -Eq "audition 2: stopped on a Latero" run.log || fail "the looped audition was not stopped"
blades=$(sed -n 's/.*blades *left at raw \([0-9]*\)\.\.\([0-9]*\).*/\1 \2/p' latero.log | head -1)
[ "$blades" = "100 100" ] ||
  fail "the Latero's blades were not left at rest (raw 100) after the stop: $(cat latero.log)"
full=$(sed -n 's/.*received: \([0-9]*\) FULL.*/\1/p' latero.log | head -1)
[ -n "$full" ] && [ "$full" -gt 0 ] || fail "the emulated Latero counted no frames: $(cat latero.log)"

echo "author window: pin, method, A/B by key and mouse, auditions of A and B differ on the emulated device, save, reopen, audition on an emulated Latero ($full frames); experiment reproduces $(ls saved/movies/*.h5 | wc -l) movies byte for byte"
