"""python.messages: meshtopo.decode_message (lib/python/meshtopo/messages.py,
the C decoder mt_msgs_decode through ctypes) on every sample message that
msgs_write_samples encodes in C, on every truncation and on random corruptions
of them (refused with meshtopo.Error or decoded, the process never crashing),
and on forged hostile replies whose lengths exceed the bytes (a count of
2^31 - 1 with 10 bytes after it, a part claiming 60000 bytes with 5, a string
longer than the buffer, offsets that do not describe the arrays): each is
refused with MT_ERR_CORRUPT naming the field. No daemon needed."""
import os
import random
import struct
import subprocess

import numpy as np
import pytest

import meshtopo

RECEIVED = ("ack_t", "reply_t", "reply_part_t", "mesh_transfer_t", "status_t", "topology_t")


@pytest.fixture(scope="module")
def samples(tmp_path_factory):
    """{file name: (type, bytes)} of every sample message (NAME.TYPE.lcmbin)."""
    tool = os.environ.get("MESHTOPO_MSGS_WRITE_SAMPLES")
    if not tool:
        pytest.fail("MESHTOPO_MSGS_WRITE_SAMPLES is not set: run the tests through ctest")
    d = tmp_path_factory.mktemp("samples")
    subprocess.run([tool, str(d)], check=True, stdout=subprocess.DEVNULL)
    return {n: (n.split(".")[1], (d / n).read_bytes()) for n in os.listdir(d)
            if n.endswith(".lcmbin")}


def fingerprint(samples, kind):
    return next(b[:8] for t, b in samples.values() if t == kind)


def refused(kind, data, *words):
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.decode_message(kind, data)
    assert e.value.status == "MT_ERR_CORRUPT"
    for w in words:
        assert w in e.value.message, (w, e.value.message)
    return e.value.message


def string(s):
    return struct.pack(">i", len(s) + 1) + s + b"\0"


def test_every_sample_decodes_and_names_its_type(samples):
    assert len(samples) >= 20
    for name, (kind, data) in samples.items():
        assert meshtopo.message_type(data) == kind, name
        if name.startswith("reply_part."):  # a toy part: 20 bytes in parts of 8
            refused(kind, data, "reply_part_t.total_size: 20")
            continue
        msg = meshtopo.decode_message(kind, data)
        assert meshtopo.decode_message(None, data).keys() == msg.keys(), name
        assert "utime" in msg, name
    ring = meshtopo.decode_message("reply_t", samples["reply_ring.reply_t.lcmbin"][1])
    assert ring["values"].dtype == np.int32 and ring["num_items"] == len(ring["item_status"])
    report = meshtopo.decode_message("reply_t", samples["reply_report.reply_t.lcmbin"][1])
    assert report["reports"][0]["mesh_id"] == "torus" and report["reports"][0]["genus"] == 1


def test_cuts_and_corruptions_are_refused_never_crash(samples):
    rnd = random.Random(4)
    for name, (kind, data) in samples.items():
        for n in range(len(data)):
            refused(kind, data[:n])
        refused(kind, data + b"\0", "1 bytes after the end of the message")
        for _ in range(300):
            c = bytearray(data)
            for _ in range(rnd.randint(1, 4)):
                c[rnd.randrange(8, len(c))] = rnd.randrange(256)
            try:
                meshtopo.decode_message(kind, bytes(c))
            except meshtopo.Error as e:
                assert e.status == "MT_ERR_CORRUPT" and e.message


def test_forged_hostile_replies_are_refused(samples):
    head = (fingerprint(samples, "reply_t") + struct.pack(">qqi", 1, 7, 0) + string(b"")
            + string(b"m") + struct.pack(">ii", 1, 1))
    refused("reply_t", head + struct.pack(">i", 2**31 - 1) + bytes(10),
            "reply_t.item_status", "2147483647 values", "10 left")
    refused("reply_t", head + struct.pack(">i", -2**31) + bytes(10), "reply_t.item_status",
            "negative")
    part = fingerprint(samples, "reply_part_t") + struct.pack(">qqqqiqi", 1, 7, 100000, 0, 57344,
                                                              0, 60000)
    refused("reply_part_t", part + bytes(5), "reply_part_t.data", "60000 values", "5 left")
    ack = fingerprint(samples, "ack_t") + struct.pack(">qqi", 1, 7, 0)
    refused("ack_t", ack + struct.pack(">i", 1000) + b"abc", "ack_t.error", "1000 bytes, 3 left")
    refused("ack_t", ack + struct.pack(">i", 2) + b"ab" + bytes(40), "ack_t.error",
            "does not end with a NUL")
    refused("ack_t", ack + string(b"") + string(b"m") + struct.pack(">iqi", 1, 0, 10**9) + bytes(64),
            "ack_t.reports", "1000000000 structs")
    refused(None, bytes(16), "no meshtopo type")
    refused("reply_t", samples["status.status_t.lcmbin"][1], "the bytes are a status_t")
    with pytest.raises(ValueError):
        meshtopo.decode_message("no_such_t", b"")


def test_rules_beyond_the_encoding(samples):
    # A well-formed reply_t whose item offsets point past its groups: cut the
    # ring sample's item_offsets[1] (its last entry) to a larger number.
    data = bytearray(samples["reply_ring.reply_t.lcmbin"][1])
    ring = meshtopo.decode_message("reply_t", bytes(data))
    offsets = struct.pack(">i", ring["num_item_offsets"]) + ring["item_offsets"].astype(">i4").tobytes()
    at = bytes(data).index(offsets) + len(offsets) - 4
    data[at:at + 4] = struct.pack(">i", ring["num_groups"] + 5)
    refused("reply_t", bytes(data), "reply_t.item_offsets")
    # A part off the grid, and one of the wrong length.
    fp = fingerprint(samples, "reply_part_t")
    refused("reply_part_t", fp + struct.pack(">qqqqiqi", 1, 7, 100000, 0, 57344, 1000, 3) + bytes(3),
            "reply_part_t.offset: 1000")
    refused("reply_part_t", fp + struct.pack(">qqqqiqi", 1, 7, 100000, 0, 57344, 57344, 3)
            + bytes(3), "reply_part_t.length: 3", "expected 42656")
    ok = meshtopo.decode_message("reply_part_t", fp + struct.pack(">qqqqiqi", 1, 7, 100000, 0,
                                                                  57344, 57344, 42656) + bytes(42656))
    assert ok["length"] == 42656 and len(ok["data"]) == 42656
    # More missing ranges than a transfer status lists.
    n = 1025
    transfer = (fingerprint(samples, "mesh_transfer_t") + struct.pack(">qqi", 1, 7, 0) + string(b"")
                + struct.pack(">qqbqi", 10, 0, 0, 0, n) + bytes(16 * n))
    refused("mesh_transfer_t", transfer, "num_missing: 1025")


def test_channels_and_answer_hash():
    assert meshtopo.channel_type("MESHTOPO_STATUS") == "status_t"
    assert meshtopo.channel_type("ROBOT_QUERY_PULL", "ROBOT_") == "reply_pull_t"
    assert meshtopo.channel_type("MESHTOPO_REPLY_host_1_ab_PART") == "reply_part_t"
    assert meshtopo.channel_type("MESHTOPO_REPLY_host_1_ab_ACK") == "ack_t"
    assert meshtopo.channel_type("LCM_SELF_TEST") is None
    # FNV-1a over one zero-padded big-endian word.
    h = (0xcbf29ce484222325 ^ 0x0102030000000000) * 0x100000001b3 % 2**64
    assert meshtopo.answer_hash(b"\x01\x02\x03") & (2**64 - 1) == h
