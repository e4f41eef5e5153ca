#!/usr/bin/env python3
"""`meshtopo inspect` reads in bounded memory (ctest cli.inspect_bounded).

Each case runs `meshtopo inspect FILE` under `/usr/bin/time -v` and checks
the exit code, the message on stderr and the peak resident set size:
  - a 21 MB .gz that inflates to 4 GiB: a valid OFF mesh, then newlines;
  - a binary PLY declaring 2^31 - 1 vertices, then 512 MiB of gzip'd zero
    bytes (valid floats, far fewer than declared);
  - a PLY declaring 2^31 vertices in a tiny file;
  - --max-input-bytes and $MESHTOPO_MAX_INPUT_BYTES.
The files are made here, in a temporary directory, from a few compressed
members repeated (gzip allows any number of members). Exit 77 (skipped)
without /usr/bin/time (Debian package `time`).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import zlib

TIME = "/usr/bin/time"
MAX_RSS_MB = 200
MIB = 1 << 20

failures = []


def expect(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
        if detail:
            print("     " + detail.replace("\n", "\n     "))


def member(data, strategy=zlib.Z_DEFAULT_STRATEGY):
    """One gzip member holding data."""
    c = zlib.compressobj(9, zlib.DEFLATED, 31, 9, strategy)
    return c.compress(data) + c.flush()


def write_gz(path, head, tail_members, tail=b""):
    with open(path, "wb") as f:
        f.write(member(head))
        for m in tail_members:
            f.write(m)
        if tail:
            f.write(member(tail))
    return os.path.getsize(path)


def inspect(meshtopo, path, *args, env=None):
    """Runs inspect under /usr/bin/time -v: (exit code, stderr, peak RSS in MB)."""
    full_env = dict(os.environ)
    full_env.pop("MESHTOPO_MAX_INPUT_BYTES", None)
    full_env.update(env or {})
    p = subprocess.run([TIME, "-v", meshtopo, "inspect", path, *args], capture_output=True,
                       text=True, env=full_env, timeout=300)
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    rss = int(m.group(1)) / 1024 if m else float("inf")
    message = "\n".join(line for line in p.stderr.splitlines() if line.startswith("meshtopo"))
    return p.returncode, message, rss


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    args = ap.parse_args()
    if not os.access(TIME, os.X_OK):
        print(f"{TIME} is missing (Debian package `time`): skipped")
        return 77
    mesh = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    newlines = b"\n" * (64 * MIB)
    # fixed Huffman codes compress less (about 160:1) than dynamic ones:
    # 48 + 16 members of 64 MiB make 4 GiB in about 21 MB
    nl_fixed, nl_dynamic = member(newlines, zlib.Z_FIXED), member(newlines)
    with tempfile.TemporaryDirectory(prefix="meshtopo-bounded-") as tmp:
        # 1. A valid mesh, then 4 GiB of newlines.
        path = os.path.join(tmp, "bomb.off.gz")
        size = write_gz(path, mesh, [nl_fixed] * 48 + [nl_dynamic] * 16)
        code, message, rss = inspect(args.meshtopo, path)
        expect(code == 3 and path in message and
               "goes on for more than 1048576 bytes after the last face" in message and
               rss < MAX_RSS_MB,
               f"{size / 1e6:.1f} MB .gz inflating to 4 GiB after a mesh: exit 3, clear error, "
               f"peak RSS {rss:.1f} MB < {MAX_RSS_MB} MB", f"exit {code}: {message}")

        # 2. A PLY declaring 2^31 - 1 vertices, then 512 MiB of zero bytes.
        path = os.path.join(tmp, "zeros.ply.gz")
        head = (b"ply\nformat binary_little_endian 1.0\nelement vertex 2147483647\n"
                b"property float x\nproperty float y\nproperty float z\nend_header\n")
        size = write_gz(path, head, [member(b"\0" * (64 * MIB), zlib.Z_FIXED)] * 8)
        code, message, rss = inspect(args.meshtopo, path)
        expect(code == 3 and path in message and
               "need at least 25769803764 bytes of data but only 536870912 follow" in message
               and rss < MAX_RSS_MB,
               f"{size / 1e6:.1f} MB .gz PLY declaring 2^31 - 1 vertices over 512 MiB of zeros: "
               f"exit 3, clear error, peak RSS {rss:.1f} MB", f"exit {code}: {message}")

        # 3. A PLY declaring 2^31 vertices in a tiny file.
        path = os.path.join(tmp, "huge.ply")
        with open(path, "wb") as f:
            f.write(head.replace(b"2147483647", b"2147483648") + b"\0" * 12)
        code, message, rss = inspect(args.meshtopo, path)
        expect(code == 3 and path in message and "vertex count 2147483648 too large" in message,
               "PLY declaring 2^31 vertices in a tiny file: exit 3, clear error",
               f"exit {code}: {message}")

        # 4. The input limit: 256 MiB of newlines between the counts and the
        # vertices (valid OFF) read by default, refused under a lower limit.
        path = os.path.join(tmp, "spaced.off.gz")
        write_gz(path, b"OFF\n3 1 0\n", [nl_dynamic] * 4, tail=mesh[len(b"OFF\n3 1 0\n"):])
        code, message, rss = inspect(args.meshtopo, path)
        expect(code == 0 and rss < MAX_RSS_MB,
               f"a valid mesh spread over 256 MiB: exit 0, peak RSS {rss:.1f} MB",
               f"exit {code}: {message}")
        limit_text = "inflates to more than the input limit of 67108864 bytes"
        code, message, rss = inspect(args.meshtopo, path, "--max-input-bytes", "64M")
        expect(code == 3 and limit_text in message and "--max-input-bytes raises it" in message,
               "--max-input-bytes 64M: exit 3 naming the limit", f"exit {code}: {message}")
        code, message, rss = inspect(args.meshtopo, path,
                                     env={"MESHTOPO_MAX_INPUT_BYTES": "67108864"})
        expect(code == 3 and limit_text in message,
               "$MESHTOPO_MAX_INPUT_BYTES=67108864: exit 3 naming the limit",
               f"exit {code}: {message}")
        code, message, rss = inspect(args.meshtopo, path, "--max-input-bytes", "1G",
                                     env={"MESHTOPO_MAX_INPUT_BYTES": "1K"})
        expect(code == 0, "--max-input-bytes overrides the environment", f"exit {code}: {message}")
        plain = os.path.join(tmp, "small.off")
        with open(plain, "wb") as f:
            f.write(mesh)
        code, message, rss = inspect(args.meshtopo, plain, "--max-input-bytes", "10")
        expect(code == 3 and f"{len(mesh)} bytes: more than the input limit of 10 bytes" in message,
               "a plain file over the limit: exit 3 naming its size and the limit",
               f"exit {code}: {message}")
        for bad in ("0", "-5", "12X", "ten", "99999999999999999999"):
            code, message, rss = inspect(args.meshtopo, plain, "--max-input-bytes", bad)
            expect(code == 2 and "--max-input-bytes" in message,
                   f"--max-input-bytes {bad}: usage error (exit 2)", f"exit {code}: {message}")
        code, message, rss = inspect(args.meshtopo, plain,
                                     env={"MESHTOPO_MAX_INPUT_BYTES": "lots"})
        expect(code == 2 and "MESHTOPO_MAX_INPUT_BYTES" in message,
               "a bad $MESHTOPO_MAX_INPUT_BYTES: usage error (exit 2)", f"exit {code}: {message}")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
