#!/usr/bin/env python3
"""A worked example of decoding meshtopo's LCM traffic safely in Python.

Debian has no Python module for LCM (no python3-lcm), so the round trip goes
through meshtopo.Client (the C client library) while lcm-logger records every
channel; the example then reads the log and decodes every event with
meshtopo.decode_message, the C decoder that checks every length against the
bytes before allocating anything. It:

  1. starts lcm-logger and waits until the log holds a daemon heartbeat
     (status_t on MESHTOPO_STATUS);
  2. submits a 64 x 64 vertex grid and asks for the one-ring of every vertex,
     an answer of about 250 KB that the daemon sends as reply_part_t pieces;
  3. stops the logger, decodes every logged event by its channel's one type
     (meshtopo.channel_type), reassembles the parts of the large answer,
     checks their answer_hash, tells what they hold by the fingerprint
     (meshtopo.message_type: a reply_t here, an ack_t for a large report),
     decodes it and compares every ring with what the client returned;
  4. shows a damaged copy refused with meshtopo.Error naming the field.

usage: decode_client.py [--lcm-url URL] [--prefix P]
Run it where a meshtopod answers on the same LCM URL (the tests run both in
a private network namespace). Exit status 0 when every answer matched,
1 otherwise, 77 without lcm-logger.
"""
import argparse
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

import meshtopo

# A 4 MiB socket receive buffer for the logger: the first 16 parts of an
# answer arrive at once, more than LCM's default buffer holds.
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
N = 64  # grid side


def log_events(path):
    """(channel, data) of each event of an lcm-logger file, as far as written."""
    with open(path, "rb") as f:
        blob = f.read()
    pos = 0
    while pos + 28 <= len(blob):
        sync, _num, _utime, clen, dlen = struct.unpack_from(">IqqII", blob, pos)
        if sync != 0xEDA1DA01 or pos + 28 + clen + dlen > len(blob):
            return
        channel = blob[pos + 28:pos + 28 + clen].decode("ascii", "replace")
        yield channel, blob[pos + 28 + clen:pos + 28 + clen + dlen]
        pos += 28 + clen + dlen


def grid():
    """(N*N, 3) positions and (F, 3) counter-clockwise triangles of a grid."""
    j, i = np.meshgrid(np.arange(N), np.arange(N))
    positions = np.stack([j.ravel(), i.ravel(), np.zeros(N * N)], axis=1).astype(np.float64)
    corner = (np.arange(N - 1)[:, None] * N + np.arange(N - 1)[None, :]).ravel()
    faces = np.concatenate([np.stack([corner, corner + 1, corner + N + 1], 1),
                            np.stack([corner, corner + N + 1, corner + N], 1)])
    return positions, faces.astype(np.int32)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--lcm-url", default=DEFAULT_URL)
    parser.add_argument("--prefix", default="MESHTOPO_")
    args = parser.parse_args()
    logger = shutil.which("lcm-logger")
    if not logger:
        print("decode_client: lcm-logger not found (Debian: liblcm-bin): skipped")
        return 77
    with tempfile.TemporaryDirectory(prefix="meshtopo-decode-") as workdir:
        return run(args, logger, os.path.join(workdir, "session.lcmlog"))


def run(args, logger, log):
    proc = subprocess.Popen([logger, "--lcm-url", args.lcm_url, "--flush-interval=10", "-q", "-f",
                             log], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        # 1. The logger hears the daemon: a heartbeat is in the log.
        deadline = time.monotonic() + 10
        while not any(ch == args.prefix + "STATUS" for ch, _ in
                      (log_events(log) if os.path.exists(log) else ())):
            if time.monotonic() > deadline:
                print("decode_client: no heartbeat in the log after 10 s")
                return 1
            time.sleep(0.05)
        # 2. The round trip, through the C client library.
        positions, faces = grid()
        with meshtopo.Client(args.lcm_url, prefix=args.prefix, timeout_ms=2000, retries=3,
                             source="decode-example") as client:
            client.wait_daemon(10_000)
            ack = client.submit("py-grid", positions, faces)
            rings = client.rings("py-grid", range(N * N))
        print("client: version %d, %d rings" % (ack.version, len(rings)))
        time.sleep(0.2)  # the logger's flush interval, and then some
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=10)

    # 3. Every event decoded by its channel's type; the parts put together.
    counts, parts = {}, {}
    for channel, data in log_events(log):
        kind = meshtopo.channel_type(channel, args.prefix)
        if kind is None:
            continue  # not a meshtopo channel (LCM_SELF_TEST, ...)
        try:
            msg = meshtopo.decode_message(kind, data)
        except meshtopo.Error as e:
            print("refused on %s: %s" % (channel, e))
            counts["refused"] = counts.get("refused", 0) + 1
            continue
        counts[kind] = counts.get(kind, 0) + 1
        if kind == "ack_t" and msg["mesh_id"] == "py-grid":
            assert msg["version"] == ack.version and msg["status"] == 0, msg["error"]
            assert msg["content_hash"] & (2**64 - 1) == ack.content_hash
        if kind == "reply_part_t":  # decode_message checked offset, length and part_size
            key = (channel, msg["request_id"], msg["total_size"], msg["answer_hash"])
            parts.setdefault(key, {})[msg["offset"]] = msg["data"]
    print("decoded:", ", ".join("%s %d" % kv for kv in sorted(counts.items())))
    if counts.get("refused") or len(parts) != 1:
        print("decode_client: expected one large answer and no refusal, got %d" % len(parts))
        return 1
    (channel, request_id, total, hash_), pieces = parts.popitem()
    whole = b"".join(pieces[k] for k in sorted(pieces))
    if len(whole) != total or meshtopo.answer_hash(whole) != hash_:
        print("decode_client: the log misses parts of answer %d (%d of %d bytes)"
              % (request_id, len(whole), total))
        return 1
    kind = meshtopo.message_type(whole)  # what the parts hold: a reply_t or an ack_t
    reply = meshtopo.decode_message(kind, whole)
    print("answer %d: %d bytes in %d parts, a %s of %d items"
          % (request_id, total, len(pieces), kind, reply["num_items"]))
    for v, ring in enumerate(rings):  # one fan per vertex of the grid
        g = reply["item_offsets"][v]
        lo, hi = reply["value_offsets"][g], reply["value_offsets"][g + 1]
        if not np.array_equal(reply["values"][lo:hi].view(np.uint32), ring.neighbors):
            print("decode_client: vertex %d: the logged answer differs from the client's" % v)
            return 1

    # 4. A damaged copy (cut short) is refused, the field named.
    try:
        meshtopo.decode_message("reply_t", whole[: total // 2])
        print("decode_client: a cut reply_t was accepted")
        return 1
    except meshtopo.Error as e:
        print("cut to %d bytes: %s" % (total // 2, e))
    print("decode_client: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
