#!/bin/sh
# As root: an output named through a link that another user planted in a sticky, world-writable folder (the case of
# /tmp) is refused, exit 2, and the file the link names, another user's, is untouched. Skipped (77) unless root.
# Usage: sticky_link.sh HUBBEAM SCENE FOLDER (emptied first).
hubbeam=$1 scene=$2 dir=$3
[ "$(id -u)" = 0 ] || exit 77
rm -rf "$dir"
mkdir -p "$dir/sticky"
chmod 1777 "$dir/sticky"
echo "nobody's data" > "$dir/victim.csv"
chown nobody "$dir/victim.csv"
ln -s "$dir/victim.csv" "$dir/sticky/out.csv"
chown -h nobody "$dir/sticky/out.csv"
err=$("$hubbeam" run "$scene" --t-end 0.1 -o "$dir/sticky/out.csv" 2>&1 >/dev/null)
code=$?
[ "$code" = 2 ] || { echo "expected exit 2, got $code: $err"; exit 1; }
echo "$err" | grep -q "out.csv is a symbolic link: hubbeam does not write through a link" ||
    { echo "unexpected message: $err"; exit 1; }
[ "$(cat "$dir/victim.csv")" = "nobody's data" ] || { echo "the file the link names was replaced"; exit 1; }
[ -z "$(ls -A "$dir/sticky" | grep -v '^out.csv$')" ] || { echo "files left: $(ls -A "$dir/sticky")"; exit 1; }
