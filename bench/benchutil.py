"""Helpers shared by the bench/ Python scripts: paths, the reference inputs'
sizes (data README), child processes timed with their own peak RSS, medians,
machine load."""
import os
import subprocess
import sys
import tempfile
import threading
import time

BENCH = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(BENCH)
DATA = os.path.normpath(os.path.join(ROOT, "..", "shared", "data", "vascular"))
VESSELMESH = os.path.join(ROOT, "build", "vesselmesh")

# Uniform sizes of ../shared/data/vascular/README.md (h = 2 pi R / 20 of a
# median opening); the aortic arch also at its "fine" size 0.06.
SIZES = {
    "abdominal-aorta-closed.stl": [1.4],
    "abdominal-aorta-open.stl": [1.4],
    "aortic-arch.stl": [0.18, 0.06],
    "bifurcation.stl": [0.085],
    "carotid-metres.stl": [0.00042],
    "coronary-closed-ascii.stl": [0.6],
    "femoral-bypass.stl": [0.3],
}


def median(v):
    s = sorted(v)
    n = len(s)
    if n == 0:
        return float("nan")
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def loadavg():
    try:
        return os.getloadavg()
    except OSError:
        return (float("nan"),) * 3


GNU_TIME = "/usr/bin/time"


def run_measured(cmd, timeout=None, env=None, cwd=None):
    """Runs cmd; returns dict(rc, seconds (wall), cpu_seconds (user + system),
    peak_rss_mb of that command alone, stdout, stderr, timed_out).

    The peak RSS comes from GNU time (%M) when /usr/bin/time exists: a child
    forked by this Python process keeps the parent's pre-exec high-water
    mark in ru_maxrss (Linux carries it across exec), which would add the
    interpreter's own ~40 MB; GNU time forks from a tiny process. Without it,
    wait4's ru_maxrss is used and is an upper bound (rss_source says which)."""
    rss_file = None
    if os.access(GNU_TIME, os.X_OK):
        fd, rss_file = tempfile.mkstemp(prefix="bench-rss-")
        os.close(fd)
        cmd = [GNU_TIME, "-f", "%M %U %S", "-o", rss_file] + list(cmd)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=out, stderr=err, env=env, cwd=cwd)
        timed_out = []

        def kill():
            timed_out.append(True)
            p.kill()

        timer = threading.Timer(timeout, kill) if timeout else None
        if timer:
            timer.start()
        try:
            _, status, ru = os.wait4(p.pid, 0)
        finally:
            if timer:
                timer.cancel()
        dt = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        res = dict(rc=p.returncode, seconds=dt, peak_rss_mb=ru.ru_maxrss / 1024.0,
                   rss_source="wait4 (upper bound)", cpu_seconds=ru.ru_utime + ru.ru_stime,
                   stdout=out.read().decode(errors="replace"),
                   stderr=err.read().decode(errors="replace"), timed_out=bool(timed_out))
    if rss_file:
        try:
            with open(rss_file) as f:
                lines = [ln for ln in f.read().split("\n") if ln.strip()]
            # GNU time prints "Command exited with non-zero status N" first then.
            rss, user, system = lines[-1].split()
            res["peak_rss_mb"] = int(rss) / 1024.0
            res["cpu_seconds"] = float(user) + float(system)
            res["rss_source"] = "GNU time"
        except (OSError, ValueError, IndexError):
            pass
        os.remove(rss_file)
    return res


def have_gmsh(python=sys.executable):
    r = subprocess.run([python, "-c", "import gmsh"], capture_output=True)
    return r.returncode == 0


def machine():
    """One line about the machine: CPU model, cores, load."""
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for ln in f:
                if ln.startswith("model name"):
                    cpu = ln.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    la = loadavg()
    return f"{cpu}, {os.cpu_count()} cores, load average {la[0]:.2f} {la[1]:.2f} {la[2]:.2f}"
