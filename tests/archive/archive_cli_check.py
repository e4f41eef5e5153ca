#!/usr/bin/python3
"""`meshtopo archive ls|show|verify|export|rm` against archives made with
archive_fixture (the library's writer, as meshtopod will use it): output,
JSON, exit codes, bad files named by verify, export -> re-import giving the
same face list and content hash, removal of versions, --help.

usage: archive_cli_check.py --meshtopo PATH --fixture PATH --corpus DIR
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

failures = []


def expect(cond, what, code=None, out="", err=""):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)
        if code is not None:
            print(f"     exit code {code}")
        if out:
            print("     stdout: " + out[:800].replace("\n", "\n             "))
        if err:
            print("     stderr: " + err[:800].replace("\n", "\n             "))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    args = ap.parse_args()

    def run(*argv):
        p = subprocess.run([args.meshtopo, *argv], capture_output=True, text=True, timeout=120)
        return p.returncode, p.stdout, p.stderr

    def fixture(d, mesh_id, version, path):
        subprocess.run([args.fixture, d, mesh_id, str(version), path], check=True)

    def read_off(path):
        with open(path, encoding="ascii") as f:
            words = [w for line in f for w in line.split("#")[0].split()]
        nv, nf = int(words[1]), int(words[2])
        verts = [float(w) for w in words[4:4 + 3 * nv]]
        pos = 4 + 3 * nv
        faces = []
        for _ in range(nf):
            n = int(words[pos])
            faces.append([int(w) for w in words[pos + 1:pos + 1 + n]])
            pos += 1 + n
        return verts, faces

    corpus = lambda name: os.path.join(args.corpus, name + ".off")
    with tempfile.TemporaryDirectory(prefix="meshtopo-cli-archive-") as tmp:
        d = os.path.join(tmp, "archive")
        fixture(d, "torus", 1, corpus("cgal_torus_quad"))
        fixture(d, "torus", 2, corpus("vcg_nonmanifold"))
        fixture(d, "bad faces", 1, corpus("assimp_malformed"))
        fixture(d, "x %.y", 1, corpus("cgal_tetrahedron"))

        # ---- ls
        code, out, err = run("archive", "ls", d)
        expect(code == 0 and "torus" in out and "bad faces" in out and "x %.y" in out,
               "ls lists every id", code, out, err)
        code, out, err = run("archive", "ls", d, "--json")
        doc = json.loads(out) if code == 0 else {}
        meshes = doc.get("meshes", [])
        expect(len(meshes) == 4 and doc.get("unreadable") == [], "ls --json: 4 versions",
               code, out, err)
        byid = {(m["mesh_id"], m["version"]): m for m in meshes}
        t2 = byid.get(("torus", 2), {})
        expect(t2.get("num_faces") == 5 and t2.get("num_defects", 0) > 0 and
               t2.get("file") == "torus.v2.hdf" and t2.get("file_bytes", 0) > 0,
               "ls --json: counts, defects, file and size of torus v2", code, out, err)
        t1 = byid.get(("torus", 1), {})
        expect(t1.get("genus") == 1 and t1.get("closed") is True, "ls --json: torus v1 genus 1")
        code, out, err = run("archive", "ls", os.path.join(tmp, "missing"))
        expect(code == 3 and "missing" in err, "ls of a missing directory: exit 3, named",
               code, out, err)

        # ---- show
        code, out, err = run("archive", "show", d, "torus", "--json")
        doc = json.loads(out) if code == 0 else {}
        expect(doc.get("version") == 2 and doc.get("report", {}).get("num_faces") == 5,
               "show: the highest version by default", code, out, err)
        code, out, err = run("archive", "show", d, "torus", "--version", "1", "--json")
        doc = json.loads(out) if code == 0 else {}
        rep = doc.get("report", {})
        expect(doc.get("version") == 1 and rep.get("genus") == 1 and rep.get("defects") == [],
               "show --version 1 --json", code, out, err)
        code, out, err = run("archive", "show", d, "torus", "--version", "1")
        expect(code == 0 and "rebuilt" not in err,
               "show restores from the stored half-edge arrays (no rebuild note)", code, out, err)
        try:
            import h5py
        except ImportError:
            h5py = None
        if h5py:
            # Damaged arrays: show still answers, rebuilt from the face list, and says so.
            damaged = os.path.join(d, "damaged")
            os.mkdir(damaged)
            name = next(n for n in os.listdir(d) if n.startswith("torus.v1."))
            shutil.copy(os.path.join(d, name), damaged)
            with h5py.File(os.path.join(damaged, name), "r+") as f:
                nxt = f["meshtopo/halfedge/next"]
                nxt[0] = 0xfffffff0
            code, out, err = run("archive", "show", damaged, "torus", "--json")
            doc = json.loads(out) if code == 0 else {}
            expect(doc.get("report", {}).get("genus") == 1 and "rebuilt from the face list" in err,
                   "show of damaged arrays: rebuilt, said on stderr", code, out, err)
            shutil.rmtree(damaged)
        code, out, err = run("archive", "show", d, "bad faces")
        expect(code == 0 and "bad faces" in out and "out of range" in out,
               "show (text) lists the defects", code, out, err)
        code, out, err = run("archive", "show", d, "nothing")
        expect(code == 3 and "nothing" in err, "show of an unknown id: exit 3", code, out, err)
        code, out, err = run("archive", "show", d, "torus", "--version", "zero")
        expect(code == 2, "show --version zero: usage error", code, out, err)
        code, out, err = run("archive", "show", d, "a/b")
        expect(code == 2 and "'/'" in err, "show of an invalid id: usage error", code, out, err)

        # ---- verify
        code, out, err = run("archive", "verify", d)
        expect(code == 0 and out.count("ok   ") == 4, "verify: every file ok", code, out, err)
        bad = os.path.join(tmp, "bad")
        shutil.copytree(d, bad)
        with open(os.path.join(bad, "torus.v1.hdf"), "r+b") as f:
            f.truncate(2000)
        with open(os.path.join(bad, "junk.v1.hdf"), "w") as f:
            f.write("not hdf5\n")
        code, out, err = run("archive", "verify", bad)
        expect(code == 3 and "BAD  " in out and "torus.v1.hdf" in out and
               "junk.v1.hdf" in out and out.count("ok   ") == 3 and "2 bad" in out,
               "verify: exit 3, each bad file named, the others ok", code, out, err)
        code, out, err = run("archive", "verify", bad, "--json")
        doc = json.loads(out) if out else {}
        expect(code == 3 and doc.get("bad") == 2 and doc.get("checked") == 5,
               "verify --json: 2 bad of 5", code, out, err)
        code, out, err = run("archive", "ls", bad, "--json")
        doc = json.loads(out) if code == 0 else {}
        expect(code == 0 and len(doc.get("unreadable", [])) == 2 and len(doc.get("meshes")) == 3,
               "ls lists unreadable files with their reason", code, out, err)

        # ---- export -> re-import
        for name, mid in (("assimp_malformed", "bad faces"), ("cgal_torus_quad", "torus")):
            off = os.path.join(tmp, name + ".off")
            version = ["--version", "1"] if mid == "torus" else []
            code, out, err = run("archive", "export", d, mid, *version, off)
            expect(code == 0 and os.path.exists(off), f"export {mid} to OFF", code, out, err)
            if code == 0:
                expect(read_off(off) == read_off(corpus(name)),
                       f"export {mid}: the OFF file's face list equals the original")
                again = os.path.join(tmp, "again")
                fixture(again, mid, 1, off)
                _, out, _ = run("archive", "ls", again, "--json")
                h = json.loads(out)["meshes"][0]["content_hash"]
                orig = [m for m in meshes if m["mesh_id"] == mid and m["version"] == 1][0]
                expect(h == orig["content_hash"], f"export {mid} -> re-import: same content hash")
                shutil.rmtree(again)
        for ext in ("obj", "ply"):
            path = os.path.join(tmp, "out." + ext)
            code, out, err = run("archive", "export", d, "torus", path)
            expect(code == 0 and os.path.getsize(path) > 0, f"export to .{ext}", code, out, err)
        code, out, err = run("archive", "export", d, "torus", os.path.join(tmp, "out.xyz"))
        expect(code == 2, "export to an unknown suffix: usage error", code, out, err)
        code, out, err = run("archive", "export", d, "torus", "--version", "7",
                             os.path.join(tmp, "v7.off"))
        expect(code == 3 and "version 7" in err, "export of a missing version: exit 3",
               code, out, err)

        # ---- rm
        code, out, err = run("archive", "rm", d, "torus", "--all", "--version", "1")
        expect(code == 2, "rm --all --version: usage error", code, out, err)
        code, out, err = run("archive", "rm", d, "torus")
        expect(code == 0 and not os.path.exists(os.path.join(d, "torus.v2.hdf")) and
               os.path.exists(os.path.join(d, "torus.v1.hdf")),
               "rm removes the highest version", code, out, err)
        fixture(d, "torus", 3, corpus("cgal_torus_quad"))
        code, out, err = run("archive", "rm", d, "torus", "--all")
        expect(code == 0 and "torus" not in "".join(os.listdir(d)), "rm --all", code, out, err)
        code, out, err = run("archive", "rm", d, "x %.y", "--version", "1")
        expect(code == 0 and len(os.listdir(d)) == 1, "rm --version 1", code, out, err)
        code, out, err = run("archive", "rm", d, "x %.y", "--version", "1")
        expect(code == 3, "rm of a missing version: exit 3", code, out, err)

        # ---- usage and help
        for sub in ("ls", "show", "verify", "export", "rm"):
            code, out, err = run("archive", sub, "--help")
            expect(code == 0 and f"archive {sub}" in out, f"archive {sub} --help", code, out, err)
        code, out, err = run("help", "archive")
        expect(code == 0 and "verify" in out, "help archive", code, out, err)
        code, out, err = run("archive", "frobnicate", d)
        expect(code == 2 and "frobnicate" in err, "unknown subcommand: exit 2", code, out, err)
        code, out, err = run("archive", "show", d)
        expect(code == 2, "show without ID: exit 2", code, out, err)
        code, out, err = run("archive", "export", d, "torus", "x.off", "--json")
        expect(code == 2 and "--json" in err, "--json with export: exit 2", code, out, err)
        code, out, err = run("--help")
        expect("archive" in out, "meshtopo --help lists archive", code, out, err)

    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
