#!/usr/bin/env python3
"""What an LCM log (lcm-logger's file) holds of meshtopo's chunked submissions.

Reads the log event by event (LCM's log format: sync word, event number,
timestamp, channel and data lengths, channel, data), counts the events of
each channel and decodes every mesh_chunk_t on PREFIX + SUBMIT_CHUNK by hand
(the field order of msgs/mesh_chunk_t.lcm, big-endian, no LCM module needed).
For each transfer (reply channel, request id) it prints the mesh id, the
content size, the chunk events, the distinct bytes they cover and whether
they cover the whole content: a transfer the log does not cover cannot be
rebuilt by replaying the log, since nothing answers the daemon's requests for
the missing ranges then.

usage: lcm_log_chunks.py [--prefix P] [--json] [--between T0 T1] LOG
  --between T0 T1  print only how many events the log holds with
                   T0 <= timestamp < T1 (microseconds since the epoch)
Exit status: 0 read, 1 the log is damaged, 2 usage.
"""

import argparse
import json
import struct
import sys

LOG_SYNC = 0xEDA1DA01


def read_events(path):
    """Yields (timestamp_us, channel, data) for every event of the log."""
    with open(path, "rb") as f:
        while True:
            head = f.read(28)
            if not head:
                return
            if len(head) < 28:
                raise ValueError("truncated event header at the end of the log")
            sync, _num, utime, chan_len, data_len = struct.unpack(">IqqII", head)
            if sync != LOG_SYNC:
                raise ValueError(f"bad sync word {sync:#x} at byte {f.tell() - 28}")
            channel = f.read(chan_len)
            data = f.read(data_len)
            if len(channel) != chan_len or len(data) != data_len:
                raise ValueError("truncated event at the end of the log")
            yield utime, channel.decode("utf-8", "replace"), data


class Reader:
    """LCM's encoding of a struct's fields, after the 8-byte fingerprint."""

    def __init__(self, data):
        self.data, self.pos = data, 8

    def take(self, fmt):
        value = struct.unpack_from(fmt, self.data, self.pos)
        self.pos += struct.calcsize(fmt)
        return value[0]

    def string(self):
        n = self.take(">i")  # length including the terminating NUL
        s = self.data[self.pos:self.pos + n - 1].decode("utf-8", "replace")
        self.pos += n
        return s


def decode_chunk(data):
    """The fields of a mesh_chunk_t the coverage needs."""
    r = Reader(data)
    chunk = {"utime": r.take(">q"), "request_id": r.take(">q"),
             "reply_channel": r.string(), "mesh_id": r.string(), "source": r.string()}
    r.take(">b")  # strict
    chunk["total_size"] = r.take(">q")
    chunk["content_hash"] = r.take(">q") & 0xFFFFFFFFFFFFFFFF
    r.take(">b")  # want_status
    chunk["offset"] = r.take(">q")
    chunk["length"] = r.take(">i")
    return chunk


def covered_bytes(ranges):
    """Bytes covered by the union of [start, end) ranges."""
    total, end_so_far = 0, -1
    for start, end in sorted(ranges):
        if end <= end_so_far:
            continue
        total += end - max(start, end_so_far)
        end_so_far = end
    return total


def summarize(path, prefix):
    channels = {}
    transfers = {}
    first = last = None
    for utime, channel, data in read_events(path):
        first = utime if first is None else first
        last = utime
        count = channels.setdefault(channel, [0, 0])
        count[0] += 1
        count[1] += len(data)
        if channel != prefix + "SUBMIT_CHUNK":
            continue
        try:
            c = decode_chunk(data)
        except struct.error:
            continue
        key = (c["reply_channel"], c["request_id"])
        t = transfers.setdefault(key, {
            "mesh_id": c["mesh_id"], "request_id": c["request_id"],
            "reply_channel": c["reply_channel"], "total_size": c["total_size"],
            "content_hash": "%016x" % c["content_hash"], "chunk_events": 0,
            "data_events": 0, "ranges": [], "first_us": utime, "last_us": utime})
        t["chunk_events"] += 1
        t["last_us"] = utime
        if c["length"] > 0:
            t["data_events"] += 1
            t["ranges"].append((c["offset"], c["offset"] + c["length"]))
    out = []
    for t in transfers.values():
        got = covered_bytes(t.pop("ranges"))
        t["covered_bytes"] = got
        t["complete"] = got == t["total_size"]
        t["seconds"] = round((t.pop("last_us") - t.pop("first_us")) / 1e6, 3)
        out.append(t)
    return {
        "log": path,
        "events": sum(c[0] for c in channels.values()),
        "seconds": round(((last or 0) - (first or 0)) / 1e6, 3),
        "channels": {ch: {"events": c[0], "bytes": c[1]} for ch, c in sorted(channels.items())},
        "transfers": out,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--prefix", default="MESHTOPO_")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--between", nargs=2, type=int, metavar=("T0", "T1"),
                    help="count the events with T0 <= timestamp < T1 (microseconds)")
    ap.add_argument("log")
    args = ap.parse_args()
    try:
        if args.between:
            t0, t1 = args.between
            print(sum(1 for utime, _, _ in read_events(args.log) if t0 <= utime < t1))
            return 0
        s = summarize(args.log, args.prefix)
    except (OSError, ValueError) as e:
        print(f"lcm_log_chunks: {args.log}: {e}", file=sys.stderr)
        return 1
    if args.json:
        print(json.dumps(s))
        return 0
    print(f"{s['log']}: {s['events']} events over {s['seconds']} s")
    for ch, c in s["channels"].items():
        print(f"  {ch:40s} {c['events']:8d} events {c['bytes']:12d} bytes")
    for t in s["transfers"]:
        pct = 100.0 * t["covered_bytes"] / t["total_size"] if t["total_size"] > 0 else 0.0
        print(f"  transfer {t['mesh_id']} (request {t['request_id']}): {t['data_events']} chunks,"
              f" {t['covered_bytes']} of {t['total_size']} bytes ({pct:.1f} %)"
              f" {'complete' if t['complete'] else 'INCOMPLETE'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
