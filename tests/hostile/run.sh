#!/usr/bin/env bash
# Hostile-input run of the `tactile` command line: several hundred bad inputs across every
# command, as a careless or hostile user would type them. NOT run by CI (it needs root for the
# tmpfs mounts, takes minutes and its verdicts are heuristics): it is a tool for people, to
# look for crashes, hangs, data loss and silent acceptance of nonsense after a change.
#
#   bash tests/hostile/run.sh PATH/TO/tactile SCRATCH_DIR [FILTER]
#
# Prints one line per case: FAMILY | COMMAND | OK, or BAD and what happened; the totals at the
# end. FILTER (a regex) runs only the families it matches. Sends nothing over the network but to
# 127.0.0.1. The scratch folder is emptied first.
#
# A case is BAD when the program crashes (a signal, a sanitizer report), hangs (timeout),
# succeeds on nonsense, exits with the wrong code (2 for usage, 1 for failed work), prints a
# library's raw message (HDF5, OpenCV, std::), names neither the file nor the option, changes
# a file it should have left alone, or leaves a temporary file behind.

set -u
B=$(realpath "${1:?usage: run.sh TACTILE SCRATCH [FILTER]}")
S=${2:?usage: run.sh TACTILE SCRATCH [FILTER]}
FILTER=${3:-.}
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
DATA=$REPO/tests/data
PY=/usr/bin/python3
H5ATTR="$PY $HERE/h5attr.py"

rm -rf "$S"
mkdir -p "$S"
S=$(realpath "$S")
F=$S/fixtures
W=$S/work
mkdir -p "$F" "$W"
TOTAL=0
OKS=0
BADS=0
MOUNTS=()

cleanup() {
  for m in "${MOUNTS[@]}"; do umount "$m" 2>/dev/null; done
}
trap cleanup EXIT

say() {  # family command verdict [detail]
  TOTAL=$((TOTAL + 1))
  if [ "$3" = OK ]; then
    OKS=$((OKS + 1))
    printf '%s | %s | OK\n' "$1" "$2"
  else
    BADS=$((BADS + 1))
    printf '%s | %s | BAD: %s\n' "$1" "$2" "$4"
  fi
}

# Words that say a library's message reached the user raw, or the program crashed.
RAW='HDF5-DIAG|H5[A-Z][a-z]*[A-Z]|OpenCV\(|cv::|std::|bad_alloc|basic_string|terminate called|what\(\)|AddressSanitizer|LeakSanitizer|runtime error:|Assertion|nlohmann|json\.exception|stoi|stod|Segmentation|core dumped|libpng error'

# sha256 of a file, or "none".
sum_of() { if [ -f "$1" ]; then sha256sum "$1" | cut -d' ' -f1; else echo none; fi; }

# Temporary files of the project's atomic writes (.NAME.XXXXXXXXXXXXXXXX.tmp) and of older
# schemes (.partial), anywhere under a folder.
temps_in() { find "$1" -maxdepth 2 \( -name '.*.tmp' -o -name '*.partial' -o -name '*.tmp' \) -not -path '*/plant/*' 2>/dev/null; }

# check FAMILY EXPECT [-m WORD]... [-k FILE]... [-d DIR]... [-n PATH]... [-t SECS] -- ARGS...
#   EXPECT: usage (exit 2), fail (exit 1), err (1 or 2), ok (exit 0)
#   -m WORD  stderr+stdout must contain WORD (case-insensitive; any of the -m words)
#   -k FILE  FILE keeps its bytes     -n PATH  PATH (removed first) must not exist afterwards
#   -d DIR   no temporary file left in DIR   -t SECS  timeout (default 60)
check() {
  local family=$1 expect=$2
  shift 2
  local words=() keep=() dirs=() absent=() secs=60
  while [ "$1" != -- ]; do
    case $1 in
      -m) words+=("$2") ;;
      -k) keep+=("$2") ;;
      -d) dirs+=("$2") ;;
      -n) absent+=("$2") ;;
      -t) secs=$2 ;;
    esac
    shift 2
  done
  shift
  [[ $family =~ $FILTER ]] || return 0
  local label="tactile $*${NOTE:+ ($NOTE)}"
  label=${label//$S\//}
  label=${label//$REPO\//}
  local before=() f
  for f in "${keep[@]}"; do before+=("$(sum_of "$f")"); done
  for f in "${absent[@]}"; do rm -rf "$f"; done
  local out=$W/out.txt
  (cd "$W" && timeout -k 5 "$secs" "$B" "$@" >"$out" 2>&1 </dev/null)
  local rc=$?
  local problem=""
  if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    problem="hang (killed after ${secs}s)"
  elif [ $rc -ge 128 ]; then
    problem="crash: exit $rc"
  elif grep -Eq "$RAW" "$out"; then
    problem="raw/crash message: $(grep -Em1 "$RAW" "$out" | cut -c1-160)"
  else
    case $expect in
      usage) [ $rc -eq 2 ] || problem="exit $rc, want 2" ;;
      fail) [ $rc -eq 1 ] || problem="exit $rc, want 1" ;;
      err) { [ $rc -eq 1 ] || [ $rc -eq 2 ]; } || problem="exit $rc, want 1 or 2" ;;
      ok) [ $rc -eq 0 ] || problem="exit $rc, want 0" ;;
    esac
    if [ -z "$problem" ] && [ $rc -ne 0 ] && [ ${#words[@]} -gt 0 ]; then
      local hit=0 w
      for w in "${words[@]}"; do grep -qiF -- "$w" "$out" && hit=1; done
      [ $hit = 1 ] || problem="message names none of: ${words[*]}"
    fi
  fi
  local i=0
  for f in "${keep[@]}"; do
    [ "$(sum_of "$f")" = "${before[$i]}" ] || problem="${problem:+$problem; }${f#$S/} changed"
    i=$((i + 1))
  done
  for f in "${absent[@]}"; do
    [ -e "$f" ] && problem="${problem:+$problem; }${f#$S/} written"
  done
  local d
  for d in "${dirs[@]}"; do
    local t
    t=$(temps_in "$d")
    [ -n "$t" ] && problem="${problem:+$problem; }temporary left: ${t//$S\//}"
  done
  if [ -n "$problem" ]; then
    problem="$problem [$(grep -v '^\s*$' "$out" | tail -1 | cut -c1-200)]"
    say "$family" "$label" BAD "$problem"
  else
    say "$family" "$label" OK
  fi
}

# A signal at a moment of a long command: exit 130/143 (or 0 if it had finished), no temporary
# file left in DIR, every FILE intact or (if the run had finished) readable by `info`.
# sigcase FAMILY SIGNAL DELAY DIR KEEPFILE -- ARGS...
sigcase() {
  local family=$1 sig=$2 delay=$3 dir=$4 keepf=$5
  shift 6
  [[ $family =~ $FILTER ]] || return 0
  local label="tactile $* <- SIG$sig at ${delay}s"
  label=${label//$S\//}
  local before
  before=$(sum_of "$keepf")
  # A terminal's Ctrl-C reaches a foreground process whose SIGINT is not ignored; a background
  # job of a script starts with SIGINT ignored, so reset it before exec. Not with a Python
  # wrapper: a SIGINT early enough reached Python itself, whose KeyboardInterrupt exited 1 before
  # `tactile` ran; env installs no handler of its own.
  (cd "$W" && exec env --default-signal=INT "$B" "$@" >"$W/sig.txt" 2>&1 </dev/null) &
  local pid=$!
  sleep "$delay"
  kill -"$sig" $pid 2>/dev/null
  local waited=0
  while kill -0 $pid 2>/dev/null && [ $waited -lt 200 ]; do sleep 0.1; waited=$((waited + 1)); done
  local problem=""
  if kill -0 $pid 2>/dev/null; then
    kill -KILL $pid
    problem="did not stop within 20 s"
  fi
  wait $pid
  local rc=$?
  local want=130
  [ "$sig" = TERM ] && want=143
  if [ -z "$problem" ] && [ $rc -ne $want ] && [ $rc -ne 0 ]; then problem="exit $rc, want $want"; fi
  grep -Eq "$RAW" "$W/sig.txt" && problem="${problem:+$problem; }raw message: $(grep -Em1 "$RAW" "$W/sig.txt" | cut -c1-120)"
  local t
  t=$(temps_in "$dir")
  [ -n "$t" ] && problem="${problem:+$problem; }temporary left: ${t//$S\//}"
  if [ $rc -ne 0 ] && [ "$(sum_of "$keepf")" != "$before" ]; then
    problem="${problem:+$problem; }old output changed"
  fi
  if [ -n "$problem" ]; then say "$family" "$label" BAD "$problem"; else say "$family" "$label" OK; fi
}

mount_tmpfs() {  # DIR SIZE [ro]
  mkdir -p "$1"
  mount -t tmpfs -o "size=$2${3:+,$3}" tmpfs "$1" && MOUNTS+=("$1")
}

############################################################################## fixtures
echo "# fixtures in $F" >&2
"$B" demo --headless --frames 40 --keep --out "$F/demo" >"$F/demo.log" 2>&1 || {
  echo "cannot make the fixtures: tactile demo failed" >&2
  exit 1
}
STRAIN=$F/demo/strain.h5
MOVIE=$F/demo/movie.h5
CALIB=$F/demo/calibration.json
FRAMES=$F/demo/frames
DOTS=$F/demo/frames/calibration/dot_grid.png
REC=$DATA/biotac-materials
LABELS=$REC/labels.csv
PRINTS=$DATA/polyu-hrf-pores
LAYOUT=$REPO/tools/experiments/layouts/lab-6x12.json
"$B" export "$MOVIE" --hjif "$F/m.hjif" >/dev/null 2>&1
"$B" classify train --recordings "$REC" --labels "$LABELS" --out "$F/model.json" >/dev/null 2>&1
# A longer movie for the signal cases: 20 s at 700 Hz.
"$B" demo --headless --frames 1200 --out "$F/long" >/dev/null 2>&1
LONG=$F/long/movie.h5
"$B" map "$F/long/strain.h5" --layout latero --out "$F/latero.h5" >/dev/null 2>&1
LATERO_MOVIE=$F/latero.h5
LONGSTRAIN=$F/long/strain.h5
printf 'not an hdf5 file\n' >"$F/text.h5"
: >"$F/empty.h5"
head -c 4096 "$MOVIE" >"$F/cut-movie.h5"
head -c 2000 "$STRAIN" >"$F/cut-strain.h5"
head -c 100000 /dev/urandom >"$F/random.h5"
{ printf '\x89HDF\r\n\x1a\n'; head -c 5000 /dev/urandom; } >"$F/hdfsig.h5"
cp "$MOVIE" "$F/scrambled-movie.h5"
$PY - "$F/scrambled-movie.h5" <<'EOF'
import random, sys
p = sys.argv[1]; b = bytearray(open(p, 'rb').read()); r = random.Random(5)
for _ in range(40): b[r.randrange(2048, len(b))] = r.randrange(256)
open(p, 'wb').write(b)
EOF
mkdir -p "$F/dir.h5"

# Bad files of every kind, each readers' family.
BADFILES=("$F/text.h5" "$F/empty.h5" "$F/cut-movie.h5" "$F/cut-strain.h5" "$F/random.h5" "$F/hdfsig.h5" "$F/dir.h5" "$F/missing.h5" "$CALIB" "/dev/null")

############################################################################## movie readers
for f in "${BADFILES[@]}" "$F/scrambled-movie.h5"; do
  for cmd in info play export view; do
    extra=()
    [ $cmd = play ] && extra=(--headless --preview "$W/p.png")
    [ $cmd = export ] && extra=(--hjif "$W/x.hjif")
    [ $cmd = view ] && extra=(--screenshot "$W/v.png")
    check "bad-movie-file" err -m "$(basename "$f")" -d "$W" -- $cmd "$f" "${extra[@]}"
  done
  check "bad-strain-file" err -m "$(basename "$f")" -n "$W/o.h5" -d "$W" -- map "$f" --out "$W/o.h5"
  check "bad-strain-file" err -m "$(basename "$f")" -d "$W" -- view "$MOVIE" --strain "$f" --screenshot "$W/v.png"
done
check "bad-strain-file" err -m strain -- map "$MOVIE" --out "$W/o.h5"
check "bad-movie-file" err -m movie -- play "$STRAIN" --headless --preview "$W/p.png"
check "bad-movie-file" err -m movie -- export "$STRAIN" --wav "$W/x.wav"

# Attributes of a movie set to nonsense.
for attr in rate_hz layout_pitch_x_mm layout_deflection_max_um layout_max_rate_hz layout_contactor_width_mm; do
  for v in nan inf -inf 0 -5 1e308 1e-300; do
    # A maximum of 0 (or 1e-300) with the minimum at -50 um is a one-sided range that holds rest:
    # a display deflecting one way only, legal (tests/movie/movie_io_test.cpp), not damage.
    [ $attr = layout_deflection_max_um ] && { [ $v = 0 ] || [ $v = 1e-300 ]; } && continue
    cp "$MOVIE" "$W/t.h5"
    $H5ATTR "$W/t.h5" $attr $v
    NOTE="$attr=$v" check "tampered-movie" fail -m "$attr" -m t.h5 -- info "$W/t.h5"
  done
done
for attr in frame_count layout_rows layout_cols format_version; do
  for v in 0 -1 2000000000 99999; do
    cp "$MOVIE" "$W/t.h5"
    $H5ATTR "$W/t.h5" $attr $v
    NOTE="$attr=$v" check "tampered-movie" fail -m "$attr" -m t.h5 -- play "$W/t.h5" --headless --preview "$W/p.png"
  done
done
for attr in frame_rate_hz field_width_mm field_height_mm; do
  for v in nan inf 0 -1 1e308 1e-300; do
    cp "$STRAIN" "$W/t.h5"
    $H5ATTR "$W/t.h5" $attr $v
    NOTE="$attr=$v" check "tampered-strain" fail -m "$attr" -m t.h5 -n "$W/o.h5" -- map "$W/t.h5" --out "$W/o.h5"
  done
done
for attr in span_frames camera_frame_count format_version; do
  for v in 0 -1 2000000000 1000; do
    cp "$STRAIN" "$W/t.h5"
    $H5ATTR "$W/t.h5" $attr $v
    # A camera_frame_count above the last strain frame is a recording whose last frames had no
    # track: not damage, so only crashes and raw messages count there.
    expect=fail
    [ $attr = camera_frame_count ] && [ $v = 1000 ] && expect=any
    rm -f "$W/o.h5"
    NOTE="$attr=$v" check "tampered-strain" $expect -m "$attr" -m t.h5 -- map "$W/t.h5" --out "$W/o.h5"
    NOTE="$attr=$v" check "tampered-strain" $expect -m "$attr" -m t.h5 -- info "$W/t.h5"
  done
done
rm -f "$W/o.h5"

############################################################################## numbers
NUMS=(nan inf -inf 1e308 -1e308 1e-300 -1 0 abc "" 1e999 0x10 "5abc" " 7" "1,5" -0)
num_cases() {  # family option cmd...
  local family=$1 opt=$2
  shift 2
  local v
  for v in "${NUMS[@]}"; do
    # A value that is valid for this option is no finding; only the clearly bad ones are checked
    # as usage errors.
    case "$v" in
      -1 | 0 | -0 | 1e-300 | " 7" | 0x10)
        # May be in range: any exit, but no crash, hang or raw message; skipped for commands
        # that would then run for minutes.
        [ "${SLOW:-}" = 1 ] || check "$family" any-number -- "$@" "$opt" "$v" ;;
      *) check "$family" usage -m "$opt" -- "$@" "$opt" "$v" ;;
    esac
  done
}
# For values that may be in range (0, -1, ...) accept any exit but require no crash/hang/raw text;
# `check` with an unknown EXPECT only enforces those.
num_cases numbers-demo --frames demo --headless --out "$W/d"
num_cases numbers-demo --speed demo --headless --out "$W/d"
num_cases numbers-synth --noise synth "$W/s" --frames 3
num_cases numbers-synth --px-per-mm synth "$W/s2" --from-print "$PRINTS/image_01.jpg" --frames 3
num_cases numbers-calibrate --spacing-mm calibrate "$DOTS" --out "$W/c.json"
num_cases numbers-features --px-per-mm features "$FRAMES/frame_000.png"
num_cases numbers-capture --span capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5"
num_cases numbers-capture --start capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5"
num_cases numbers-capture --smoothing capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5"
num_cases numbers-map --reference-frame map "$STRAIN" --out "$W/m.h5"
num_cases numbers-map --gain map "$STRAIN" --out "$W/m.h5"
num_cases numbers-play --loops play "$MOVIE" --headless --preview "$W/p.png"
num_cases numbers-play --blade-full-scale-um play "$MOVIE" --headless --preview "$W/p.png"
num_cases numbers-view --at view "$MOVIE" --screenshot "$W/v.png"
SLOW=1 num_cases numbers-experiment --threads experiment "$REPO/tools/experiments/methods.json" --plan --out "$W/e"
SLOW=1 num_cases numbers-perceive --trials perceive --out "$W/pc"
SLOW=1 num_cases numbers-perceive --seeds perceive --out "$W/pc" --trials 2
SLOW=1 num_cases numbers-classify --cv classify train --recordings "$REC" --labels "$LABELS" --out "$W/mm.json"
num_cases numbers-classify --threads classify test --model "$F/model.json" --recordings "$REC" --labels "$LABELS"
num_cases numbers-emulate --port emulate --latero --seconds 0.1
num_cases numbers-bench --repeats bench map --frames 2
SLOW=1 num_cases numbers-bench --min-points bench capture --frames 35 --quick --out "$W/bc"
num_cases numbers-train-pores --label-radius-mm train-pores --prints "$PRINTS" --px-per-mm 47 --out "$W/pm.json"
rm -rf "$W"/d "$W"/s "$W"/*.h5 "$W"/*.json "$W"/e "$W"/pc "$W"/bc

############################################################################## layout JSON
layout_case() {  # name json-text
  printf '%s' "$2" >"$W/L.json"
  NOTE=$1 check "bad-layout" fail -m L.json -n "$W/o.h5" -- map "$STRAIN" --out "$W/o.h5" --layout "$W/L.json"
}
GOOD='"name":"x","rows":6,"cols":12,"pitch_mm":[0.8,1.5],"contactor_size_mm":[0.4,1.2],"deflection_axis":"x","deflection_range_um":[-60,60],"max_rate_hz":800'
layout_case empty ''
layout_case array '[]'
layout_case null 'null'
layout_case cut "{$GOOD"
layout_case rows0 "{${GOOD/\"rows\":6/\"rows\":0}}"
layout_case rowsbig "{${GOOD/\"rows\":6/\"rows\":1e9}}"
layout_case rowsneg "{${GOOD/\"rows\":6/\"rows\":-6}}"
layout_case rowsfrac "{${GOOD/\"rows\":6/\"rows\":6.5}}"
layout_case rowsstr "{${GOOD/\"rows\":6/\"rows\":\"6\"}}"
layout_case pitchinf "{${GOOD/\[0.8,1.5\]/[1e999,1.5]}}"
layout_case pitch1 "{${GOOD/\[0.8,1.5\]/[0.8]}}"
layout_case pitch3 "{${GOOD/\[0.8,1.5\]/[0.8,1.5,2]}}"
layout_case pitchneg "{${GOOD/\[0.8,1.5\]/[-0.8,1.5]}}"
layout_case rangeinv "{${GOOD/\[-60,60\]/[60,-60]}}"
layout_case rangeinf "{${GOOD/\[-60,60\]/[-1e999,60]}}"
layout_case rate0 "{${GOOD/\"max_rate_hz\":800/\"max_rate_hz\":0}}"
layout_case ratenan "{${GOOD/\"max_rate_hz\":800/\"max_rate_hz\":NaN}}"
layout_case axis "{${GOOD/\"x\",\"def/\"z\",\"def}}"
layout_case dupkey "{$GOOD,\"rows\":200}"
layout_case unknown "{$GOOD,\"colour\":1}"
layout_case nameempty "{${GOOD/\"name\":\"x\"/\"name\":\"\"}}"
layout_case namepath "{${GOOD/\"name\":\"x\"/\"name\":\"../../etc/x\"}}"
# A byte order mark before the JSON is accepted, as in every CSV and JSON the project reads.
printf '\xef\xbb\xbf%s' "{$GOOD}" >"$W/L.json"
NOTE=bom check "bad-layout" ok -- map "$STRAIN" --out "$W/o.h5" --layout "$W/L.json"
rm -f "$W/o.h5"
layout_case trailing "{$GOOD} garbage"
layout_case deep "$(printf '%.0s[' $(seq 1 100000))"
check "bad-layout" err -m layout -n "$W/o.h5" -- map "$STRAIN" --out "$W/o.h5" --layout "$F/dir.h5"
check "bad-layout" err -m nolayout -n "$W/o.h5" -- map "$STRAIN" --out "$W/o.h5" --layout nolayout
check "bad-layout" err -m layout -n "$W/o.h5" -- map "$STRAIN" --out "$W/o.h5" --layout ""
check "bad-layout" err -m L.json -n "$W/o.h5" -- import "$F/m.hjif" --out "$W/o.h5" --layout "$W/L.json"

############################################################################## calibration JSON
calib_case() {  # json-text name
  printf '%s' "$1" >"$W/C.json"
  NOTE=$2 check "bad-calibration" fail -m C.json -n "$W/s.h5" -- capture "$FRAMES" --calib "$W/C.json" --out "$W/s.h5"
  NOTE=$2 check "bad-calibration" fail -m C.json -- features "$FRAMES/frame_000.png" --calib "$W/C.json"
}
CG=$(cat "$CALIB")
calib_case '' empty
calib_case '{}' obj
calib_case "${CG/\"mm_per_px\": 0./\"mm_per_px\": -0.}" mmneg
calib_case "${CG/\"image_width_px\": 640/\"image_width_px\": 0}" width0
calib_case "${CG/\"image_width_px\": 640/\"image_width_px\": 1e12}" widthhuge
calib_case "${CG/\"image_width_px\": 640/\"image_width_px\": 64}" widthsmall
calib_case "${CG/\"format_version\": 1/\"format_version\": 99}" version
calib_case "$(echo "$CG" | sed 's/0.016096803892766486/1e999/')" inf
calib_case "$(echo "$CG" | sed 's/0.016096803892766486/0/; s/0.022521805752962046/0/')" singular
calib_case "$(echo "$CG" | sed 's/"px_to_mm": \[/"px_to_mm": [1,/')" ten
calib_case "$(echo "$CG" | head -c 100)" cut
# The message names the image and says "no dot grid found"; "dot_grid" was only the name of
# the fixture's own grid image, a word no message about another image would contain.
check "bad-calibration" fail -m "frame_000.png: no dot grid found" -- calibrate "$FRAMES/frame_000.png" --out "$W/c.json"
check "bad-calibration" fail -m text.h5 -- calibrate "$F/text.h5" --out "$W/c.json"

############################################################################## images
mkdir -p "$W/img"
head -c 300 "$FRAMES/frame_000.png" >"$W/img/cut.png"
: >"$W/img/empty.png"
echo hello >"$W/img/text.png"
head -c 20000 /dev/urandom >"$W/img/random.jpg"
# A PNG header declaring 100000 x 100000 pixels followed by nothing: a decompression bomb's shape.
$PY - "$W/img/huge.png" <<'EOF'
import struct, sys, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
ihdr = struct.pack('>IIBBBBB', 100000, 100000, 8, 0, 0, 0, 0)
raw = zlib.compress(b'\0' * 1000)
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', raw) + chunk(b'IEND', b''))
EOF
$PY - "$W/img/tiny.png" <<'EOF'
import struct, sys, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
ihdr = struct.pack('>IIBBBBB', 1, 1, 8, 0, 0, 0, 0)
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', zlib.compress(b'\0\x80')) + chunk(b'IEND', b''))
EOF
for img in cut.png empty.png text.png random.jpg huge.png tiny.png; do
  check "bad-image" fail -m "$img" -t 60 -- features "$W/img/$img" --px-per-mm 50
  check "bad-image" fail -m "$img" -t 60 -- calibrate "$W/img/$img" --out "$W/c.json"
  check "bad-image" fail -m "$img" -t 60 -- synth "$W/s" --from-print "$W/img/$img" --frames 3
done
# A frame folder with one broken frame among good ones, and one holding only junk.
mkdir -p "$W/seq" "$W/junk" "$W/emptyseq"
cp "$FRAMES"/frame_00[0-9].png "$W/seq/"
cp "$W/img/cut.png" "$W/seq/frame_005.png"
cp "$W/img/text.png" "$W/img/random.jpg" "$W/junk/"
check "bad-image" fail -m frame_005 -n "$W/s.h5" -- capture "$W/seq" --calib "$CALIB" --out "$W/s.h5"
check "bad-image" fail -m junk -n "$W/s.h5" -- capture "$W/junk" --calib "$CALIB" --out "$W/s.h5"
check "bad-image" fail -m emptyseq -n "$W/s.h5" -- capture "$W/emptyseq" --calib "$CALIB" --out "$W/s.h5"
check "bad-image" err -m x.mp4 -n "$W/s.h5" -- capture "$W/img/x.mp4" --calib "$CALIB" --out "$W/s.h5"
echo notavideo >"$W/img/v.mp4"
check "bad-video" fail -m v.mp4 -n "$W/s.h5" -- capture "$W/img/v.mp4" --calib "$CALIB" --out "$W/s.h5"
head -c 50000 /dev/urandom >"$W/img/r.avi"
check "bad-video" fail -m r.avi -n "$W/s.h5" -- capture "$W/img/r.avi" --calib "$CALIB" --out "$W/s.h5"
check "bad-capture" fail -m frame -n "$W/s.h5" -- capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5" --start 39
# A frame index past the input's end is a usage error naming the option (tools/tactile/main.cpp,
# RequestError), as `view --at` past the movie's end; a --start inside it that leaves too few
# frames, or a --span longer than the tracks, is work that measured nothing: exit 1.
check "bad-capture" usage -m start -n "$W/s.h5" -- capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5" --start 500
check "bad-capture" fail -m span -n "$W/s.h5" -- capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5" --span 100
check "bad-capture" err -m pore -n "$W/s.h5" -- capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5" --pores ridge-blob --pore-model "$F/model.json"
# Stale frames of a longer earlier synth run left in the folder capture reads.
"$B" synth "$W/syn" --frames 12 >/dev/null 2>&1
check "stale-frames" usage -m frame_004 -- synth "$W/syn" --frames 4
n=$(ls "$W/syn" | grep -c '^frame_')
if [[ "stale-frames" =~ $FILTER ]]; then
  if [ "$n" -ne 12 ]; then say stale-frames "synth syn --frames 4 over a 12-frame synth: folder" BAD "$n frame files (capture would read a mixed sequence)"
  else say stale-frames "synth syn --frames 4 over a 12-frame synth: folder" OK; fi
fi
# Strain maps drawn into the frames folder become frames of the next capture.
check "stale-frames" usage -m maps -n "$W/syn/strain_000.png" -- capture "$W/syn" --px-per-mm 50 --out "$W/sm.h5" --maps "$W/syn" --min-track 2

############################################################################## classify inputs
mkdir -p "$W/rec"
cp "$REC"/*.csv "$W/rec/"
cl_labels() {  # name text
  printf '%s' "$2" >"$W/rec/labels-$1.csv"
  NOTE=$1 check "bad-labels" fail -m "labels-$1.csv" -n "$W/mm.json" -- classify train --recordings "$W/rec" --labels "$W/rec/labels-$1.csv" --out "$W/mm.json"
}
cl_labels empty ''
cl_labels header 'file,class
'
cl_labels onerow 'file,class
mat1_1_bio.csv,mat1
'
cl_labels missing 'file,class
nofile.csv,a
mat1_1_bio.csv,b
'
cl_labels traversal 'file,class
../../../../etc/passwd,a
mat1_1_bio.csv,b
'
cl_labels absolute "file,class
$W/rec/mat1_1_bio.csv,a
mat1_2_bio.csv,b
"
cl_labels dup 'file,class
mat1_1_bio.csv,a
mat1_1_bio.csv,b
mat1_2_bio.csv,b
'
cl_labels noclass 'file,class
mat1_1_bio.csv,
mat1_2_bio.csv,b
'
cl_labels ragged 'file,class
mat1_1_bio.csv,a,1,2,3
mat1_2_bio.csv
'
cl_labels nanvalue 'file,class,value
mat1_1_bio.csv,a,nan
mat1_2_bio.csv,b,1
mat1_3_bio.csv,a,2
mat1_4_bio.csv,b,inf
'
cl_labels abcvalue 'file,class,value
mat1_1_bio.csv,a,abc
mat1_2_bio.csv,b,1
'
cl_labels binary "$(head -c 3000 /dev/urandom | tr -d '\0')"
cl_labels selfref 'file,class
labels-selfref.csv,a
mat1_2_bio.csv,b
'
rec_case() {  # name text
  printf '%s' "$2" >"$W/rec/bad_bio.csv"
  printf 'file,class\nbad_bio.csv,a\nmat1_1_bio.csv,a\nmat1_2_bio.csv,b\nmat7_1_bio.csv,b\n' >"$W/rec/lb.csv"
  NOTE=$1 check "bad-recording" fail -m bad_bio.csv -n "$W/mm.json" -- classify train --recordings "$W/rec" --labels "$W/rec/lb.csv" --out "$W/mm.json"
}
HDR=$(head -1 "$REC/mat1_1_bio.csv")
# Sets the pressure (pdc, the 4th column) of lines FROM..TO to VALUE.
set_pdc() { awk -F, -v OFS=, -v a="$1" -v b="$2" -v v="$3" 'NR >= a && NR <= b { $4 = v } 1'; }
rec_case empty ''
rec_case header "$HDR"
rec_case onerow "$(head -2 "$REC/mat1_1_bio.csv")"
rec_case nan "$(head -200 "$REC/mat1_1_bio.csv" | set_pdc 50 60 nan)"
rec_case inf "$(head -200 "$REC/mat1_1_bio.csv" | set_pdc 50 60 1e999)"
rec_case abc "$(head -200 "$REC/mat1_1_bio.csv" | set_pdc 50 50 abc)"
rec_case ragged "$(head -200 "$REC/mat1_1_bio.csv" | sed '50s/,[0-9]*,$//')"
rec_case cols "$(head -200 "$REC/mat1_1_bio.csv" | cut -d, -f1-20)"
rec_case timeback "$(head -200 "$REC/mat1_1_bio.csv" | sed '100s/^1581072655/1481072655/')"
rec_case random "$(head -c 5000 /dev/urandom | tr -d '\0')"
rec_case huge "$(head -200 "$REC/mat1_1_bio.csv" | set_pdc 50 60 1e308)"
# Models
model_case() {  # name text
  printf '%s' "$2" >"$W/M-$1.json"
  check "bad-model" fail -m "M-$1.json" -- classify predict --model "$W/M-$1.json" "$REC/mat1_1_bio.csv"
  check "bad-model" fail -m "M-$1.json" -- classify test --model "$W/M-$1.json" --recordings "$REC" --labels "$LABELS"
}
MG=$(cat "$F/model.json")
model_case empty ''
model_case obj '{}'
model_case cut "$(head -c 500 "$F/model.json")"
model_case format "${MG/tactile classifier model/tactile layout}"
model_case classes "$(echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["class_names"]=m["class_names"][:1]; print(json.dumps(m))')"
model_case inputs "$(echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["input_names"]=m["input_names"][:3]; print(json.dumps(m))')"
model_case trim "$(echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["contact"]["trim_fraction"]=7; print(json.dumps(m))')"
model_case neg "$(echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["contact"]["baseline_s"]=-1; print(json.dumps(m))')"
model_case huge "$(echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["contact"]["baseline_s"]=1e300; print(json.dumps(m))')"
model_case tamper "$(echo "$MG" | $PY -c '
import json,sys
m=json.load(sys.stdin)
def walk(x):
    if isinstance(x, dict):
        for k in x: x[k] = walk(x[k])
    elif isinstance(x, list):
        if x and all(isinstance(v, float) for v in x): return [1e308] * len(x)
        return [walk(v) for v in x]
    return x
print(json.dumps(walk(m)))')"
model_case scaler "$(echo "$MG" | $PY -c '
import json,sys
m=json.load(sys.stdin)
m["scaler"]["max"] = [v * 0.5 for v in m["scaler"]["max"]]
print(json.dumps(m))')"
check "bad-predict" fail -m text.h5 -- classify predict --model "$F/model.json" "$F/text.h5"
check "bad-predict" fail -m mat1_1 -- classify predict --model "$F/model.json" "$W/rec/bad_bio.csv" "$REC/mat1_1_bio.csv"
check "bad-predict" err -m recording -- classify predict --model "$F/model.json"
check "bad-predict" fail -m missing.csv -- classify predict --model "$F/model.json" "$W/missing.csv"
check "bad-predict" fail -m recordings -- classify test --model "$F/model.json" --recordings "$PRINTS" --labels "$LABELS"
# Pore models and marks
printf '{}' >"$W/pore.json"
check "bad-pore-model" fail -m pore.json -- features "$FRAMES/frame_000.png" --px-per-mm 50 --pores ridge-blob --pore-model "$W/pore.json"
check "bad-pore-model" fail -m model.json -- features "$FRAMES/frame_000.png" --px-per-mm 50 --pores ridge-blob --pore-model "$F/model.json"
mkdir -p "$W/marks"
cp "$PRINTS/image_01.jpg" "$PRINTS/image_02.jpg" "$W/marks/"
for m in 'abc def' '-5 -5' '1e9 1e9' '0 0' '12' '1.5 2.5 3' 'nan nan'; do
  printf '10 10\n%s\n20 20\n' "$m" >"$W/marks/pores_01.txt"
  cp "$PRINTS/pores_02.txt" "$W/marks/"
  check "bad-marks" fail -m pores_01 -n "$W/pm.json" -- train-pores --prints "$W/marks" --px-per-mm 47 --out "$W/pm.json"
done
rm -f "$W/marks/pores_01.txt"
check "bad-marks" fail -m pores_01 -n "$W/pm.json" -- train-pores --prints "$W/marks" --px-per-mm 47 --out "$W/pm.json"
check "bad-marks" fail -m marks -n "$W/s" -- synth "$W/s" --from-print "$PRINTS/image_01.jpg" --marks "$F/text.h5" --frames 3

############################################################################## HJIF
hjif_case() {  # name text
  printf '%s' "$2" >"$W/H-$1.hjif"
  check "bad-hjif" fail -m "H-$1.hjif" -n "$W/o.h5" -d "$W" -- import "$W/H-$1.hjif" --out "$W/o.h5"
}
HG=$(cat "$F/m.hjif")
hjif_case empty ''
hjif_case obj '{}'
hjif_case cut "$(head -c 3000 "$F/m.hjif")"
hjif_case random "$(head -c 3000 /dev/urandom | tr -d '\0')"
hjif_case ts0 "${HG/\"timescale\":700/\"timescale\":0}"
hjif_case tsneg "${HG/\"timescale\":700/\"timescale\":-700}"
hjif_case tshuge "${HG/\"timescale\":700/\"timescale\":1e300}"
hjif_case tsfrac "${HG/\"timescale\":700/\"timescale\":0.001}"
hjif_case nochan "$(echo "$HG" | $PY -c 'import json,sys; h=json.load(sys.stdin); h["perceptions"][0]["channels"]=[]; print(json.dumps(h))')"
hjif_case onechan "$(echo "$HG" | $PY -c 'import json,sys; h=json.load(sys.stdin); h["perceptions"][0]["channels"]=h["perceptions"][0]["channels"][:1]; print(json.dumps(h))')"
hjif_case pos "${HG/\"relative_position\":5,/\"relative_position\":2000000000,}"
hjif_case posneg "${HG/\"relative_position\":5,/\"relative_position\":-5,}"
hjif_case amp "${HG/\"amplitude_modulation\":0\}/\"amplitude_modulation\":1e308\}}"
hjif_case amp2 "${HG/\"amplitude_modulation\":0\}/\"amplitude_modulation\":1.5\}}"
hjif_case ampnan "${HG/\"amplitude_modulation\":0\}/\"amplitude_modulation\":NaN\}}"
hjif_case exp "$(echo "$HG" | $PY -c 'import json,sys; h=json.load(sys.stdin); h["perceptions"][0]["perception_unit_exponent"]=400; print(json.dumps(h))')"
hjif_case twoperc "$(echo "$HG" | $PY -c 'import json,sys; h=json.load(sys.stdin); h["perceptions"].append(h["perceptions"][0]); print(json.dumps(h))')"
hjif_case modality "${HG/\"Position\"/\"Vibrotactile\"}"
hjif_case kpnull "$(echo "$HG" | $PY -c '
import sys,re
s=sys.stdin.read()
print(re.sub(r"\"keyframes\":\s*\[", "\"keyframes\":null,\"x\":[", s, count=1))')"
hjif_case layoutdesc "${HG/tactile-movie layout/tactile-movie layout {\\\"rows\\\":100000\}}"
check "bad-hjif" fail -m m.hjif -n "$W/o.h5" -- import "$F/m.hjif" --out "$W/o.h5" --layout latero
check "bad-hjif" fail -m text.h5 -n "$W/o.h5" -- import "$F/text.h5" --out "$W/o.h5"

############################################################################## experiment JSON
exp_case() {  # name text
  printf '%s' "$2" >"$W/E-$1.json"
  check "bad-experiment" err -m "E-$1.json" -t 60 -n "$W/eo" -- experiment "$W/E-$1.json" --out "$W/eo" --quiet
}
EG='"name":"t","seed":1,"sources":[{"name":"a","ground_truth":{"scene":"bump","frames":10}}],"layouts":["stress"],"methods":["integrated"]'
exp_case empty ''
exp_case arr '[]'
exp_case nosources "{${EG/\"sources\":\[*\],\"layouts/\"sources\":[],\"layouts}}"
exp_case frames0 "{${EG/\"frames\":10/\"frames\":0}}"
exp_case frameshuge "{${EG/\"frames\":10/\"frames\":1e9}}"
exp_case framesneg "{${EG/\"frames\":10/\"frames\":-10}}"
exp_case spacing0 "{${EG/\"frames\":10\}/\"frames\":10\},\"grid_spacing_mm\":0}"
exp_case spacingtiny "{${EG/\"frames\":10\}/\"frames\":10\},\"grid_spacing_mm\":1e-9}"
exp_case rate "{$EG,\"parameters\":{\"rate_hz\":[0]}}"
exp_case ratenan "{$EG,\"parameters\":{\"rate_hz\":[1e999]}}"
exp_case gain "{$EG,\"parameters\":{\"gain_um_per_strain\":[1e308]}}"
exp_case slew "{$EG,\"parameters\":{\"slew_limit_um_per_s\":[-1]}}"
exp_case peak "{$EG,\"parameters\":{\"peak_fraction\":[7]}}"
exp_case refframe "{$EG,\"parameters\":{\"reference_frame\":[100000]}}"
exp_case quality "{$EG,\"parameters\":{\"min_triangle_quality\":[2]}}"
exp_case namepath "{${EG/\"name\":\"a\"/\"name\":\"../../x\"}}"
# Names that become paths or manifest lines: each refused naming its field, nothing written.
EGREST=',"seed":1,"sources":[{"name":"a","ground_truth":{"scene":"bump","frames":10}}],"layouts":["stress"],"methods":["integrated"]'
exp_case expnameup "{\"name\":\"../../x\"$EGREST}"
exp_case expnameabs "{\"name\":\"$W/abs\"$EGREST}"
exp_case expnameline "{\"name\":\"t\\nx\"$EGREST}"
exp_case namedotdot "{${EG/\"name\":\"a\"/\"name\":\"..\"}}"
exp_case namedot "{${EG/\"name\":\"a\"/\"name\":\".\"}}"
exp_case namebackslash "{${EG/\"name\":\"a\"/\"name\":\"..\\\\x\"}}"
exp_case namenul "{${EG/\"name\":\"a\"/\"name\":\"a\\u0000b\"}}"
exp_case namelong "{${EG/\"name\":\"a\"/\"name\":\"$(head -c 240 /dev/zero | tr '\0' a)\"}}"
sed 's/"name": *"[^"]*"/"name": ".."/' "$LAYOUT" >"$W/Ldotdot.json"
exp_case layoutdotdot "{${EG/\[\"stress\"\]/[\"$W/Ldotdot.json\"]}}"
# Without --out the folder is NAME-results beside the caller: a name with '..' put it elsewhere.
printf '%s' "{\"name\":\"../escaped\"$EGREST}" >"$W/E-noout.json"
check "bad-experiment" fail -m "not a plain name" -n "$S/escaped-results" -n "$W/escaped-results" -- experiment "$W/E-noout.json" --plan
# Text of the command line that ends up in the Slurm scripts.
check "bad-experiment" usage -m partition -n "$W/esl" -n "$W/pwned" -- experiment "$REPO/tools/experiments/methods.json" --out "$W/esl" --slurm --partition "$(printf 'short\ntouch %s' "$W/pwned")"
check "bad-experiment" usage -m out -n "$W/e sl" -- experiment "$REPO/tools/experiments/methods.json" --out "$W/e sl" --slurm
check "bad-experiment" usage -m out -n "$W/e%jsl" -- experiment "$REPO/tools/experiments/methods.json" --out "$W/e%jsl" --slurm
check "bad-experiment" usage -m out -n "$W/$(printf 'e\nsl')" -- experiment "$REPO/tools/experiments/methods.json" --out "$W/$(printf 'e\nsl')" --slurm
exp_case dupname "{${EG/\}\],\"layouts/\}, {\"name\":\"a\",\"ground_truth\":{\"scene\":\"hole\"\}\}],\"layouts}}"
exp_case fileself "{${EG/\"ground_truth\":\{\"scene\":\"bump\",\"frames\":10\}/\"file\":\"E-fileself.json\"}}"
exp_case filedir "{${EG/\"ground_truth\":\{\"scene\":\"bump\",\"frames\":10\}/\"file\":\"/\"}}"
exp_case filetext "{${EG/\"ground_truth\":\{\"scene\":\"bump\",\"frames\":10\}/\"file\":\"$F/text.h5\"}}"
exp_case layoutbad "{${EG/\[\"stress\"\]/[\"L.json\"]}}"
exp_case layoutnone "{${EG/\[\"stress\"\]/[]}}"
exp_case methodbad "{${EG/\[\"integrated\"\]/[\"magic\"]}}"
exp_case scene "{${EG/bump/moon}}"
exp_case seedneg "{${EG/\"seed\":1/\"seed\":-1}}"
exp_case seedstr "{${EG/\"seed\":1/\"seed\":\"one\"}}"
exp_case noise "{${EG/\"frames\":10/\"frames\":10,\"noise\":1e999}}"
exp_case combos "{$EG,\"parameters\":{\"gain_um_per_strain\":[$(seq -s, 1 3000)],\"peak_fraction\":[$(seq -s, 0.1 0.0001 0.9 | head -c 20000 | sed 's/,[^,]*$//')]}}"
exp_case perception "{$EG,\"perception\":{\"trials\":-5}}"
exp_case perception2 "{$EG,\"perception\":7}"
check "bad-experiment" err -m cell -- experiment "$REPO/tools/experiments/methods.json" --out "$W/ex" --cell 99999
check "bad-experiment" err -m cell -- experiment "$REPO/tools/experiments/methods.json" --out "$W/ex" --cell ../../etc
check "bad-experiment" err -m manifest -- experiment "$REPO/tools/experiments/methods.json" --out "$W/exm" --merge
check "bad-experiment" err -m time -- experiment "$REPO/tools/experiments/methods.json" --out "$W/ex" --slurm --time abc
mkdir -p "$W/exm2"
"$B" experiment "$REPO/tools/experiments/methods.json" --out "$W/exm2" --plan >/dev/null 2>&1
printf 'garbage\tgarbage\n\n\x00\x01' >"$W/exm2/manifest.tsv"
check "bad-experiment" fail -m manifest -- experiment "$REPO/tools/experiments/methods.json" --out "$W/exm2" --merge
check "bad-experiment" fail -m manifest -- experiment "$REPO/tools/experiments/methods.json" --out "$W/exm2" --cell 0

############################################################################## recordings for perceive
mkdir -p "$W/precs" "$W/precs2"
printf 'junk\n' >"$W/precs/a_bio.csv"
check "bad-recording" fail -m a_bio.csv -n "$W/po/recordings.csv" -- perceive --out "$W/po" --recordings "$W/precs"
check "bad-recording" fail -m precs2 -- perceive --out "$W/po" --recordings "$W/precs2"

############################################################################## outputs: same as input
cp "$MOVIE" "$W/mv.h5"
cp "$STRAIN" "$W/st.h5"
cp "$F/model.json" "$W/md.json"
ln -f "$W/st.h5" "$W/st-hard.h5"
ln -sf "$W/st.h5" "$W/st-sym.h5"
ln -f "$W/mv.h5" "$W/mv-hard.h5"
ln -sf "$W/mv.h5" "$W/mv-sym.h5"
mkdir -p "$W/sub"
for o in "$W/st.h5" "./st.h5" "sub/../st.h5" "$W/st-hard.h5" "$W/st-sym.h5" "$W//st.h5"; do
  check "out-is-input" usage -m st.h5 -k "$W/st.h5" -d "$W" -- map "$W/st.h5" --out "$o"
done
for o in "$W/st.h5" "./st.h5" "$W/st-sym.h5"; do
  check "out-is-input" usage -k "$W/st.h5" -d "$W" -- map "$W/st.h5" --out "$W/o.h5" --csv "$o"
done
check "out-is-input" usage -k "$W/o2.h5" -- map "$W/st.h5" --out "$W/o2.h5" --csv "$W/o2.h5"
for o in "$W/mv.h5" "./mv.h5" "$W/mv-hard.h5" "$W/mv-sym.h5"; do
  check "out-is-input" usage -m mv.h5 -k "$W/mv.h5" -d "$W" -- play "$W/mv.h5" --headless --preview "$o"
  check "out-is-input" usage -m mv.h5 -k "$W/mv.h5" -d "$W" -- export "$W/mv.h5" --hjif "$o"
  check "out-is-input" usage -m mv.h5 -k "$W/mv.h5" -d "$W" -- export "$W/mv.h5" --wav "$o"
  check "out-is-input" usage -m mv.h5 -k "$W/mv.h5" -d "$W" -- view "$W/mv.h5" --screenshot "$o"
done
check "out-is-input" usage -k "$W/mv.h5" -- export "$W/mv.h5" --wav "$W/same.out" --hjif "$W/same.out"
cp "$F/m.hjif" "$W/in.hjif"
ln -sf "$W/in.hjif" "$W/in-sym.hjif"
check "out-is-input" usage -m in.hjif -k "$W/in.hjif" -- import "$W/in.hjif" --out "$W/in.hjif"
check "out-is-input" usage -m hjif -k "$W/in.hjif" -- import "$W/in.hjif" --out "$W/in-sym.hjif"
printf '{%s}' "$GOOD" >"$W/lay.json"
check "out-is-input" usage -m lay.json -k "$W/lay.json" -- import "$W/in.hjif" --out "$W/lay.json" --layout "$W/lay.json"
check "out-is-input" usage -m lay.json -k "$W/lay.json" -- map "$W/st.h5" --out "$W/lay.json" --layout "$W/lay.json"
check "out-is-input" usage -m lay.json -k "$W/lay.json" -- map "$W/st.h5" --out "$W/o.h5" --csv "$W/lay.json" --layout "$W/lay.json"
cp "$DOTS" "$W/dots.png"
check "out-is-input" usage -m dots.png -k "$W/dots.png" -- calibrate "$W/dots.png" --out "$W/dots.png"
check "out-is-input" usage -m dots.png -k "$W/dots.png" -- calibrate "$W/dots.png" --out "./dots.png"
cp "$FRAMES/frame_000.png" "$W/f0.png"
check "out-is-input" usage -m f0.png -k "$W/f0.png" -- features "$W/f0.png" --px-per-mm 50 --csv "$W/f0.png"
cp "$CALIB" "$W/cal.json"
check "out-is-input" usage -m cal.json -k "$W/cal.json" -- features "$W/f0.png" --calib "$W/cal.json" --csv "$W/cal.json"
mkdir -p "$W/fr"
cp "$FRAMES"/frame_0[0-3]?.png "$W/fr/"
cp "$CALIB" "$W/fr/cal.json"
check "out-is-input" usage -m frame_000 -k "$W/fr/frame_000.png" -- capture "$W/fr" --calib "$W/fr/cal.json" --out "$W/fr/frame_000.png"
check "out-is-input" usage -m cal.json -k "$W/fr/cal.json" -- capture "$W/fr" --calib "$W/fr/cal.json" --out "$W/fr/cal.json"
check "out-is-input" usage -m fr -k "$W/fr/frame_000.png" -- capture "$W/fr" --calib "$W/fr/cal.json" --out "$W/fr"
check "out-is-input" usage -m st.h5 -k "$W/st.h5" -- capture "$W/fr" --calib "$W/fr/cal.json" --out "$W/st.h5" --csv "$W/st.h5"
# --maps / --csv folders equal to the frames folder: strain_NNN.png land among the frames.
check "out-is-input" err -m fr -k "$W/fr/frame_000.png" -n "$W/fr/strain_000.png" -- capture "$W/fr" --calib "$W/fr/cal.json" --out "$W/s9.h5" --maps "$W/fr"
cp "$REC/mat1_1_bio.csv" "$W/rec/"
cp "$LABELS" "$W/rec/labels.csv"
ln -sf "$W/rec/labels.csv" "$W/lab-sym.csv"
for o in "$W/rec/labels.csv" "$W/lab-sym.csv" "$W/rec/./labels.csv" "$W/rec/mat1_1_bio.csv" "$W/rec"; do
  check "out-is-input" usage -k "$W/rec/labels.csv" -k "$W/rec/mat1_1_bio.csv" -- classify train --recordings "$W/rec" --labels "$W/rec/labels.csv" --out "$o"
done
check "out-is-input" usage -k "$W/md.json" -- classify train --recordings "$W/rec" --labels "$W/rec/labels.csv" --out "$W/md.json" --select --cv 2 --c 1 --labels "$W/md.json"
# Results beside the recordings or the model are new names, not overwrites: only the inputs count.
check "out-is-input" any -k "$W/rec/labels.csv" -k "$W/rec/mat1_1_bio.csv" -- classify test --model "$W/md.json" --recordings "$W/rec" --labels "$W/rec/labels.csv" --csv "$W/rec"
printf 'x' >"$W/rec/predictions.csv.keep"
check "out-is-input" any -k "$W/md.json" -- classify test --model "$W/md.json" --recordings "$W/rec" --labels "$W/rec/labels.csv" --csv "$W"
ln -sf "$W/md.json" "$W/pmodel-sym.json"
check "out-is-input" usage -k "$W/md.json" -- train-pores --prints "$PRINTS" --px-per-mm 47 --out "$PRINTS/pores_01.txt"
cp "$W/fr/frame_000.png" "$W/print.png"
check "out-is-input" usage -m print.png -k "$W/print.png" -- synth "$W" --from-print "$W/print.png" --frames 3
mkdir -p "$W/exself"
cp "$REPO/tools/experiments/methods.json" "$W/exself/experiment.json"
mkdir -p "$W/exself/layouts" && cp "$LAYOUT" "$W/exself/layouts/"
check "out-is-input" err -m experiment.json -k "$W/exself/experiment.json" -- experiment "$W/exself/experiment.json" --out "$W/exself" --plan
cp "$REPO/tools/experiments/methods.json" "$W/methods.json"
mkdir -p "$W/exq/layouts"
check "out-is-input" err -k "$W/methods.json" -- experiment "$W/methods.json" --out "$W" --plan
check "out-is-input" usage -m st.h5 -k "$W/st.h5" -- evaluate "$FRAMES" "$W/st.h5" --csv "$W/st.h5"
check "out-is-input" usage -m demo -k "$W/st.h5" -- demo --headless --frames 3 --out "$W/st.h5"
check "out-is-input" usage -k "$W/st.h5" -- synth "$W/st.h5" --frames 3
check "out-is-input" usage -k "$W/st.h5" -- perceive --out "$W/st.h5" --trials 2

############################################################################## outputs: unwritable places
for o in "$W/nofolder/o.h5" "$W/dir.h5" "$W/" "/dev/full" "/proc/version" "" "$W/o.h5/"; do
  mkdir -p "$W/dir.h5"
  check "bad-output" err -m out -t 30 -- map "$STRAIN" --out "$o"
  check "bad-output" err -t 30 -- export "$MOVIE" --hjif "$o"
  check "bad-output" err -t 30 -- play "$MOVIE" --headless --preview "$o"
  check "bad-output" err -t 30 -- calibrate "$DOTS" --out "$o"
  check "bad-output" err -t 30 -- classify train --recordings "$REC" --labels "$LABELS" --out "$o"
  check "bad-output" err -t 30 -- import "$F/m.hjif" --out "$o"
done
check "bad-output" err -m nofolder -- capture "$FRAMES" --calib "$CALIB" --out "$W/nofolder/s.h5"
check "bad-output" err -m dir.h5 -- capture "$FRAMES" --calib "$CALIB" --out "$W/dir.h5"
check "bad-output" err -m csv -- capture "$FRAMES" --calib "$CALIB" --out "$W/s.h5" --csv "$STRAIN"
check "bad-output" err -m csv -- map "$STRAIN" --out "$W/o.h5" --csv "$W/dir.h5"
check "bad-output" err -m perceive -- perceive --out /dev/full --trials 2
check "bad-output" err -m demo -- demo --headless --frames 3 --out "$STRAIN"
check "bad-output" err -m evaluate -- evaluate "$FRAMES" "$STRAIN" --csv "$STRAIN"

# Read-only file system (as root, chmod does not stop a write).
RO=$S/ro
mount_tmpfs "$RO" 1m
cp "$STRAIN" "$MOVIE" "$RO/"
echo old >"$RO/old.h5"
mount -o remount,ro "$RO"
check "read-only" err -m "read-only" -m "$RO" -k "$RO/old.h5" -d "$RO" -- map "$STRAIN" --out "$RO/old.h5"
check "read-only" err -m "read-only" -d "$RO" -- capture "$FRAMES" --calib "$CALIB" --out "$RO/s.h5"
check "read-only" err -m "read-only" -- export "$MOVIE" --hjif "$RO/x.hjif"
check "read-only" err -m "read-only" -- export "$MOVIE" --wav "$RO/x.wav"
check "read-only" err -m "read-only" -- play "$MOVIE" --headless --preview "$RO/p.png"
check "read-only" err -m "read-only" -- calibrate "$DOTS" --out "$RO/c.json"
check "read-only" err -m "read-only" -- classify train --recordings "$REC" --labels "$LABELS" --out "$RO/m.json"
check "read-only" err -m "read-only" -- classify test --model "$F/model.json" --recordings "$REC" --labels "$LABELS" --csv "$RO/t"
check "read-only" err -m "read-only" -- import "$F/m.hjif" --out "$RO/i.h5"
check "read-only" err -m "read-only" -- synth "$RO/syn" --frames 3
check "read-only" err -m "read-only" -- demo --headless --frames 3 --out "$RO/demo"
check "read-only" err -m "read-only" -- perceive --out "$RO/pc" --trials 2
check "read-only" err -m "read-only" -- experiment "$REPO/tools/experiments/methods.json" --out "$RO/e" --plan
check "read-only" err -m "read-only" -- features "$FRAMES/frame_000.png" --px-per-mm 50 --csv "$RO/f.csv"
check "read-only" err -m "read-only" -- evaluate "$FRAMES" "$STRAIN" --csv "$RO/ev"
check "read-only" err -m "read-only" -- train-pores --prints "$PRINTS" --px-per-mm 47 --out "$RO/pm.json"
check "read-only" err -m "read-only" -- view "$RO/movie.h5" --screenshot "$RO/v.png"
check "read-only" ok -- info "$RO/movie.h5"
check "read-only" ok -- play "$RO/movie.h5" --headless --preview "$W/p-ro.png"
check "read-only" ok -- map "$RO/strain.h5" --out "$W/ro-map.h5"
umount "$RO"

# A full disk: 64 kB of tmpfs, each case with an old output that must survive.
FULL=$S/full
mount_tmpfs "$FULL" 64k
full_case() {  # output-name args...
  local o=$1
  shift
  rm -rf "${FULL:?}"/* "$FULL"/.[!.]* 2>/dev/null
  echo "old bytes of $o" >"$FULL/$o"
  head -c 1G /dev/zero >"$FULL/fill" 2>/dev/null
  check "full-disk" fail -m "no space" -m "$o" -k "$FULL/$o" -d "$FULL" -t 120 -- "$@"
}
full_case s.h5 capture "$FRAMES" --calib "$CALIB" --out "$FULL/s.h5"
full_case m.h5 map "$STRAIN" --out "$FULL/m.h5"
full_case m.csv map "$STRAIN" --out "$W/full-m.h5" --csv "$FULL/m.csv"
full_case x.hjif export "$MOVIE" --hjif "$FULL/x.hjif"
full_case x.wav export "$MOVIE" --wav "$FULL/x.wav"
full_case i.h5 import "$F/m.hjif" --out "$FULL/i.h5"
full_case p.png play "$LONG" --headless --preview "$FULL/p.png"
full_case c.json calibrate "$DOTS" --out "$FULL/c.json"
full_case m.json classify train --recordings "$REC" --labels "$LABELS" --out "$FULL/m.json"
full_case f.csv features "$FRAMES/frame_000.png" --px-per-mm 50 --csv "$FULL/f.csv"
full_case pm.json train-pores --prints "$PRINTS" --px-per-mm 47 --out "$FULL/pm.json"
rm -rf "${FULL:?}"/*
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- synth "$FULL/syn" --frames 20
rm -rf "${FULL:?}"/*
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- demo --headless --frames 10 --out "$FULL/demo"
rm -rf "${FULL:?}"/*
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- perceive --out "$FULL/pc" --trials 2 --footprints 5
rm -rf "${FULL:?}"/*
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- classify test --model "$F/model.json" --recordings "$REC" --labels "$LABELS" --csv "$FULL/t"
rm -rf "${FULL:?}"/*
head -c 1G /dev/zero >"$FULL/fill" 2>/dev/null
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- evaluate "$FRAMES" "$STRAIN" --csv "$FULL/ev"
rm -rf "${FULL:?}"/*
check "full-disk" fail -m "no space" -d "$FULL" -t 120 -- capture "$FRAMES" --calib "$CALIB" --out "$W/fullcap.h5" --maps "$FULL/maps"
rm -rf "${FULL:?}"/*
cat >"$W/small-exp.json" <<'EOF'
{"name":"s","seed":1,"sources":[{"name":"a","ground_truth":{"scene":"bump","frames":30}}],"layouts":["stress"],"methods":["integrated","proportional"]}
EOF
check "full-disk" fail -m "no space" -d "$FULL" -d "$FULL/e" -t 120 -- experiment "$W/small-exp.json" --out "$FULL/e" --quiet
umount "$FULL"

# Links planted where a temporary file or an output would go.
mkdir -p "$W/plant"
echo precious >"$W/plant/precious"
for n in .m.h5.tmp m.h5.partial .m.h5.0000000000000000.tmp m.h5.tmp; do
  ln -sf "$W/plant/precious" "$W/plant/$n"
done
check "planted-link" ok -k "$W/plant/precious" -- map "$STRAIN" --out "$W/plant/m.h5"
ln -sf "$W/plant/precious" "$W/plant/link.h5"
check "planted-link" ok -k "$W/plant/precious" -- map "$STRAIN" --out "$W/plant/link.h5"
if [[ planted-link =~ $FILTER ]]; then
  if [ -L "$W/plant/link.h5" ]; then say planted-link "map over a symlink output" BAD "link kept, target?"; else say planted-link "map over a symlink output: link replaced, target kept" OK; fi
fi
ln -sf /nonexistent/dir/x "$W/plant/dangling.json"
check "planted-link" ok -- calibrate "$DOTS" --out "$W/plant/dangling.json"
mkfifo "$W/plant/fifo.h5" 2>/dev/null
check "planted-link" err -m fifo -t 20 -- map "$STRAIN" --out "$W/plant/fifo.h5"
check "planted-link" err -m fifo -t 20 -- info "$W/plant/fifo.h5"
check "planted-link" err -m fifo -t 20 -- map "$W/plant/fifo.h5" --out "$W/plant/x.h5"
check "planted-link" err -t 20 -- classify predict --model "$W/plant/fifo.h5" "$REC/mat1_1_bio.csv"
check "planted-link" err -t 20 -- map "$STRAIN" --out "$W/plant/y.h5" --layout "$W/plant/fifo.h5"

############################################################################## existing output survives a failed run
cp "$MOVIE" "$W/keep.h5"
check "keep-old" fail -k "$W/keep.h5" -d "$W" -- map "$F/cut-strain.h5" --out "$W/keep.h5"
check "keep-old" usage -k "$W/keep.h5" -d "$W" -- map "$STRAIN" --out "$W/keep.h5" --gain nan
check "keep-old" fail -k "$W/keep.h5" -d "$W" -- import "$W/H-cut.hjif" --out "$W/keep.h5"
check "keep-old" fail -k "$W/keep.h5" -d "$W" -- capture "$W/junk" --calib "$CALIB" --out "$W/keep.h5"
check "keep-old" fail -k "$W/keep.h5" -d "$W" -- capture "$FRAMES" --calib "$CALIB" --out "$W/keep.h5" --frames 1
check "keep-old" fail -k "$W/keep.h5" -d "$W" -- map "$STRAIN" --out "$W/keep.h5" --layout "$W/L.json"
cp "$F/model.json" "$W/keep.json"
check "keep-old" fail -k "$W/keep.json" -d "$W" -- classify train --recordings "$W/rec" --labels "$W/rec/labels-onerow.csv" --out "$W/keep.json"
check "keep-old" fail -k "$W/keep.json" -d "$W" -- calibrate "$FRAMES/frame_000.png" --out "$W/keep.json"
mkdir -p "$W/kd"
echo old >"$W/kd/preview.png"
check "keep-old" fail -k "$W/kd/preview.png" -d "$W/kd" -- play "$F/cut-movie.h5" --headless --preview "$W/kd/preview.png"
echo old >"$W/kd/x.hjif"
check "keep-old" fail -k "$W/kd/x.hjif" -d "$W/kd" -- export "$F/cut-movie.h5" --hjif "$W/kd/x.hjif"
# A run refused for a usage error leaves both outputs of export alone.
echo old >"$W/kd/x.wav"
check "keep-old" usage -k "$W/kd/x.wav" -k "$W/kd/x.hjif" -- export "$MOVIE" --hjif "$W/kd/x.hjif" --wav "$W/kd/x.wav" --bogus

############################################################################## network-ish options (127.0.0.1 only)
for h in "" ":" "127.0.0.1:0" "127.0.0.1:99999" "127.0.0.1:abc" "127.0.0.1:-1" "[::1" "127.0.0.1: 80"; do
  check "bad-host" usage -m latero -t 20 -- play "$LATERO_MOVIE" --latero "$h"
  check "bad-host" usage -m latero -t 20 -- devices --latero "$h"
done
check "bad-host" fail -m 127.0.0.1 -t 30 -- devices --latero 127.0.0.1:9
check "bad-host" fail -m 127.0.0.1 -t 30 -- play "$LATERO_MOVIE" --latero 127.0.0.1:9
for b in "8.8.8.8" "" "::ffff:1.2.3.4.5"; do
  check "bad-bind" err -m bind -t 20 -- emulate --latero --bind "$b" --seconds 0.2 --port 0
done
check "bad-bind" err -m port -t 20 -- emulate --latero --port 65536 --seconds 0.2
# Garbage datagrams at an emulator: it must count them and keep running.
if [[ bad-datagram =~ $FILTER ]]; then
  "$B" emulate --latero --port 0 --seconds 3 >"$W/emu.txt" 2>&1 &
  epid=$!
  sleep 0.8
  port=$(grep -Eo '127\.0\.0\.1:[0-9]+' "$W/emu.txt" | head -1 | cut -d: -f2)
  if [ -n "$port" ]; then
    $PY - "$port" <<'EOF'
import os, socket, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
for n in [0, 1, 2, 3, 7, 8, 64, 1400, 65000]:
    for _ in range(20):
        s.sendto(os.urandom(n), ("127.0.0.1", int(sys.argv[1])))
EOF
  fi
  wait $epid
  rc=$?
  if [ -z "$port" ]; then say bad-datagram "emulate --latero <- random datagrams" BAD "no port printed: $(head -2 "$W/emu.txt")"
  elif [ $rc -ne 0 ]; then say bad-datagram "emulate --latero <- 180 random datagrams" BAD "exit $rc"
  elif ! grep -qi malformed "$W/emu.txt"; then say bad-datagram "emulate --latero <- 180 random datagrams" BAD "no malformed count"
  else say bad-datagram "emulate --latero <- 180 random datagrams" OK; fi
fi

############################################################################## values no measurement can have
# A recording whose pressure reads millions of counts (the converters give 0..4095), and one in
# which no signal ever changes (a sensor that measured nothing).
rec_value_case() {  # name text words
  printf '%s' "$2" >"$W/rec/bad_bio.csv"
  printf 'file,class\nbad_bio.csv,a\nmat1_1_bio.csv,a\nmat1_2_bio.csv,b\nmat7_1_bio.csv,b\n' >"$W/rec/lb.csv"
  NOTE=$1 check "absurd-value" fail -m "$3" -n "$W/mm.json" -- classify train --recordings "$W/rec" --labels "$W/rec/lb.csv" --out "$W/mm.json"
}
rec_value_case millions "$(head -200 "$REC/mat1_1_bio.csv" | set_pdc 50 50 5e6)" "out of range"
ROW=$(sed -n 2p "$REC/mat1_1_bio.csv")
rec_value_case constant "$(head -1 "$REC/mat1_1_bio.csv"; for i in $(seq 100); do echo "${ROW/#1581/$((1581 + i))}"; done)" "measured nothing"

############################################################################## inputs people actually have
# CR LF line ends and a UTF-8 byte-order mark, as a spreadsheet saved on Windows writes them.
crlf() { printf '\xef\xbb\xbf'; sed 's/$/\r/' "$1"; }
mkdir -p "$W/crlf"
for m in mat1_1 mat1_2 mat7_1 mat7_2; do crlf "$REC/${m}_bio.csv" >"$W/crlf/${m}_bio.csv"; done
printf 'file,class\nmat1_1_bio.csv,a\nmat1_2_bio.csv,a\nmat7_1_bio.csv,b\nmat7_2_bio.csv,b\n' >"$W/crlf/lb0.csv"
crlf "$W/crlf/lb0.csv" >"$W/crlf/lb.csv"
check "crlf-bom" ok -- classify train --recordings "$W/crlf" --labels "$W/crlf/lb.csv" --out "$W/crlf-model.json"
cp -r "$FRAMES" "$W/crlf-frames"
crlf "$FRAMES/landmarks.csv" >"$W/crlf-frames/landmarks.csv"
check "crlf-bom" ok -- evaluate "$W/crlf-frames" "$STRAIN" --csv "$W/crlf-ev"
sed '1s/.*/id;type;frame;x_px/' "$FRAMES/landmarks.csv" >"$W/crlf-frames/landmarks.csv"
check "said-wrong" fail -m "header is 'id;type;frame;x_px'" -- evaluate "$W/crlf-frames" "$STRAIN" --csv "$W/crlf-ev2"
echo "$MG" | $PY -c 'import json,sys; m=json.load(sys.stdin); m["version"]=4294967297; print(json.dumps(m))' >"$W/M-v2p32.json"
check "said-wrong" fail -m "version 4294967297" -- classify predict --model "$W/M-v2p32.json" "$REC/mat1_1_bio.csv"
check "said-wrong" usage -m "--export-recordings" -n "$W/pe" -- perceive --out "$W/pe" --trials 2 --export-trials 2

############################################################################## a Latero that answers nonsense
# A peer on 127.0.0.1 answering each request with a datagram of the kind named (at most 300
# answers, for at most 8 s): the probe must say what came back, not that nothing did.
if [[ nonsense-latero =~ $FILTER ]]; then
  for kind in magic oversized echo random; do
    $PY - "$kind" "$W/nl-port.txt" <<'EOF' &
import os, socket, sys, time
kind, port_file = sys.argv[1], sys.argv[2]
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(("127.0.0.1", 0))
open(port_file + ".tmp", "w").write(str(s.getsockname()[1]))
os.rename(port_file + ".tmp", port_file)
s.settimeout(0.2)
end, answered = time.time() + 8, 0
while time.time() < end and answered < 300:
    try:
        data, peer = s.recvfrom(4096)
    except socket.timeout:
        continue
    if kind == "magic":
        reply = bytes([data[0] ^ 0xFF, 1, 0x81]) + bytes(32)
    elif kind == "oversized":
        reply = data + bytes(3000)
    elif kind == "echo":
        reply = data
    else:
        reply = bytes([0x55]) + os.urandom(40)
    s.sendto(reply, peer)
    answered += 1
EOF
    npid=$!
    for _ in $(seq 50); do [ -s "$W/nl-port.txt" ] && break; sleep 0.1; done
    port=$(cat "$W/nl-port.txt" 2>/dev/null)
    rm -f "$W/nl-port.txt"
    NOTE=$kind check "nonsense-latero" fail -m "malformed repl" -t 20 -- devices --latero "127.0.0.1:$port"
    kill $npid 2>/dev/null
    wait $npid 2>/dev/null
  done
fi

############################################################################## usage oddities
check "usage" usage -- map
check "usage" usage -- map "$STRAIN"
check "usage" usage -- nosuchcommand
check "usage" usage -- classify
check "usage" usage -- classify nosuch
check "usage" usage -- bench
check "usage" usage -- bench nosuch
check "usage" usage -- map "$STRAIN" --out "$W/o.h5" --method magic
check "usage" usage -- map "$STRAIN" --out "$W/o.h5" --out "$W/p.h5"
check "usage" usage -- capture "$FRAMES" --calib "$CALIB" --px-per-mm 50 --out "$W/s.h5"
check "usage" usage -- export "$MOVIE"
check "usage" usage -- play "$LATERO_MOVIE" --headless --latero 127.0.0.1
check "usage" usage -- view "$MOVIE" --strain "$STRAIN" --no-strain
check "usage" usage -- experiment "$REPO/tools/experiments/methods.json" --status
check "usage" usage -- perceive --out "$W/pc" --seeds 2 --recordings "$REC"
check "usage" usage -- perceive --out "$W/pc" --footprints 3
check "usage" usage -- classify train --recordings "$REC" --labels "$LABELS" --out "$W/m.json" --inputs magic
check "usage" usage -- classify train --recordings "$REC" --labels "$LABELS" --out "$W/m.json" --inputs ""
check "usage" usage -- synth "$W/s" --px-per-mm 50
check "usage" usage -- synth "$W/s" --slide-x 1 --slide-speed 1 --from-print "$PRINTS/image_01.jpg"
check "usage" usage -- demo --out ""
check "usage" usage -- "$(head -c 5000 /dev/zero | tr '\0' a)"
check "usage" usage -- map "$STRAIN" --out "$W/o.h5" --rate-hz 700.5
check "usage" usage -- map "$STRAIN" --out "$W/o.h5" --rate-hz 100000000
check "usage" usage -- bench prints "$PRINTS" --held-out abc --out "$W/bp" --quick
check "usage" usage -- bench prints "$PRINTS" --held-out 99 --out "$W/bp" --quick
check "usage" usage -- experiment "$REPO/tools/experiments/methods.json" --slurm --out "$W/sl" --time 99:99:99:99

############################################################################## signals during long commands
SIG=$S/sig
mkdir -p "$SIG"
for d in 0.05 0.3 1.5; do
  for sg in INT TERM; do
    echo old >"$SIG/p.png"
    sigcase "signal" $sg $d "$SIG" "$SIG/p.png" -- play "$LONG" --headless --preview "$SIG/p.png" --loops 20
    echo old >"$SIG/m.h5"
    sigcase "signal" $sg $d "$SIG" "$SIG/m.h5" -- map "$LONGSTRAIN" --out "$SIG/m.h5" --csv "$SIG/m.csv"
    echo old >"$SIG/s.h5"
    sigcase "signal" $sg $d "$SIG" "$SIG/s.h5" -- capture "$FRAMES" --calib "$CALIB" --out "$SIG/s.h5" --csv "$SIG/csv" --maps "$SIG/maps"
    rm -rf "$SIG/e"
    sigcase "signal" $sg $d "$SIG/e" "$SIG/none" -- experiment "$W/small-exp.json" --out "$SIG/e" --quiet
    sigcase "signal" $sg $d "$SIG/demo" "$SIG/none" -- demo --headless --frames 60 --out "$SIG/demo"
    sigcase "signal" $sg $d "$SIG/pc" "$SIG/none" -- perceive --out "$SIG/pc" --trials 2
    echo old >"$SIG/x.wav"
    sigcase "signal" $sg $d "$SIG" "$SIG/x.wav" -- export "$LONG" --wav "$SIG/x.wav" --hjif "$SIG/x.hjif"
  done
done
# The emulated Latero: a Ctrl-C of play must bring the blades back to rest.
if [[ signal-latero =~ $FILTER ]]; then
  "$B" emulate --latero --port 0 --seconds 20 >"$W/emu2.txt" 2>&1 &
  epid=$!
  # Waited for, not slept on: on a loaded machine the line came later than any fixed pause.
  port=""
  for _ in $(seq 100); do
    port=$(grep -Eo '127\.0\.0\.1:[0-9]+' "$W/emu2.txt" | head -1 | cut -d: -f2)
    [ -n "$port" ] && break
    sleep 0.1
  done
  for d in 0.3 1.0; do
    (exec env --default-signal=INT "$B" play "$LATERO_MOVIE" --loops 50 --latero "127.0.0.1:$port" >"$W/pl.txt" 2>&1) &
    ppid=$!
    sleep $d
    kill -INT $ppid
    wait $ppid
    rc=$?
    # Stopped while still reading the movie, it sent nothing, so it has no blades to bring back;
    # stopped while it started (loaded, parsed its command line), it did nothing at all.
    if [ $rc -eq 130 ] && grep -Eqi 'rest|nothing was sent|nothing was done' "$W/pl.txt"; then say signal-latero "play --latero <- SIGINT at ${d}s" OK
    else say signal-latero "play --latero <- SIGINT at ${d}s" BAD "exit $rc: $(tail -1 "$W/pl.txt")"; fi
  done
  kill -INT $epid 2>/dev/null
  wait $epid
fi

echo "TOTAL $TOTAL cases: $OKS OK, $BADS BAD"
