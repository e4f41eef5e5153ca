#!/usr/bin/env python3
"""layering.client_only: the CLI, the benchmarks and the test clients talk to
meshtopod through meshtopo::client only. They contain no LCM calls of their
own (lcm_create, lcm_subscribe, lcm_publish, lcm_handle) and no walk over a
reply's offset arrays (item_offsets, value_offsets, value2_offsets): the
client library decodes for them. The two benchmark files that measure raw LCM
itself, the floor the daemon is compared with, and the soak's hostile sender,
which sends what no client library would, are the exceptions.

usage: check_client_only.py [--root DIR] | --self-test
"""
import argparse
import os
import re
import sys
import tempfile

CHECKED = ("tools/cli", "tools/cli/archive", "tools/bench", "lib/python/src",
           "tests/daemon/lcm/meshtopod_*_client.c",
           "tests/daemon/lcm/parts_expect.*")
RAW_LCM_FILES = ("tools/bench/rtt_pingpong.c", "tools/bench/transfer_raw.c",
                 "tools/bench/soak_hostile.c")
FORBIDDEN = re.compile(r"\b(lcm_create|lcm_subscribe|lcm_publish|lcm_handle\w*|item_offsets|"
                       r"value_offsets|value2_offsets)\b")
COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def files(root):
    out = []
    for pattern in CHECKED:
        head, _, tail = pattern.rpartition("/")
        directory = os.path.join(root, head if "*" in tail else pattern)
        if not os.path.isdir(directory):
            continue
        if "*" in tail:
            rx = re.compile("^" + re.escape(tail).replace(r"\*", ".*") + "$")
            names = [n for n in os.listdir(directory) if rx.match(n)]
        else:
            names = [n for n in os.listdir(directory) if n.endswith((".c", ".h"))]
        out += [os.path.join(directory, n) for n in sorted(names)]
    return out


def check(root):
    hits = []
    checked = 0
    for path in files(root):
        rel = os.path.relpath(path, root)
        if rel in RAW_LCM_FILES:
            continue
        checked += 1
        text = open(path, encoding="utf-8", errors="replace").read()
        # Comments may name the arrays; only code counts.
        code = COMMENT.sub(lambda m: "\n" * m.group(0).count("\n"), text)
        for number, line in enumerate(code.splitlines(), 1):
            for m in FORBIDDEN.finditer(line):
                hits.append(f"{rel}:{number}: {m.group(1)}")
    return checked, hits


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "tools/cli"))
        os.makedirs(os.path.join(root, "tools/bench"))
        os.makedirs(os.path.join(root, "tests/daemon/lcm"))
        clean = "/* item_offsets are read by the client */\nint f(void) { return 0; }\n"
        open(os.path.join(root, "tools/cli/a.c"), "w").write(clean)
        open(os.path.join(root, "tools/bench/rtt_pingpong.c"), "w").write("lcm_publish(l);\n")
        checked, hits = check(root)
        if hits or checked != 1:
            print("self-test: a clean tree was refused:", hits)
            return 1
        open(os.path.join(root, "tools/cli/b.c"), "w").write("x = r->value_offsets[g];\n")
        open(os.path.join(root, "tests/daemon/lcm/meshtopod_x_client.c"),
             "w").write("\n\nlcm_subscribe(l, c, f, u);\n")
        checked, hits = check(root)
        want = ["tests/daemon/lcm/meshtopod_x_client.c:3: lcm_subscribe",
                "tools/cli/b.c:1: value_offsets"]
        if sorted(hits) != want:
            print("self-test: expected", want, "got", hits)
            return 1
    print("self-test: OK")
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default=os.path.join(os.path.dirname(__file__), "..", ".."))
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    checked, hits = check(os.path.abspath(args.root))
    if hits:
        print(f"FAIL: {len(hits)} raw LCM call(s) or reply offset walk(s) in {checked} files "
              "that must use meshtopo::client:")
        print("\n".join("  " + h for h in hits))
        return 1
    print(f"OK: {checked} files of the CLI, benchmarks and test clients use meshtopo::client only"
          f" (raw LCM files left out: {', '.join(RAW_LCM_FILES)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
