#!/bin/sh
# Breaks the code on purpose to see whether a test notices: replaces one exact occurrence of OLD by NEW in FILE,
# rebuilds incrementally, runs the tests (all, or those whose names match REGEX), restores FILE whatever happens,
# and says KILLED (a test failed) or SURVIVED (every test passed: a wrong answer the suite lets through).
#
#   tests/mutate.sh FILE 'OLD' 'NEW' [REGEX]    one mutant; REGEX as for ctest -R
#   tests/mutate.sh --all [LIST]                 every mutant of LIST (default tests/mutants.txt), one line each
#
# Each line of LIST holds one call's arguments, quoted as in a shell (blank lines and # comments skipped).
# Run from anywhere; the build directory is BUILD (default build, as the release preset makes it), the targets
# rebuilt MUTATE_TARGETS (default hubbeam hubbeam_tests), the tests run MUTATE_JOBS at a time (default 2), each
# at most MUTATE_TIMEOUT seconds (default 600; a mutant that makes a test hang is killed by the timeout).
# Exit status: 0 killed, 1 survived, 2 bad use (OLD not found exactly once), 3 the mutant does not build;
# with --all, 0 when every mutant was killed, else 1.
set -u

root=$(cd "$(dirname "$0")/.." && pwd -P)
build=${BUILD:-$root/build}
case $build in /*) ;; *) build=$root/$build ;; esac
targets=${MUTATE_TARGETS:-hubbeam hubbeam_tests}
jobs=${MUTATE_JOBS:-2}
timeout=${MUTATE_TIMEOUT:-600}

usage() {
    echo "usage: tests/mutate.sh FILE 'OLD' 'NEW' [REGEX] | tests/mutate.sh --all [LIST]" >&2
    exit 2
}

# One mutant: FILE OLD NEW [REGEX]; prints one result line, returns 0 killed, 1 survived, 2 bad use, 3 no build.
mutate_one() {
    [ $# -ge 3 ] && [ $# -le 4 ] || usage
    file=$1
    case $file in /*) ;; *) file=$root/$file ;; esac
    regex=${4:-}
    [ -f "$file" ] || { echo "mutate.sh: $1: no such file" >&2; return 2; }
    backup=$(mktemp) || return 2
    cp "$file" "$backup" || return 2
    # Restored by writing the content back (not by moving the copy, which would keep the old time stamp and let the
    # build keep the mutant's object file): the next build compiles the original again.
    restore() {
        if [ -n "${backup:-}" ]; then
            cat "$backup" >"$file" && rm -f "$backup"
            backup=
        fi
    }
    trap restore EXIT
    trap 'restore; exit 130' INT
    trap 'restore; exit 143' TERM HUP

    # Exactly one occurrence, replaced literally (no regular expressions in OLD or NEW).
    /usr/bin/python3 -I -c '
import sys
path, old, new = sys.argv[1:4]
text = open(path, encoding="utf-8").read()
n = text.count(old)
if n != 1:
    sys.exit("mutate.sh: %s: %r occurs %d times, not once" % (path, old, n))
open(path, "w", encoding="utf-8").write(text.replace(old, new, 1))
' "$file" "$2" "$3" || { restore; return 2; }

    start=$(date +%s)
    label="${1}: '$2' -> '$3'"
    if ! cmake --build "$build" --target $targets -j "$jobs" >"$build/mutate-build.log" 2>&1; then
        restore
        printf 'NO BUILD  %s (see %s)\n' "$label" "$build/mutate-build.log"
        return 3
    fi
    if [ -n "$regex" ]; then
        set -- -R "$regex"
    else
        set --
    fi
    (cd "$build" && ctest -j "$jobs" --timeout "$timeout" "$@") >"$build/mutate-test.log" 2>&1
    status=$?
    restore
    seconds=$(($(date +%s) - start))
    if [ $status -eq 0 ]; then
        if grep -q "No tests were found" "$build/mutate-test.log"; then
            printf "mutate.sh: no test matches '%s'\n" "$regex" >&2
            return 2
        fi
        printf 'SURVIVED  %s (%s s)\n' "$label" "$seconds"
        return 1
    fi
    failed=$(sed -n '/tests FAILED:/,$s/^[[:space:]]*[0-9]* - \(.*\) ([^)]*)$/\1/p' "$build/mutate-test.log" |
        sed 's/$/;/' | paste -sd' ' - | sed 's/;$//')
    printf 'KILLED    %s (%s s) by: %s\n' "$label" "$seconds" "$failed"
    return 0
}

if [ "${1:-}" = "--all" ]; then
    [ $# -le 2 ] || usage
    list=${2:-$root/tests/mutants.txt}
    survived=0
    while IFS= read -r line <&3; do
        case $line in '' | '#'*) continue ;; esac
        eval "set -- $line"
        (mutate_one "$@")
        [ $? -eq 0 ] || survived=1
    done 3<"$list"
    # The sources are the original again: leave the build matching them.
    cmake --build "$build" --target $targets -j "$jobs" >"$build/mutate-build.log" 2>&1
    exit $survived
fi
mutate_one "$@"
status=$?
# The build holds the mutant's objects until the next build; rebuild now so that nothing else runs them.
cmake --build "$build" --target $targets -j "$jobs" >"$build/mutate-build.log" 2>&1
exit $status
