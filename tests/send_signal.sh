#!/bin/sh
# Runs a command, waits until it has created the temporary file of its CSV (so its signal handlers are in
# place and rows are being written), lets it run 0.3 s more, then sends it a signal and returns its exit
# status. Usage: send_signal.sh SIGNAL CSV COMMAND [ARG...]. A fixed delay raced the process's start-up on a
# loaded machine: a signal before the handlers exist kills it with nothing written, correctly, but untested.
sig=$1 csv=$2
shift 2
# A shell starts background jobs with SIGINT and SIGQUIT ignored: coreutils' env gives the command their defaults
# back.
env --default-signal=INT,QUIT "$@" &
pid=$!
tries=0
while [ $tries -lt 600 ]; do
    for f in "$(dirname "$csv")"/."$(basename "$csv")".tmp-*; do
        [ -e "$f" ] && break 2
    done
    sleep 0.05
    tries=$((tries + 1))
done
sleep 0.3
kill -s "$sig" "$pid"
# A run that ignores the signal is killed after 20 s (and fails its test) instead of running on.
# (Its output goes nowhere: holding the test's pipes, its sleep would make the test wait the 20 s out.)
( sleep 20; kill -s KILL "$pid" 2>/dev/null ) >/dev/null 2>&1 &
watchdog=$!
wait "$pid"
status=$?
kill "$watchdog" 2>/dev/null
exit $status
