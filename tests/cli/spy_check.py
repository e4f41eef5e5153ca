#!/usr/bin/env python3
"""cli.spy: `meshtopo spy` starts lcm-spy with the meshtopo message types.

Run inside netns-run (lcm-spy joins udpm on a private lo). Checks `--help`,
the errors for a missing java and an unreadable $MESHTOPO_MSGS_JAR (exit 3,
naming what is missing), then starts `meshtopo spy --lcm-url URL` under
`xvfb-run -a` with the build tree's jar found by the compiled-in path, and
waits until lcm-spy has printed "Found N LCM types" (N = the number of .lcm
files; lcm.jar alone holds none) and "Found K plugins" (printed after its
window was made). Then stops the spy by its PID (SIGTERM, SIGKILL after a
grace period) and expects xvfb-run to end. Exit 77 when java or xvfb-run is
absent.

usage: spy_check.py --meshtopo PATH --types N
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

CALL_TIMEOUT = 30  # seconds for any one short CLI run
STARTUP_TIMEOUT = 15  # seconds for lcm-spy to load the types and open its window
GRACE = 5  # seconds between SIGTERM and SIGKILL
SKIP = 77
URL = "udpm://239.255.76.67:7667?ttl=0"
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def run(cmd, env=None):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, timeout=CALL_TIMEOUT, env=env)
    except subprocess.TimeoutExpired:
        check(False, "did not finish within %d s: %s" % (CALL_TIMEOUT, " ".join(cmd)))
        return None


def env_without_jar(**extra):
    env = dict(os.environ)
    env.pop("MESHTOPO_MSGS_JAR", None)
    env.update(extra)
    return env


def check_usage(cli):
    p = run([cli, "spy", "--help"])
    if p:
        check(p.returncode == 0 and "lcm-spy" in p.stdout and "--lcm-url" in p.stdout,
              "meshtopo spy --help exits 0 and describes lcm-spy and --lcm-url")
    p = run([cli, "--help"])
    if p:
        check(p.returncode == 0 and re.search(r"^\s+spy\s", p.stdout, re.M),
              "meshtopo --help lists spy")
    p = run([cli, "spy", "extra"])
    if p:
        check(p.returncode == 2, "meshtopo spy with a positional argument exits 2")
    with tempfile.TemporaryDirectory() as empty:
        p = run([cli, "spy"], env=env_without_jar(PATH=empty))
        if p:
            check(p.returncode == 3 and "java" in p.stderr and "default-jre" in p.stderr,
                  "without java on PATH: exit 3 naming java and default-jre (%r)"
                  % p.stderr.strip())


def check_no_display(cli):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    p = run([cli, "spy"], env=env)
    if p:
        check(p.returncode == 3 and "no display" in p.stderr and "Exception" not in p.stderr,
              "without a display: exit 3 and a sentence, no Java stack trace (%r)"
              % p.stderr.strip())


def check_bad_jar(cli):
    missing = "/nonexistent/meshtopo-msgs.jar"
    p = run([cli, "spy"], env=env_without_jar(MESHTOPO_MSGS_JAR=missing))
    if p:
        check(p.returncode == 3 and missing in p.stderr and "MESHTOPO_MSGS_JAR" in p.stderr,
              "unreadable $MESHTOPO_MSGS_JAR: exit 3 naming it (%r)" % p.stderr.strip())


def stop_group(proc):
    """Last resort: the process group of the xvfb-run we started (its own session)."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        if proc.poll() is not None:
            return
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return
        try:
            proc.wait(timeout=GRACE)
        except subprocess.TimeoutExpired:
            pass


def check_spy(cli, types):
    # The shell prints its PID, then becomes `meshtopo spy`, which becomes java:
    # that PID is the spy's.
    cmd = ["xvfb-run", "-a", "sh", "-c", 'echo "spy-pid $$"; exec "$0" spy --lcm-url "$1"',
           cli, URL]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=env_without_jar(), start_new_session=True)
    lines = []
    reader = threading.Thread(target=lambda: lines.extend(proc.stdout), daemon=True)
    reader.start()
    try:
        deadline = time.monotonic() + STARTUP_TIMEOUT
        spy_pid = found_types = found_plugins = None
        while time.monotonic() < deadline and proc.poll() is None:
            for line in list(lines):
                m = re.match(r"spy-pid (\d+)", line)
                if m:
                    spy_pid = int(m.group(1))
                m = re.match(r"Found (\d+) LCM types", line)
                if m:
                    found_types = int(m.group(1))
                if re.match(r"Found \d+ plugins", line):
                    found_plugins = True
            if spy_pid and found_types is not None and found_plugins:
                break
            time.sleep(0.1)
        output = "".join(lines)
        check(proc.poll() is None, "lcm-spy is still running after start-up")
        check(found_types == types,
              "lcm-spy found %d LCM types (the meshtopo messages): %s" % (types, found_types))
        check(bool(found_plugins), "lcm-spy opened its window (printed 'Found K plugins')")
        check("Exception" not in output and "Unrecognized option" not in output,
              "no Java exception or refused JVM option in lcm-spy's output")
        if spy_pid and proc.poll() is None:
            os.kill(spy_pid, signal.SIGTERM)
            try:
                proc.wait(timeout=GRACE)
                check(True, "SIGTERM to the spy (pid %d) stopped it and xvfb-run" % spy_pid)
            except subprocess.TimeoutExpired:
                check(False, "the spy (pid %d) still running %d s after SIGTERM" % (spy_pid, GRACE))
    finally:
        stop_group(proc)
        reader.join(timeout=GRACE)
    if failures:
        sys.stdout.write("---- output of xvfb-run meshtopo spy ----\n" + "".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--types", type=int, required=True, help="number of meshtopo message types")
    a = ap.parse_args()
    check_usage(a.meshtopo)
    java = shutil.which("java")
    xvfb = shutil.which("xvfb-run")
    if java:
        check_bad_jar(a.meshtopo)
        check_no_display(a.meshtopo)
    if not java or not xvfb:
        print("skip: %s not found (Debian: %s)" % (
            "java" if not java else "xvfb-run", "default-jre" if not java else "xvfb xauth"))
        return 1 if failures else SKIP
    check_spy(a.meshtopo, a.types)
    print("%d failure(s)" % len(failures) if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
