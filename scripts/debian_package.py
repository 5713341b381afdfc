"""Installs a Debian package a benchmark needs (LAMMPS, YADE) when its
command is missing: the benchmarks' own scripts do this on demand, so
`make test` never needs them."""
import os
import shutil
import subprocess
import sys


def ensure(package, command, who):
    if shutil.which(command):
        return
    if os.geteuid() != 0:
        sys.exit(f"{who}: {command} (Debian package {package}) is missing; install it as root: apt-get install {package}")
    print(f"{who}: installing Debian's {package}", file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(["apt-get", "install", "-y", "-qq", "--no-install-recommends", package], check=True, env=env,
                   stdout=subprocess.DEVNULL)


def version(package):
    """The installed version, or a note that it is not a Debian package."""
    out = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", package], capture_output=True, text=True)
    return out.stdout.strip() if out.returncode == 0 and out.stdout.strip() else "(not a Debian package)"
