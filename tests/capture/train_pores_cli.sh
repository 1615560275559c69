#!/bin/sh
# Usage: train_pores_cli.sh TACTILE DATA_DIR WORK_DIR: the fixture of the train-pores command-line
# tests. Builds WORK_DIR (3 marked PolyU prints, a still sequence of a 4th, an empty folder, a
# folder with a broken marks file, a print alone, a corrupt model file), then trains on the 3
# prints and checks what a user would look at: the model file holds 153 finite numbers and the
# table has an overall TDR.
tactile=$1 data=$2 work=$3
fail() {
  echo "train_pores_cli: $*" >&2
  exit 1
}
rm -rf "$work" && mkdir -p "$work/three" "$work/empty" "$work/broken" "$work/one" || fail "cannot make $work"
for n in 01 02 03; do
  ln -s "$data/image_$n.jpg" "$data/pores_$n.txt" "$work/three/" || fail "cannot link print $n"
done
ln -s "$data/image_01.jpg" "$data/pores_01.txt" "$work/one/" || fail "cannot link print 01"
# A still finger: print 04 (not trained on) three times, a sequence whose landmarks a capture
# with the model must track (three different prints make no sequence to track).
mkdir -p "$work/still" || fail "cannot make $work/still"
for n in 0 1 2; do
  ln -s "$data/image_04.jpg" "$work/still/frame_00$n.jpg" || fail "cannot link frame $n"
done
ln -s "$data/image_01.jpg" "$work/broken/" || fail "cannot link print 01"
printf '42 1\n86 1 7\n' > "$work/broken/pores_01.txt"
printf '{"format": "tactile-pore-model", "format_version": 1, "coeffic' > "$work/corrupt.json"

"$tactile" train-pores --prints "$work/three" --px-per-mm 47 --out "$work/model.json" \
  > "$work/train.log" 2>&1
rc=$?
cat "$work/train.log"
[ "$rc" -eq 0 ] || fail "train-pores exited $rc"
grep -q 'labelling print 3 of 3' "$work/train.log" || fail "no progress line for print 3 of 3"
grep -Eq '^ *overall +0\.[0-9]{3} +0\.[0-9]{3} +[0-9]+ +[0-9]+ +[0-9]+$' "$work/train.log" ||
  fail "no overall TDR / FDR row"
# One coefficient per line between "coefficients": [ and ]: count them and check each is a
# plain finite number (JSON has no NaN or infinity; a broken fit would show as null).
awk '/"coefficients": \[/ { on = 1; next }
     on && /^ *\]/ { on = 0 }
     on { n++; if ($0 !~ /^ *-?[0-9][0-9.]*([eE][-+]?[0-9]+)?,?$/) bad++ }
     END { if (n != 153 || bad > 0) { print "coefficients: " n ", not numbers: " bad; exit 1 } }' \
  "$work/model.json" || fail "model.json does not hold 153 finite coefficients"
grep -q '"coefficient_count": 153' "$work/model.json" || fail "no coefficient_count 153"
# The same model with a threshold no candidate reaches: features must then find no pore, which
# shows that --pore-model applies the file's threshold, not the built-in one.
sed 's/"min_log_odds": -0.5,/"min_log_odds": 1000.0,/' "$work/model.json" > "$work/strict.json"
grep -q '"min_log_odds": 1000.0' "$work/strict.json" || fail "could not write strict.json"
echo "train_pores_cli: model and table as expected"
