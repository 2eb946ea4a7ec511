"""What the benchmark ran on: CPU, memory, kernel, compiler, build, commit, date."""
import datetime
import os
import platform
import subprocess
from pathlib import Path


def _first_value(path, key, separator=":"):
    """Value of the first 'key: value' line of a /proc-style file, or None."""
    try:
        for line in Path(path).read_text(errors="replace").splitlines():
            name, _, value = line.partition(separator)
            if name.strip() == key:
                return value.strip()
    except OSError:
        pass
    return None


def _cmake_cache(build_dir, key):
    try:
        for line in (Path(build_dir) / "CMakeCache.txt").read_text().splitlines():
            if line.startswith(key + ":"):
                return line.partition("=")[2]
    except OSError:
        pass
    return None


def _output(argv, cwd=None):
    try:
        return subprocess.run(argv, cwd=cwd, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def _compiler(build_dir):
    compiler = _cmake_cache(build_dir, "CMAKE_CXX_COMPILER")
    version = _output([compiler, "--version"]) if compiler else None
    return version.splitlines()[0] if version else "unknown"


def _commit(repo):
    commit = _output(["git", "rev-parse", "--short=10", "HEAD"], cwd=repo)
    if commit is None:
        return "unknown"
    dirty = _output(["git", "status", "--porcelain", "--untracked-files=no"], cwd=repo)
    return commit + (" (with uncommitted changes)" if dirty else "")


def _os_name():
    name = _first_value("/etc/os-release", "PRETTY_NAME", separator="=")
    return name.strip('"') if name else platform.system()


def describe(build_dir, repo):
    memory_kib = _first_value("/proc/meminfo", "MemTotal")
    memory = f"{int(memory_kib.split()[0]) / 2**20:.1f} GiB" if memory_kib else "unknown"
    return {
        "cpu": _first_value("/proc/cpuinfo", "model name") or platform.processor() or "unknown",
        "cores": os.cpu_count(),
        "memory": memory,
        "os": _os_name(),
        "kernel": platform.release(),
        "compiler": _compiler(build_dir),
        "build_type": _cmake_cache(build_dir, "CMAKE_BUILD_TYPE") or "unknown",
        "commit": _commit(repo),
        "date": datetime.datetime.now().astimezone().isoformat(timespec="minutes"),
    }
