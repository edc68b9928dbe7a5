"""Start a command from a small process and report its resource use (issue #27's fuzz).

Linux charges a child's peak resident set from its parent's pages until it execs (the
kernel keeps the larger of the forked image's and the new program's high-water marks), so a
``gear3d`` started directly by a pytest worker that has loaded OpenCascade reports the
worker's 300 MiB as its own peak. This launcher runs as its own small interpreter
(``python -S``, about 10 MB), starts the command from there with a CPU-time cap (the hang
guard), waits for it with ``os.wait4`` and prints ``rc cpu_seconds maxrss_kib`` on its
stdout: the measurement of the command's own process tree only.

Usage: ``python -S launch.py CPU_CAP_S ARGV...`` (the command's stdin, stdout and stderr are
the launcher's stdin, the file descriptor named by ``GEAR3D_LAUNCH_OUT`` and its stderr).
"""
import os
import resource
import sys


def main() -> None:
    cap = int(float(sys.argv[1]))
    out_fd = int(os.environ.pop("GEAR3D_LAUNCH_OUT"))
    pid = os.fork()
    if pid == 0:
        resource.setrlimit(resource.RLIMIT_CPU, (cap, cap + 5))
        os.dup2(out_fd, 1)
        os.execvp(sys.argv[2], sys.argv[2:])
    _, status, ru = os.wait4(pid, 0)
    sys.stdout.write(f"{os.waitstatus_to_exitcode(status)} {ru.ru_utime + ru.ru_stime!r} {ru.ru_maxrss}\n")


if __name__ == "__main__":
    main()
