"""The local cluster a sweep starts for itself: it refuses clients without the sweep's credentials, listens on
loopback only, serves a dashboard only when asked, ends cleanly on SIGTERM, and works from a script without an
`if __name__ == "__main__":` guard, from `python3 -c` (as a notebook: no file behind __main__) and from stdin.
Needs HUBBEAM and SOURCE_DIR."""
import os
import re
import select
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import psutil

HUBBEAM = os.environ["HUBBEAM"]
SOURCE = os.environ["SOURCE_DIR"]
SPINUP = os.path.join(SOURCE, "cases", "spinup_omega4.toml")


def wait_for_line(child, pattern, timeout):
    """The first line of the child's standard error that matches pattern (the lines before it are kept)."""
    seen = []
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        # Wait for output no longer than the time left: a child that prints nothing must not hang the test.
        if not select.select([child.stderr], [], [], max(0.0, end - time.monotonic()))[0]:
            break
        line = child.stderr.readline().decode()  # unbuffered: select() sees every byte not yet read
        if not line:
            break
        seen.append(line)
        m = re.search(pattern, line)
        if m:
            return m, seen
    raise AssertionError(f"no line matching {pattern!r} within {timeout} s: {''.join(seen)}")


def listening(pid):
    """(address, port) of every TCP socket the process listens on."""
    return {(c.laddr.ip, c.laddr.port) for c in psutil.Process(pid).connections(kind="inet")
            if c.status == psutil.CONN_LISTEN}


class LocalClusterTest(unittest.TestCase):
    def test_other_clients_are_refused_and_only_loopback_listens(self):
        from distributed import Client

        with tempfile.TemporaryDirectory() as d:
            # One point that runs for minutes, so the cluster is up while it is probed; with and without --dashboard.
            spec = os.path.join(d, "long.toml")
            with open(spec, "w") as f:
                f.write(f'scene = "{SPINUP}"\n[set]\nnx = 0\n"output.t_end" = 1e6\n"output.dt_out" = 1.0\n'
                        f'"solver.max_steps" = 1e12\n')
            children = [subprocess.Popen([HUBBEAM, "sweep", spec, "-o", os.path.join(d, f"{n}.csv"), "--workers", "1",
                                          *extra], stderr=subprocess.PIPE, bufsize=0)
                        for n, extra in (("plain", []), ("dashboard", ["--dashboard"]))]
            try:
                lines = [wait_for_line(c, r"local cluster at (\S+)", 90)[0] for c in children]
                address = lines[0].group(1)
                self.assertTrue(address.startswith("tls://127.0.0.1:"), address)
                for attempt in (address, address.replace("tls://", "tcp://")):
                    start = time.monotonic()
                    with self.assertRaises((OSError, TypeError, ValueError), msg=attempt):
                        Client(attempt, timeout=3).run(os.getuid)
                    self.assertLess(time.monotonic() - start, 20)
                plain, with_dashboard = (listening(c.pid) for c in children)
                for sockets in (plain, with_dashboard):
                    self.assertTrue(sockets)
                    self.assertEqual({ip for ip, _ in sockets}, {"127.0.0.1"}, sockets)
                self.assertNotIn("dashboard", lines[0].string)
                self.assertNotIn(8787, {port for _, port in plain})
                dashboard = re.search(r"dashboard http://127\.0\.0\.1:(\d+)/", lines[1].string)
                self.assertIsNotNone(dashboard, lines[1].string)
                self.assertIn(int(dashboard.group(1)), {port for _, port in with_dashboard})
            finally:
                for c in children:
                    c.send_signal(signal.SIGTERM)
                results = []
                for c in children:
                    try:
                        code = c.wait(timeout=30)
                    except subprocess.TimeoutExpired:  # not ended by SIGTERM: fail, but leave nothing running
                        c.kill()
                        code = c.wait()
                    results.append((code, c.stderr.read().decode()))
            for code, err in results:
                self.assertEqual(code, 143, err)
                self.assertIn("terminated", err)
                self.assertNotIn("leaked", err)  # multiprocessing's resource tracker: no semaphore left behind
                self.assertNotIn("Traceback", err)


class InvocationTest(unittest.TestCase):
    def test_a_script_without_a_guard_a_notebook_and_stdin(self):
        code = ("import hubbeam\n"
                f"table = hubbeam.sweep({{'scene': {SPINUP!r}, 'set': {{'output.t_end': 1.0}}, "
                "'grid': {'ny': [4, 6]}, 'keep': ['max_abs_tip_uy', 'steps']}, output='t.csv', workers=2)\n"
                "print(*(type(r[k]).__name__ for r in table for k in ('max_abs_tip_uy', 'steps', 'status')))\n")
        # A notebook's cell: code without a file behind __main__, run while an event loop runs (as in a kernel).
        cell = "import asyncio\nasync def cell():\n" + "".join("    " + line + "\n" for line in code.splitlines()) + \
            "asyncio.run(cell())\n"
        with tempfile.TemporaryDirectory() as d:
            folders = [os.path.join(d, n) for n in ("script", "notebook", "stdin")]
            for f in folders:
                os.mkdir(f)
            script = os.path.join(folders[0], "unguarded.py")
            with open(script, "w") as f:
                f.write(code)
            forms = [([sys.executable, script], None), ([sys.executable, "-c", cell], None),
                     ([sys.executable, "-"], code)]
            children = [subprocess.Popen(command, cwd=folder, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=subprocess.PIPE, text=True)
                        for (command, _), folder in zip(forms, folders)]
            for child, (_, given) in zip(children, forms):
                if given:
                    child.stdin.write(given)
                child.stdin.close()
            for child, (command, _) in zip(children, forms):
                try:
                    child.wait(timeout=120)
                except subprocess.TimeoutExpired:
                    for c in children:
                        c.kill()
                    self.fail(f"{command}: no result within 120 s")
                out, err = child.stdout.read(), child.stderr.read()
                self.assertEqual(child.returncode, 0, f"{command}: {err}")
                self.assertEqual(out.split(), ["float", "int", "str"] * 2, command)
                self.assertLess(len(err.splitlines()), 10, err)  # no storm of restarted workers
                # The closing line gives absolute seconds and what they include, no percentage over 2 points.
                last = err.strip().splitlines()[-1]
                self.assertRegex(last, r"^sweep: 2 points in [0-9.]+ s on 2 workers, after [0-9.]+ s to start")
                self.assertNotIn("%", last)


if __name__ == "__main__":
    unittest.main()
