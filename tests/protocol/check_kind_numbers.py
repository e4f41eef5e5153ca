#!/usr/bin/env python3
"""protocol.kind_numbers: no query-kind number is written outside msgs/.

The kinds are the int32 constants of msgs/query_t.lcm (but the SHAPE_* values
of DIHEDRAL_ANGLES); msgs/src/query_kinds.c makes them one table, and the
daemon, the client, the CLI and Python read that table or the generated
constants (MESHTOPO_QUERY_T_VERTEX_RING, Python's meshtopo.QUERY_KINDS). Every
.c and .h file under daemon/, lib/ and tools/ is read as C with its comments
dropped, every .py file there with its # comments dropped, and these are
reported with file:line:

  compare  in a file about queries (one naming query_t, reply_t, a
           MESHTOPO_QUERY_T_ constant, a query call or the kind table), a name
           ending in `kind` (q->kind, kind, qk->kind, ...) compared with,
           assigned or switched to a number that is a kind's (`kind == 13`,
           `kind = 7`, `case 4:` in a `switch (... kind)`); other files have
           kinds of their own (defect kinds, face shapes, block items);
  range    the range of kinds written out ("(1..13)", "1-13");
  call     a query call given a kind as a number (mt_client_query(c, id, 0,
           7, ...), mt_py_client_query, Python's client.query(id, 7));
  copy     a Python constant QUERY_... or a C #define / enumerator naming a
           kind, set to a number (QUERY_REPORT = 7).

usage: check_kind_numbers.py [--root DIR]   (default: the repository holding this file)
       check_kind_numbers.py --self-test    (each planted number is refused, a clean
                                             tree passes)
exit status: 0 none written, 1 some written (listed), 2 usage or msgs/query_t.lcm
could not be read.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

SCANNED_DIRS = ("daemon", "lib", "tools")
KINDS_LCM = "msgs/query_t.lcm"
NOT_KINDS = ("SHAPE_",)  # int32 constants of query_t.lcm that are not kinds

CONST_RE = re.compile(r"^\s*const\s+int32_t\s+([A-Z_][A-Z0-9_]*)\s*=\s*(-?\d+)\s*;", re.M)


def read_kinds(root):
    """{name: number} of the query kinds declared in msgs/query_t.lcm."""
    with open(os.path.join(root, KINDS_LCM), encoding="utf-8") as f:
        text = f.read()
    kinds = {name: int(value) for name, value in CONST_RE.findall(text)
             if not name.startswith(NOT_KINDS)}
    if not kinds:
        raise ValueError("no kind constants in " + KINDS_LCM)
    return kinds


def strip_c_comments(text):
    """The text with /* */ and // comments blanked (newlines kept); string
    literals are left as they are (a range in a message counts)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == '"' or c == "'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def strip_py_comments(text):
    return re.sub(r"#[^\n]*", "", text)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def call_args(text, open_paren):
    """The top-level arguments of the call whose '(' is at open_paren."""
    depth, args, start = 0, [], open_paren + 1
    for i in range(open_paren, len(text)):
        c = text[i]
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
            if depth == 0:
                args.append(text[start:i])
                return [a.strip() for a in args]
        elif c == "," and depth == 1:
            args.append(text[start:i])
            start = i + 1
    return []


# Query calls and the position of their kind argument (0-based).
C_CALLS = {"mt_client_query": 3, "mt_client_query_async": 3, "mt_py_client_query": 3}
PY_CALLS = {"query": 1, "mt_py_client_query": 3}


def check_calls_and_copies(path, text, kinds, python, numbers, report):
    """The call and copy rules (any file)."""
    calls = PY_CALLS if python else C_CALLS
    for name, index in calls.items():
        for m in re.finditer(r"(?:\.|\b)%s\s*\(" % re.escape(name), text):
            args = call_args(text, m.end() - 1)
            if len(args) > index and re.fullmatch(r"\(?\s*-?\d+\s*\)?", args[index]) and \
                    re.sub(r"\D", "", args[index]) in numbers:
                report(m.start(), "call", "%s(..., %s, ...)" % (name, args[index]))
    names = "|".join(sorted(kinds))
    if python:
        for m in re.finditer(r"\b(QUERY_\w+|%s)\s*=\s*(-?\d+)\b" % names, text):
            if m.group(2) in numbers:
                report(m.start(), "copy", m.group(0))
    else:
        for m in re.finditer(r"(?:#\s*define\s+|\b)(\w*(?:%s))\b\s*=?\s*\(?(-?\d+)\)?\s*[,;\n}]"
                             % names, text):
            if m.group(2) in numbers and not m.group(1).startswith("MESHTOPO_QUERY_T_"):
                report(m.start(), "copy", m.group(0).strip())
    return []


# What marks a file as one about queries (for the compare rule).
QUERY_FILE_RE = re.compile(r"query_t|reply_t|MESHTOPO_QUERY_T_|mt_client_query|"
                           r"mt_py_client_query|mt_msgs_query_kind|QUERY_KINDS|\.query\(")


def check_text(path, text, kinds, python):
    numbers = {str(v) for v in kinds.values()}
    first, last = min(kinds.values()), max(kinds.values())
    found = []

    def report(pos, rule, what):
        found.append("%s:%d: %s: %s" % (path, line_of(text, pos), rule, what))

    found += check_calls_and_copies(path, text, kinds, python, numbers, report)
    for m in re.finditer(r"\b%d\s*(?:\.\.|-|\u2013|to)\s*%d\b" % (first, last), text):
        report(m.start(), "range", m.group(0))
    if not QUERY_FILE_RE.search(text):
        return found
    kind_name = r"[A-Za-z_][\w]*kind\b|\bkind\b"
    for m in re.finditer(r"(?:%s)\s*(==|!=|<=|>=|<|>|=(?!=))\s*\(?\s*(-?\d+)\b" % kind_name,
                         text, re.I):
        if m.group(2) in numbers:
            report(m.start(), "compare", m.group(0).strip())
    for m in re.finditer(r"\b(-?\d+)\s*(==|!=|<=|>=|<|>)\s*[\w>.-]*kind\b", text, re.I):
        if m.group(1) in numbers:
            report(m.start(), "compare", m.group(0).strip())
    if not python:
        for m in re.finditer(r"\bswitch\s*\(\s*[\w>.\-\[\]]*kind\s*\)\s*\{", text, re.I):
            depth, i = 0, m.end() - 1
            while i < len(text):
                if text[i] == "{":
                    depth += 1
                elif text[i] == "}":
                    depth -= 1
                    if depth == 0:
                        break
                i += 1
            for c in re.finditer(r"\bcase\s+\(?\s*(\d+)\s*\)?\s*:", text[m.end():i]):
                if c.group(1) in numbers:
                    report(m.end() + c.start(), "compare", c.group(0).strip())
    return found


def check_tree(root):
    kinds = read_kinds(root)
    found = []
    for top in SCANNED_DIRS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = sorted(d for d in dirnames if d not in ("__pycache__", "build"))
            for name in sorted(filenames):
                python = name.endswith(".py")
                if not (python or name.endswith((".c", ".h"))):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = f.read()
                text = strip_py_comments(text) if python else strip_c_comments(text)
                found += check_text(os.path.relpath(path, root), text, kinds, python)
    return found


def run(root):
    try:
        found = check_tree(root)
    except (OSError, ValueError) as e:
        print("check_kind_numbers: %s" % e, file=sys.stderr)
        return 2
    for line in found:
        print(line)
    if found:
        print("%d query-kind number(s) written outside msgs/: read them from "
              "meshtopo/query_kinds.h or the MESHTOPO_QUERY_T_* constants" % len(found))
        return 1
    print("no query-kind number written outside msgs/")
    return 0


# Each plant is one file that must be refused on its own.
PLANTS = {
    "daemon/route_compare.c": "void f(const meshtopo_query_t *q) { if (q->kind == 13) g(); }\n",
    "daemon/route_reverse.c": "int f(const meshtopo_reply_t *r) { return 7 != r->kind; }\n",
    "daemon/route_switch.c": ("int f(const meshtopo_query_t *q)\n{\n    switch (q->kind) {\n"
                              "        case 4:\n            return 1;\n    }\n    return 0;\n}\n"),
    "daemon/route_range.c": 'const char *m = "kind: %d is not a query_t kind (1..13)";\n',
    "lib/client/src/call.c": ("int f(mt_client *c, reply *r)\n{\n    return mt_client_query(c, "
                              "\"m\", 0, 7, NULL, 0, r, NULL);\n}\n"),
    "tools/cli/define.c": "#define REPORT 7\n",
    "lib/python/meshtopo/copy.py": "QUERY_REPORT = 7\n",
    "lib/python/meshtopo/call.py": "def f(c):\n    return c.query(\"m\", 3, [0])\n",
    "lib/python/meshtopo/assign.py": "def f(c):\n    kind = 12\n    return c.query(\"m\", kind)\n",
}
CLEAN = {
    "daemon/clean.c": ("/* kind 13 in a comment, (1..13) too */\n"
                       "int f(const q_t *q) { return q->kind == MESHTOPO_QUERY_T_REPORT; }\n"
                       "int g(int count) { return count == 7; }\n"),
    "tools/cli/blocks.c": "int f(const item *it) { return it->kind == 1; }\n",
    "lib/python/meshtopo/clean.py": ("# QUERY_REPORT = 7 in a comment\n"
                                     "def f(c):\n    return c.query(\"m\", \"report\")\n"),
}


def self_test():
    here = os.path.abspath(__file__)
    repo = os.path.dirname(os.path.dirname(os.path.dirname(here)))
    failures = 0
    with tempfile.TemporaryDirectory(prefix="kind-numbers-") as tmp:
        def tree(files):
            root = os.path.join(tmp, "t%d" % len(os.listdir(tmp)))
            os.makedirs(os.path.join(root, "msgs"))
            shutil.copy(os.path.join(repo, KINDS_LCM), os.path.join(root, KINDS_LCM))
            for rel, text in files.items():
                os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
                with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                    f.write(text)
            return root

        def check(root):
            p = subprocess.run([sys.executable, here, "--root", root], capture_output=True,
                               text=True)
            return p.returncode, p.stdout

        rc, out = check(tree(CLEAN))
        if rc != 0:
            print("FAIL a clean tree is refused (%d):\n%s" % (rc, out))
            failures += 1
        else:
            print("ok   a clean tree passes")
        for rel, text in PLANTS.items():
            rc, out = check(tree({**CLEAN, rel: text}))
            if rc == 1 and rel in out and out.count(rel + ":") >= 1:
                print("ok   refused: %s (%s)" % (rel, out.splitlines()[0].split(": ", 1)[1]))
            else:
                print("FAIL not refused: %s (exit %d):\n%s" % (rel, rc, out))
                failures += 1
    print("%d failure(s)" % failures)
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    return self_test() if args.self_test else run(args.root)


if __name__ == "__main__":
    sys.exit(main())
