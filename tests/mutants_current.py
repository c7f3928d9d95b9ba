"""Every mutant of tests/mutants.txt names code that is there: its OLD text occurs exactly once in its FILE, as
tests/mutate.sh requires. A refactor that rewrites a guarded line makes its mutant stale (mutate.sh --all then says
"occurs 0 times" long after); this test says so at once, without building anything."""
import os
import shlex
import sys

root = sys.argv[1]
stale = []
with open(os.path.join(root, "tests", "mutants.txt"), encoding="utf-8") as f:
    for number, line in enumerate(f, 1):
        if not line.strip() or line.startswith("#"):
            continue
        parts = shlex.split(line)
        if not 3 <= len(parts) <= 4:
            stale.append(f"tests/mutants.txt:{number}: expected FILE 'OLD' 'NEW' [REGEX], got {len(parts)} fields")
            continue
        path, old = os.path.join(root, parts[0]), parts[1]
        try:
            with open(path, encoding="utf-8") as source:
                count = source.read().count(old)
        except OSError as e:
            stale.append(f"tests/mutants.txt:{number}: {parts[0]}: {e.strerror}")
            continue
        if count != 1:
            stale.append(f"tests/mutants.txt:{number}: {parts[0]}: its OLD text occurs {count} times, not once")
print("\n".join(stale) if stale else "every mutant names code that is there")
sys.exit(1 if stale else 0)
