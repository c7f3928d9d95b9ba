"""Where a sweep runs: a local Dask cluster in this process or a client of a running scheduler, Dask's own
configuration left out for `hubbeam sweep`, and the progress shown while the points finish."""
from __future__ import annotations

import logging
import os
import socket
import sys
import time
from typing import Any

from .sweep_spec import SweepError, _printable


def _notebook_bar(total: int, before: int):
    """A tqdm progress bar where the sweep runs in a notebook (an IPython kernel, whose standard error is no terminal
    to rewrite a line on) and tqdm is installed (python3-tqdm); else None. tqdm's widget where ipywidgets is there
    too, its text bar otherwise."""
    if "ipykernel" not in sys.modules:
        return None
    try:
        try:
            import ipywidgets  # noqa: F401  (tqdm.notebook draws with it)
            from tqdm.notebook import tqdm
        except ImportError:
            from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, initial=before, desc="sweep", unit="point", file=sys.stderr)


class _Progress:
    """One line on standard error per finished point, rewritten in place on a terminal; a tqdm bar in a notebook."""

    def __init__(self, total: int, before: int, enabled: bool):
        self.total, self.before, self.enabled = total, before, enabled
        self.done = self.failed = 0
        self.start = time.perf_counter()
        self.tty = enabled and sys.stderr.isatty()
        self.bar = _notebook_bar(total, before) if enabled else None

    def point(self, ok: bool) -> None:
        self.done += 1
        self.failed += 0 if ok else 1
        if self.bar is not None:
            self.bar.update(1)
            if self.failed:
                self.bar.set_postfix(not_ok=self.failed)
            return
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        left = elapsed / self.done * (self.total - self.before - self.done)
        line = (f"sweep: {self.before + self.done} of {self.total} points ({self.before} from before), "
                f"{self.failed} not ok, {elapsed:.1f} s, about {left:.0f} s left")
        print(("\r" + line + "\033[K") if self.tty else line, end="" if self.tty else "\n", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.tty and self.done:
            print(file=sys.stderr)


def _import_hubbeam() -> str:
    import hubbeam

    return hubbeam.__version__


def local_cluster(workers: int | None = None, dashboard: bool = False):
    """A local Dask cluster for sweeps and a client of it: (client, close). One worker with `workers` threads (one
    per core by default) in this process: the runs release the GIL, so threads run in parallel, and no process is
    spawned (a script without an `if __name__ == "__main__":` guard, a notebook and stdin work alike). Its scheduler
    and worker listen on 127.0.0.1 only, speak TLS with credentials made for this cluster alone (a client without
    them is refused), and the dashboard is off unless asked for (then on 127.0.0.1:8787, or a free port)."""
    from distributed import Client, Scheduler, SpecCluster, Worker
    from distributed.security import Security

    security = Security.temporary()  # a fresh CA and certificates, in memory, for this cluster only
    common = {"host": "127.0.0.1", "protocol": "tls://", "security": security}
    # Every HTTP server on loopback: Dask's default address for them is every interface.
    scheduler = {"cls": Scheduler, "options": {**common, "dashboard": dashboard,
                                               "dashboard_address": "127.0.0.1:8787" if dashboard else "127.0.0.1:0"}}
    worker = {"cls": Worker, "options": {**common, "nthreads": workers or os.cpu_count() or 1, "dashboard": False,
                                         "dashboard_address": "127.0.0.1:0"}}
    cluster = SpecCluster(scheduler=scheduler, workers={0: worker}, security=security, silence_logs=logging.CRITICAL)
    try:
        client = Client(cluster, security=security)
    except BaseException:
        cluster.close()
        raise

    def close() -> None:
        # Shutting the cluster down on a loaded machine can time out inside Dask's event loop; the table is complete
        # (or as complete as it will be) by then, so that is no failure of the sweep, and asyncio's report of it
        # ("Future exception was never retrieved") is not printed.
        quiet = logging.getLogger("asyncio")
        level = quiet.level
        quiet.setLevel(logging.CRITICAL)
        try:
            for step in (client.close, cluster.close):
                try:
                    step()
                except Exception:  # noqa: BLE001 - see above
                    pass
        finally:
            quiet.setLevel(level)

    return client, close


def _tcp_reachable(address: str) -> str | None:
    """None if a TCP connection to the scheduler's host and port opens within 3 s, else why not."""
    host_port = address.split("://", 1)[-1]
    host, _, port = host_port.rpartition(":")
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=3):
            return None
    except ValueError:
        return "expected host:port after the protocol"
    except OSError as e:
        return e.strerror or str(e) or type(e).__name__


def _remote_client(scheduler: str, security: Any):
    """A client of the scheduler at its address, or SweepError within a few seconds naming what is wrong."""
    from distributed import Client

    shown = _printable(scheduler)
    protocol = scheduler.split("://", 1)[0] if "://" in scheduler else "tcp"
    if protocol not in ("tcp", "tls"):
        raise SweepError(f"--scheduler: expected a tls://host:port or tcp://host:port address, got {shown}")
    if protocol == "tls" and security is None:
        raise SweepError(f"--scheduler: expected the cluster's certificates for {shown} (--tls-ca-file, --tls-cert, "
                         f"--tls-key; security= in Python)")
    if protocol == "tcp":
        print(f"hubbeam: warning: {shown} is a plain tcp:// scheduler: it runs whatever any client that reaches it "
              f"sends, as the workers' user; use tls:// with certificates (docs/python.md, Security)", file=sys.stderr)
    why = _tcp_reachable(scheduler)
    if why is not None:
        raise SweepError(f"--scheduler: cannot reach {shown}: {why}")
    try:
        return Client(scheduler, security=security, timeout=10)
    except (OSError, TimeoutError) as e:
        raise SweepError(f"--scheduler: cannot connect to {shown}: {_printable(e, 200)}") from None


def _security_of_files(ca: str | None, cert: str | None, key: str | None):
    """A Security for a tls:// scheduler from the CA's certificate and this client's certificate and key."""
    given = {"--tls-ca-file": ca, "--tls-cert": cert, "--tls-key": key}
    if not any(given.values()):
        return None
    for option, path in given.items():
        if not path:
            raise SweepError(f"{option}: expected a PEM file (a tls:// scheduler needs all three of --tls-ca-file, "
                             f"--tls-cert, --tls-key), got nothing")
        if not os.path.isfile(path):
            raise SweepError(f"{option}: cannot open {_printable(path)}: expected a PEM file")
    from distributed.security import Security

    return Security(tls_ca_file=ca, tls_client_cert=cert, tls_client_key=key, require_encryption=True)


def _connect(scheduler: Any, workers: int | None, dashboard: bool, security: Any, progress: bool):
    """The sweep's client and what closes it, None for the caller's own client (theirs to close): a local cluster
    without a scheduler, else a client of the scheduler's address, else the distributed.Client given."""
    if scheduler is None:
        client, close = local_cluster(workers, dashboard)
        if progress:
            print(f"sweep: local cluster at {client.scheduler.address} (TLS, this sweep's certificates only)"
                  + (f", dashboard {client.dashboard_link}" if dashboard else ""), file=sys.stderr, flush=True)
        return client, close
    if isinstance(scheduler, (str, os.PathLike)):
        client = _remote_client(os.fspath(scheduler), security)
        return client, client.close
    if hasattr(scheduler, "submit") and hasattr(scheduler, "scheduler_info"):
        return scheduler, None  # the caller's distributed.Client: theirs to close
    raise SweepError(f"scheduler: expected an address or a distributed.Client, got "
                     f"{_printable(type(scheduler).__name__)}")


def _ignore_dask_configuration() -> None:
    """Dask with its own defaults only, for `hubbeam sweep`: no configuration file (~/.config/dask, $DASK_CONFIG,
    /etc/dask) and no DASK_* variable is read. Dask's configuration can name Python to run in this process (a
    scheduler's, worker's or client's "preload": a module, a file, a URL), and `hubbeam sweep` runs only hubbeam's
    Python (its interpreter is isolated, python3 -I). Importing dask.config reads the files: where this runs first
    (as in `hubbeam sweep`) it is imported with HOME and DASK_ROOT_CONFIG pointing at an empty private folder, so
    that none is even parsed; in any case the configuration is then reset to the defaults and the search path
    emptied for any later refresh, before a scheduler, worker or client reads it."""
    import shutil
    import tempfile
    import warnings

    for name in [n for n in os.environ if n.startswith("DASK_")]:
        del os.environ[name]
    if "dask.config" not in sys.modules:
        empty = tempfile.mkdtemp(prefix="hubbeam-no-dask-config-")
        home = os.environ.get("HOME")
        os.environ.update(HOME=empty, DASK_ROOT_CONFIG=empty)
        try:
            # dask.config reads every DASK_* value through ast.literal_eval, ours too: a folder name whose random
            # part begins with a digit and a letter ("...-config-8k...") made Python print "SyntaxWarning: invalid
            # decimal literal" on stderr.
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", SyntaxWarning)
                import dask.config  # noqa: F401
        finally:
            del os.environ["DASK_ROOT_CONFIG"]
            if home is None:
                del os.environ["HOME"]
            else:
                os.environ["HOME"] = home  # the variant cache's default folder is under it
            shutil.rmtree(empty, ignore_errors=True)
    import dask.config

    dask.config.paths[:] = []  # collect()'s default: a later refresh() reads no file either
    dask.config.refresh(paths=[], env={})

