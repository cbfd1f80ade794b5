#!/usr/bin/env python3
"""Runs the GoogleTest tests that ctest selects, one process per test executable instead of one
per test (test-all.sh's sanitized stage): under AddressSanitizer each process costs 0.2-0.6 s of
start-up and leak check, about 600 of them most of two minutes of CI's wall time
(docs/studies/build_time.md).

    run_tests_per_executable.py --build build-asan --jobs 2 -- -L unit -E 'Heavy.Test|Other.Test'

The arguments after -- select tests as they would for ctest. Each executable runs its selected
tests in one process (a --gtest_filter of their names) with the environment and working
directory ctest gives them; `jobs` executables run at a time, the ones with most tests first.
Exit 0 when every executable passes, 1 when one fails (its output is printed), 2 on bad input.
"""
import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor


def selected_tests(build, ctest_args):
    try:
        out = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1", *ctest_args], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"run_tests_per_executable.py: error: ctest --test-dir {build}: {e}", file=sys.stderr)
        sys.exit(2)
    groups = {}
    for t in json.loads(out)["tests"]:
        cmd = t["command"]
        names = [a.split("=", 1)[1] for a in cmd[1:] if a.startswith("--gtest_filter=")]
        if not names:
            print(f"run_tests_per_executable.py: error: test {t['name']} is not a GoogleTest test", file=sys.stderr)
            sys.exit(2)
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        if props.get("DISABLED"):  # a DISABLED_ GoogleTest test: ctest does not run it either
            continue
        env = tuple(props.get("ENVIRONMENT", []))
        key = (cmd[0], env, props.get("WORKING_DIRECTORY", build))
        groups.setdefault(key, []).append(names[0])
    return groups


def run(key, names, timeout):
    exe, env, cwd = key
    environ = dict(os.environ)
    for assignment in env:
        k, v = assignment.split("=", 1)
        environ[k] = v
    start = time.monotonic()
    try:
        p = subprocess.run([exe, "--gtest_filter=" + ":".join(names)], cwd=cwd, env=environ, capture_output=True,
                           text=True, timeout=timeout)
        ok, output = p.returncode == 0, p.stdout + p.stderr
    except subprocess.TimeoutExpired as e:
        ok, output = False, f"timed out after {timeout} s\n{e.stdout or ''}"
    return exe, len(names), ok, output, time.monotonic() - start


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", required=True)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--timeout", type=int, default=3600, help="seconds per executable")
    p.add_argument("ctest_args", nargs=argparse.REMAINDER)
    a = p.parse_args()
    args = a.ctest_args[1:] if a.ctest_args[:1] == ["--"] else a.ctest_args
    groups = selected_tests(a.build, args)
    order = sorted(groups, key=lambda k: -len(groups[k]))
    failed = 0
    total = sum(len(v) for v in groups.values())
    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for exe, n, ok, output, seconds in pool.map(lambda k: run(k, groups[k], a.timeout), order):
            print(f"{'passed' if ok else 'FAILED'}: {os.path.basename(exe)}, {n} tests, {seconds:.1f} s", flush=True)
            if not ok:
                failed += 1
                print(output)
    print(f"{total} tests in {len(groups)} processes: {'all passed' if failed == 0 else f'{failed} processes failed'}")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
