#!/bin/sh
# Two hubbeam runs writing the same CSV: the second must be refused (exit 2, "another hubbeam is writing") while
# the first writes, and the first, stopped by SIGTERM, must still put its file in place. Usage: second_writer.sh HUBBEAM SCENE CSV.
hubbeam=$1 scene=$2 csv=$3
rm -f "$csv" "$(dirname "$csv")/.$(basename "$csv")".tmp-*
env --default-signal=INT "$hubbeam" run "$scene" --t-end 3000 -o "$csv" >/dev/null 2>&1 &
first=$!
tries=0
while [ $tries -lt 600 ]; do  # until the first run has its temporary file (and so its lock)
    for f in "$(dirname "$csv")"/."$(basename "$csv")".tmp-*; do
        [ -e "$f" ] && break 2
    done
    sleep 0.05
    tries=$((tries + 1))
done
err=$("$hubbeam" run "$scene" --t-end 1 -o "$csv" 2>&1 >/dev/null)
code=$?
kill -s TERM "$first"
wait "$first"
first_code=$?
status=0
if [ $code -ne 2 ]; then echo "second run: expected exit code 2, got $code ($err)"; status=1; fi
case $err in
    *"another hubbeam is writing $csv"*) ;;
    *) echo "second run: expected 'another hubbeam is writing $csv', got: $err"; status=1 ;;
esac
if [ $first_code -ne 143 ]; then echo "first run: expected exit code 143 (SIGTERM), got $first_code"; status=1; fi
if ! head -1 "$csv" 2>/dev/null | grep -q '^t,theta,'; then echo "first run: no CSV at $csv"; status=1; fi
for f in "$(dirname "$csv")"/."$(basename "$csv")".*; do
    [ -e "$f" ] && { echo "left behind: $f"; status=1; }
done
[ $status -eq 0 ] && echo "second writer refused, first run's CSV whole"
exit $status
