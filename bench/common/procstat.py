"""One measured child process for the Python benchmarks (bench/memory, bench/outofcore).

run() starts argv, optionally samples it while it runs (e.g. its PSS), and returns its wall time,
its own peak RSS from wait4's rusage (the kernel's high-water mark of that process alone), its
exit code and its stderr. Both benchmarks take their figures from here, so they measure alike.
The kernel counts into a child's high-water mark the memory it had before exec, i.e. this Python
process's (~12 MB), so peak RSS below that floor reads as the floor (`/bin/true` reads 12 MB here,
876 kB under /usr/bin/time); geokiosk's smallest workload, `--version`, is above it (13.4 MB here,
13.2 MB under /usr/bin/time).
"""
import os
import subprocess
import time

# llvmpipe through Mesa's EGL vendor, whatever else the machine has installed.
MESA_ENV = dict(os.environ,
                __EGL_VENDOR_LIBRARY_FILENAMES="/usr/share/glvnd/egl_vendor.d/50_mesa.json",
                GALLIUM_DRIVER="llvmpipe")


def pss_kb(pid):
    """Proportional set size of a live process (kB; 0 once it is gone)."""
    try:
        with open(f"/proc/{pid}/smaps_rollup") as f:
            for line in f:
                if line.startswith("Pss:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def run(argv, cwd=None, env=None, sample=None, every=0.02):
    """Run argv to its end. With `sample` (a function of the pid), call it every `every` s while
    the child runs and keep the largest value. Returns a dict: wall_s, peak_rss_mb, exit,
    stderr, sampled_max (None without `sample`)."""
    t0 = time.monotonic()
    p = subprocess.Popen([str(a) for a in argv], cwd=cwd, env=env or MESA_ENV,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    peak = None
    while True:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG if sample else 0)
        if pid:
            break
        value = sample(p.pid)
        peak = value if peak is None else max(peak, value)
        time.sleep(every)
    wall = time.monotonic() - t0
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    return {"wall_s": wall, "peak_rss_mb": round(usage.ru_maxrss / 1024.0, 1),
            "exit": os.waitstatus_to_exitcode(status), "stderr": err, "sampled_max": peak}
