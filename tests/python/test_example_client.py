"""python.example_client: lib/python/examples/decode_client.py against a real
meshtopod inside the private network namespace of tests/netns/netns-run (the
test refuses to run outside it): the example records the session with
lcm-logger, decodes every logged event with meshtopo.decode_message,
reassembles a large answer from its reply_part_t pieces and compares it with
what meshtopo.Client returned. The daemon is started on the example's LCM URL
and stopped by its PID."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile

import pytest

pytestmark = pytest.mark.skipif(
    os.environ.get("MESHTOPO_NETNS") != "1",
    reason="runs only inside tests/netns/netns-run (a private network namespace)")

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLE = os.path.join(REPO, "lib", "python", "examples", "decode_client.py")
URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"


def test_decode_client_example():
    if not shutil.which("lcm-logger"):
        pytest.skip("lcm-logger not found (Debian: liblcm-bin)")
    daemon = os.environ.get("MESHTOPOD")
    if not daemon:
        pytest.fail("MESHTOPOD is not set: run the tests through ctest (python.example_client)")
    log = tempfile.NamedTemporaryFile(prefix="meshtopod-", suffix=".log", delete=False)
    proc = subprocess.Popen([daemon, "--lcm-url", URL, "--heartbeat-ms", "100", "--workers", "2"],
                            stdout=log, stderr=subprocess.STDOUT)
    try:
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            [os.environ.get("MESHTOPO_PYTHON_PATH", os.path.join(REPO, "lib", "python"))]
            + [p for p in [os.environ.get("PYTHONPATH")] if p]))
        run = subprocess.run([sys.executable, EXAMPLE, "--lcm-url", URL], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             timeout=90)
        print(run.stdout)
        assert run.returncode == 0, run.stdout
        assert "decode_client: OK" in run.stdout
        assert "a reply_t of 4096 items" in run.stdout
        assert "cut to" in run.stdout and "MT_ERR_CORRUPT" in run.stdout
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            rc = proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            rc = proc.wait()
        log.close()
        os.unlink(log.name)
    assert rc == 0, "meshtopod exited %s" % rc
