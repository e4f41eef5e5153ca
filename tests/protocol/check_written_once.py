#!/usr/bin/env python3
"""protocol.written_once: every constant and rule of meshtopo's LCM protocol is
written once, in msgs/, and read from there by the daemon, the libraries and
the tools (DESIGN.md: "limits and rules of the protocol live once").

The constants are read from the `const` members of msgs/*.lcm, so a new one is
covered as soon as it is declared. Then every .c and .h file under daemon/,
lib/ and tools/ is read as C tokens (comments dropped; string and character
literals kept apart from code) and these are reported, with file:line:

  value    a constant whose value has 4 or more digits (60000, 57344, 1024)
           appears as a number in code;
  limit    a #define, const or enumerator whose name mentions a protocol
           concept (PART, PULL, RANGE, GAP, MISSING, SINGLE_MESSAGE,
           FIRST_PARTS, MESH_ID) is given a bare number equal to one of the
           protocol's limits (the constants named after those concepts or
           ending in _MAX, _MIN, _SIZE or _LIMIT), e.g. a second 16 for
           reply_part_t.FIRST_PARTS; unless a _Static_assert in msgs/ ties
           that name to the constant (MESHTOPO_MESH_T_MESH_ID_MAX ==
           MT_MESH_ID_MAX: meshtopo::ident, below msgs/ and the archive,
           cannot include LCM's headers, and msgs/ checks it agrees);
  id-rule  a function that tests both a '/' byte and ".." (the mesh-id rule),
           or a function named *id_check*, outside lib/ident/src/mesh_id_rule.c
           (mt_mesh_id_check, below msgs/ and the archive, which both call
           it); msgs/src/mesh_id.c's mt_msgs_mesh_id_check, which only calls
           it, is the rule's name in msgs/;
  names    one function or one declaration (a table) holding 5 or more of the
           status-code names, outside msgs/src/status_codes.c.

The id and name rules are looked for in msgs/src and msgs/include too (every
file but their home), and their homes must hold them. A limit const declared
in two .lcm files is reported as well. "OUT_OF_RANGE" (a status, a defect
kind) is not the RANGE concept.

usage: check_written_once.py [--root DIR]   (default: the repository holding this file)
       check_written_once.py --self-test    (the check finds what is planted in a
                                             scratch tree and passes a clean one)
exit status: 0 all written once, 1 something written twice (listed), 2 usage or
the msgs/ definitions could not be read.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SCANNED_DIRS = ("daemon", "lib", "tools")
RULE_DIRS = ("msgs/src", "msgs/include")  # the id and names rules only
ID_RULE_HOME = "lib/ident/src/mesh_id_rule.c"
ID_RULE_FUNCTION = "mt_mesh_id_check"
# (file, function): names of the rule that only call ID_RULE_FUNCTION.
ID_RULE_ALIASES = {("msgs/src/mesh_id.c", "mt_msgs_mesh_id_check")}
# Where a _Static_assert may tie a restated limit to its .lcm constant.
TIE_DIRS = ("msgs/src", "msgs/include")
NAMES_HOME = "msgs/src/status_codes.c"
STATUS_NAMES = ("BAD_REQUEST", "UNDECODABLE", "UNKNOWN_MESH", "OUT_OF_RANGE", "TOO_LARGE",
                "DEFECT_REFUSED", "ARCHIVE_FAILED")
NAMES_TABLE_MIN = 5
DISTINCTIVE_MIN = 1000  # values with 4 or more digits


def distinctive(value):
    """A value that only the protocol would write: 4+ digits and not a power
    of two (1024 is also a buffer size or a kilobyte; limits with that value
    are still caught by name, check_limits)."""
    v = abs(value)
    return v >= DISTINCTIVE_MIN and v & (v - 1) != 0
CONCEPT_RE = re.compile(r"(?<![A-Z0-9])(SINGLE_MESSAGE|FIRST_PARTS|MESH_ID|PARTS?|PULLS?|"
                        r"RANGES?|GAPS?|MISSING)(?![A-Z0-9])")
LIMIT_SUFFIX_RE = re.compile(r"_(MAX|MIN|SIZE|LIMIT)$")


class Fail(Exception):
    """The protocol definitions could not be read: exit status 2."""


def mentions_concept(name):
    return CONCEPT_RE.search(name.upper().replace("OUT_OF_RANGE", "")) is not None


# ---- msgs/*.lcm --------------------------------------------------------------

LCM_CONST_RE = re.compile(r"\bconst\s+(u?int(?:8|16|32|64)_t|byte)\s+([A-Za-z_]\w*)\s*=\s*"
                          r"([-+]?(?:0[xX][0-9a-fA-F]+|\d+))\s*;")


class Const:
    def __init__(self, struct, name, value, path, line):
        self.struct, self.name, self.value = struct, name, value
        self.path, self.line = path, line
        self.is_limit = mentions_concept(name) or LIMIT_SUFFIX_RE.search(name) is not None
        self.c_name = f"MESHTOPO_{struct.upper()}_{name}"

    def label(self):
        return f"{self.struct}.{self.name}"


def strip_lcm_comments(text):
    """The .lcm text with // and /* */ comments blanked (newlines kept)."""
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group()), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def read_consts(root):
    msgs = os.path.join(root, "msgs")
    try:
        names = sorted(n for n in os.listdir(msgs) if n.endswith(".lcm"))
    except OSError as e:
        raise Fail(f"cannot list {msgs}: {e}")
    if not names:
        raise Fail(f"no message definitions (*.lcm) in {msgs}")
    consts = []
    for n in names:
        with open(os.path.join(msgs, n), encoding="utf-8") as f:
            text = strip_lcm_comments(f.read())
        m = re.search(r"\bstruct\s+(\w+)", text)
        struct = m.group(1) if m else n[:-4]
        for m in LCM_CONST_RE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            consts.append(Const(struct, m.group(2), int(m.group(3), 0), f"msgs/{n}", line))
    return consts


# ---- C tokens ----------------------------------------------------------------

TOKEN_RE = re.compile(r"""
    (?P<ws>[ \t\r\f\v]+)
  | (?P<nl>\n)
  | (?P<splice>\\\n)
  | (?P<lcom>//(?:[^\n\\]|\\\n?)*)
  | (?P<bcom>/\*.*?(?:\*/|\Z))
  | (?P<str>(?:u8|[uUL])?"(?:[^"\\\n]|\\.|\\\n)*"?)
  | (?P<chr>(?:u8|[uUL])?'(?:[^'\\\n]|\\.)*'?)
  | (?P<num>\.?[0-9](?:[eEpP][-+]|[0-9A-Za-z_.])*)
  | (?P<id>[A-Za-z_]\w*)
  | (?P<punct>\#\#|->|\+\+|--|<<=?|>>=?|[<>=!&|^+\-*/%]=|&&|\|\||\.\.\.|.)
""", re.X | re.S)

ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "0": "\0", "\\": "\\", "'": "'", '"': '"',
           "?": "?", "a": "\a", "b": "\b", "f": "\f", "v": "\v"}


def literal_text(tok):
    """The characters a string or character literal stands for (roughly: the
    common escapes, octal and hex decoded; enough to compare with '/' or "..")."""
    body = tok[tok.index(tok[-1]) + 1:-1] if tok[-1] in "\"'" else tok
    out, i = [], 0
    while i < len(body):
        c = body[i]
        if c != "\\" or i + 1 == len(body):
            out.append(c)
            i += 1
            continue
        e = body[i + 1]
        if e == "x":
            m = re.match(r"[0-9a-fA-F]+", body[i + 2:])
            out.append(chr(int(m.group(), 16) & 0xFF) if m else "x")
            i += 2 + (len(m.group()) if m else 0)
        elif e in "01234567":
            m = re.match(r"[0-7]{1,3}", body[i + 1:])
            out.append(chr(int(m.group(), 8)))
            i += 1 + len(m.group())
        else:
            out.append(ESCAPES.get(e, e))
            i += 2
    return "".join(out)


def number_value(tok):
    """The value of a C number token, or None when it is not a number we read."""
    t = tok
    t_int = re.sub(r"(?:[uU](?:ll|LL|l|L)?|(?:ll|LL|l|L)[uU]?|wb|WB|uwb|UWB)$", "", t)
    try:
        if re.fullmatch(r"0[xX][0-9a-fA-F]+", t_int):
            return int(t_int, 16)
        if re.fullmatch(r"0[bB][01]+", t_int):
            return int(t_int[2:], 2)
        if re.fullmatch(r"0[0-7]*", t_int):
            return int(t_int, 8)
        if re.fullmatch(r"[1-9][0-9]*", t_int):
            return int(t_int)
        f = float(re.sub(r"[fFlL]$", "", t))
        return int(f) if f == int(f) else None
    except (ValueError, OverflowError):
        return None


class Tok:
    __slots__ = ("kind", "text", "line", "spaced")

    def __init__(self, kind, text, line, spaced):
        self.kind, self.text, self.line = kind, text, line
        self.spaced = spaced  # white space or a comment comes before it

    def __repr__(self):
        return f"{self.kind}:{self.text}@{self.line}"


def tokenize(text):
    """(code, directives): code tokens outside preprocessor lines, and one
    (line, tokens) per directive (`#` first, continuation lines joined)."""
    code, directives = [], []
    line, at_line_start, directive, spaced = 1, True, None, False
    for m in TOKEN_RE.finditer(text):
        kind, tok = m.lastgroup, m.group()
        start_line = line
        line += tok.count("\n")
        if kind == "nl":
            at_line_start, directive, spaced = True, None, True
            continue
        if kind in ("ws", "splice", "lcom", "bcom"):
            spaced = True
            continue
        if at_line_start and tok == "#":
            directive = (start_line, [])
            directives.append(directive)
        at_line_start = False
        t = Tok(kind, tok, start_line, spaced)
        spaced = False
        (directive[1] if directive is not None else code).append(t)
    return code, directives


KEYWORDS = {"if", "while", "for", "switch", "return", "sizeof", "_Alignof", "alignof",
            "__attribute__", "__declspec", "_Static_assert", "static_assert", "defined",
            "__typeof__", "typeof", "_Generic"}


class Unit:
    """A top-level piece of a C file: a function body or one declaration."""

    def __init__(self, tokens, is_function, name):
        self.tokens, self.is_function, self.name = tokens, is_function, name
        self.line = tokens[0].line if tokens else 0


def unit_name(tokens, is_function):
    depth = 0
    for i, t in enumerate(tokens):
        if t.text in ("(", "[", "=") and depth == 0 and i > 0:
            prev = tokens[i - 1]
            if prev.kind == "id" and prev.text not in KEYWORDS:
                if t.text == "(" or not is_function:
                    return prev.text
        if t.text in ("(", "[", "{"):
            depth += 1
        elif t.text in (")", "]", "}"):
            depth -= 1
    ids = [t.text for t in tokens if t.kind == "id" and t.text not in KEYWORDS]
    return ids[-1] if ids else "?"


def split_units(code):
    """Top-level units: `... ( ... ) { body }` at brace depth 0 without a
    top-level `=` is a function; anything else ends at its `;`."""
    units, start, depth, func, extern_c = [], 0, 0, False, 0
    for i, t in enumerate(code):
        if t.text == "{" and depth == 0 and i >= 2 and code[i - 1].text == '"C"' and \
                code[i - 2].text == "extern":
            extern_c += 1  # extern "C" { ... } holds declarations, not a unit
            start = i + 1
        elif t.text == "}" and depth == 0 and extern_c:
            extern_c -= 1
            start = i + 1
        elif t.text == "{":
            if depth == 0 and i > start and code[i - 1].text == ")":
                func = not any(h.text == "=" for h in code[start:i])
            depth += 1
        elif t.text == "}":
            depth = max(0, depth - 1)
            if depth == 0 and func:
                units.append(Unit(code[start:i + 1], True, unit_name(code[start:i + 1], True)))
                start, func = i + 1, False
        elif t.text == ";" and depth == 0:
            units.append(Unit(code[start:i + 1], False, unit_name(code[start:i + 1], False)))
            start = i + 1
    if start < len(code):
        units.append(Unit(code[start:], False, unit_name(code[start:], False)))
    return units


# ---- The four rules ----------------------------------------------------------

class Finding:
    def __init__(self, rule, path, line, message, consts=()):
        self.rule, self.path, self.line, self.message = rule, path, line, message
        self.consts = list(consts)

    def where(self):
        return f"{self.path}:{self.line}"

    def __str__(self):
        return f"{self.where()}: [{self.rule}] {self.message}"


def names_of(consts):
    return " / ".join(f"{c.label()} ({c.c_name})" for c in consts)


def bare_number(tokens):
    """The value of a replacement list or initializer that is one number,
    possibly in parentheses or behind a cast: 16, (16), 16u, ((size_t)16)."""
    toks = list(tokens)
    while len(toks) >= 2 and toks[0].text == "(" and toks[-1].text == ")":
        toks = toks[1:-1]
    if len(toks) >= 3 and toks[0].text == "(":
        close = next((k for k, t in enumerate(toks) if t.text == ")"), None)
        if close and all(t.kind == "id" or t.text == "*" for t in toks[1:close]):
            return bare_number(toks[close + 1:])
    if len(toks) == 1 and toks[0].kind == "num":
        return number_value(toks[0].text)
    return None


def check_values(path, code, directives, by_value, findings):
    for t in code + [t for _, toks in directives for t in toks]:
        if t.kind != "num":
            continue
        v = number_value(t.text)
        hits = [c for c in by_value.get(v, ()) if distinctive(c.value)]
        if hits:
            findings.append(Finding("value", path, t.line,
                                    f"{t.text} is the value of {names_of(hits)}", hits))


def static_ties(code):
    """{(a, b), (b, a)} for each _Static_assert(a == b, ...) in code."""
    ties = set()
    for i, t in enumerate(code):
        if t.text in ("_Static_assert", "static_assert") and i + 5 < len(code):
            a, eq, b = code[i + 2], code[i + 3], code[i + 4]
            if (code[i + 1].text == "(" and a.kind == "id" and eq.text == "==" and
                    b.kind == "id" and code[i + 5].text in (",", ")")):
                ties |= {(a.text, b.text), (b.text, a.text)}
    return ties


def check_limits(path, code, directives, limits_by_value, findings, ties=frozenset()):
    def report(name, value, line, what):
        hits = [c for c in limits_by_value.get(value, ()) if (c.c_name, name) not in ties]
        if value is not None and hits and mentions_concept(name):
            findings.append(Finding("limit", path, line,
                                    f"{what} {name} = {value} restates {names_of(hits)}", hits))

    for line, toks in directives:
        if len(toks) >= 3 and toks[1].text == "define" and toks[2].kind == "id":
            rest = toks[3:]
            if rest and rest[0].text == "(" and not rest[0].spaced:
                continue  # a function-like macro
            report(toks[2].text, bare_number(rest), line, "#define")
    # Enumerators and const declarations: NAME = number followed by , ; or }.
    enum_depths, depth, stmt_start = [], 0, 0
    pending_enum = False
    for i, t in enumerate(code):
        if t.text == "enum":
            # `enum {` or `enum tag {` opens a list of enumerators.
            k = i + 2 if i + 1 < len(code) and code[i + 1].kind == "id" else i + 1
            pending_enum = k < len(code) and code[k].text == "{"
        elif t.text == "{":
            depth += 1
            if pending_enum:
                enum_depths.append(depth)
            pending_enum = False
            stmt_start = i + 1
        elif t.text == "}":
            if enum_depths and enum_depths[-1] == depth:
                enum_depths.pop()
            depth -= 1
            stmt_start = i + 1
        elif t.text == ";":
            pending_enum = False
            stmt_start = i + 1
        elif t.text == "=" and i > 0 and code[i - 1].kind == "id":
            j = i + 1
            while j < len(code) and code[j].text not in (",", ";", "}"):
                j += 1
            in_enum = bool(enum_depths) and enum_depths[-1] == depth
            is_const = any(s.text == "const" for s in code[stmt_start:i])
            if in_enum or is_const:
                report(code[i - 1].text, bare_number(code[i + 1:j]), code[i - 1].line,
                       "enumerator" if in_enum else "const")


def tests_slash(tokens):
    return any(t.kind == "chr" and literal_text(t.text) == "/" for t in tokens)


# ".." itself, or quoted in a message; "../" in a path being built is not the rule.
DOTDOT_IN_STRING = ('".."', "'..'")


def tests_dotdot(tokens):
    for k, t in enumerate(tokens):
        if t.kind == "str":
            s = literal_text(t.text)
            if s == ".." or any(p in s for p in DOTDOT_IN_STRING):
                return True
        if t.kind == "chr" and literal_text(t.text) == ".":
            # c == '.' && id[i + 1] == '.': two dot bytes in one expression.
            for u in tokens[k + 1:k + 16]:
                if u.text in (";", "{", "}"):
                    break
                if u.kind == "chr" and literal_text(u.text) == ".":
                    return True
    return False


def is_alias(path, unit):
    """A name of the rule that hands the id to its one copy and nothing more."""
    return ((path, unit.name) in ID_RULE_ALIASES and
            any(t.kind == "id" and t.text == ID_RULE_FUNCTION for t in unit.tokens) and
            not (tests_slash(unit.tokens) or tests_dotdot(unit.tokens)))


def check_id_rule(path, units, findings):
    if path == ID_RULE_HOME:
        return
    for u in units:
        if not u.is_function:
            continue
        if is_alias(path, u):
            continue
        if re.search(r"id_check", u.name, re.I):
            findings.append(Finding("id-rule", path, u.line,
                                    f"function {u.name}() is named like the mesh-id check, "
                                    f"whose one copy is {ID_RULE_FUNCTION} ({ID_RULE_HOME})"))
        elif tests_slash(u.tokens) and tests_dotdot(u.tokens):
            findings.append(Finding("id-rule", path, u.line,
                                    f"function {u.name}() tests both '/' and \"..\": the mesh-id "
                                    f"rule, whose one copy is {ID_RULE_FUNCTION} ({ID_RULE_HOME})"))


def status_names_in(unit):
    return sorted({literal_text(t.text) for t in unit.tokens if t.kind == "str"} &
                  set(STATUS_NAMES))


def check_names(path, units, findings):
    for u in units:
        names = status_names_in(u)
        if len(names) >= NAMES_TABLE_MIN:
            what = "function" if u.is_function else "declaration"
            findings.append(Finding("names", path, u.line,
                                    f"{what} {u.name} spells {len(names)} status-code names "
                                    f"({', '.join(names)}): the table is {NAMES_HOME}'s"))


# ---- The whole tree ----------------------------------------------------------

def source_files(root, dirs):
    for d in dirs:
        top = os.path.join(root, d)
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames[:] = sorted(n for n in dirnames if not n.startswith("build"))
            for n in sorted(filenames):
                if n.endswith((".c", ".h")):
                    full = os.path.join(dirpath, n)
                    yield os.path.relpath(full, root).replace(os.sep, "/"), full


def read_c(full):
    with open(full, encoding="utf-8", errors="replace") as f:
        text = f.read()
    code, directives = tokenize(text)
    return code, directives


def places(findings):
    """file:line of each finding, in file then line order, once each."""
    return [f"{p}:{n}" for p, n in sorted({(f.path, f.line) for f in findings})]


def check_tree(root):
    """(report lines, findings) for the repository at root."""
    consts = read_consts(root)
    by_value, limits_by_value = {}, {}
    for c in consts:
        by_value.setdefault(c.value, []).append(c)
        if c.is_limit:
            limits_by_value.setdefault(c.value, []).append(c)
    findings = []

    # A limit declared in two .lcm files.
    by_name = {}
    for c in consts:
        if c.is_limit:
            by_name.setdefault(c.name, []).append(c)
    for name, cs in sorted(by_name.items()):
        for c in cs[1:]:
            findings.append(Finding("limit", c.path, c.line,
                                    f"{c.label()} = {c.value} is declared again (first in "
                                    f"{cs[0].path}:{cs[0].line})", [cs[0]]))

    ties = set()
    for rel, full in source_files(root, TIE_DIRS):
        ties |= static_ties(read_c(full)[0])
    for rel, full in source_files(root, SCANNED_DIRS):
        code, directives = read_c(full)
        units = split_units(code)
        check_values(rel, code, directives, by_value, findings)
        check_limits(rel, code, directives, limits_by_value, findings, ties)
        check_id_rule(rel, units, findings)
        check_names(rel, units, findings)
    for rel, full in source_files(root, RULE_DIRS):
        if rel in (ID_RULE_HOME, NAMES_HOME):
            continue
        units = split_units(read_c(full)[0])
        check_id_rule(rel, units, findings)
        check_names(rel, units, findings)

    # The homes hold what they are the home of.
    homes = []
    id_home = os.path.join(root, ID_RULE_HOME)
    if os.path.exists(id_home):
        units = split_units(read_c(id_home)[0])
        ok = [u for u in units if u.is_function and u.name == ID_RULE_FUNCTION and
              tests_slash(u.tokens) and tests_dotdot(u.tokens)]
    else:
        ok = []
    if not ok:
        findings.append(Finding("id-rule", ID_RULE_HOME, 1,
                                f"{ID_RULE_FUNCTION}(), testing '/' and \"..\", is not here"))
    homes.append(("mesh-id rule", f"{ID_RULE_HOME} ({ID_RULE_FUNCTION})", "id-rule", bool(ok)))
    names_home = os.path.join(root, NAMES_HOME)
    tables = []
    if os.path.exists(names_home):
        tables = [u for u in split_units(read_c(names_home)[0])
                  if len(status_names_in(u)) >= NAMES_TABLE_MIN]
    if not tables:
        findings.append(Finding("names", NAMES_HOME, 1,
                                "the status-code name table is not here"))
    homes.append(("status-code names", f"{NAMES_HOME} ({', '.join(u.name for u in tables)})",
                  "names", bool(tables)))

    unique = {(f.path, f.line, f.rule, f.message): f for f in findings}
    findings = [unique[k] for k in sorted(unique)]
    lines = []
    for c in consts:
        elsewhere = places(f for f in findings if c in f.consts)
        kind = "" if c.is_limit or abs(c.value) >= DISTINCTIVE_MIN else " (enumeration)"
        where = "only" if not elsewhere else "and also " + ", ".join(elsewhere)
        lines.append(f"{c.name} = {c.value}{kind}: {c.path} {where}")
    for what, home, rule, found in homes:
        elsewhere = places(f for f in findings if f.rule == rule and
                           f.path != home.split()[0])
        if not found:
            lines.append(f"{what}: MISSING from {home}")
        else:
            lines.append(f"{what}: {home} " +
                         ("only" if not elsewhere else "and also " + ", ".join(elsewhere)))
    return lines, findings


def run_check(root):
    try:
        lines, findings = check_tree(root)
    except (Fail, OSError) as e:
        print(f"check_written_once: {e}", file=sys.stderr)
        return 2
    for line in lines:
        print(line)
    if not findings:
        print("OK: every protocol constant and rule is written once")
        return 0
    print(f"FAILED: {len(findings)} place(s) write the protocol again:")
    for f in findings:
        print(f"  {f}")
    return 1


# ---- --self-test -------------------------------------------------------------

SELF_TEST_LCM = """\
// A scratch type for the self-test.
package t;

struct x_t
{
    int64_t utime;
    const int32_t MESH_ID_MAX = 255;       // bytes
    const int32_t PART_SIZE = 57344;
    const int32_t FIRST_PARTS = 16;
    const int32_t KIND_ONE = 2;            // an enumeration, not a limit
}
"""

SELF_TEST_HOME_ID = """\
/* The home of the id rule, and its limit. */
#define MT_MESH_ID_MAX 255
int mt_mesh_id_check(const char *id)
{
    for (; *id; id++) {
        if (*id == '/') return 1;
        if (*id == '.' && id[1] == '.') return 1;
    }
    return 0;
}
"""

# msgs/'s name of the rule, and the tie of the home's limit to the .lcm's.
SELF_TEST_ALIAS_ID = """\
/* The id rule's name in msgs/. */
_Static_assert(MESHTOPO_X_T_MESH_ID_MAX == MT_MESH_ID_MAX, "the same limit");
int mt_msgs_mesh_id_check(const char *id) { return mt_mesh_id_check(id); }
"""

SELF_TEST_HOME_NAMES = """\
/* The home of the names. */
static const char *const names[] = {
    "OK", "BAD_REQUEST", "UNDECODABLE", "UNKNOWN_MESH", "OUT_OF_RANGE", "TOO_LARGE",
};
"""

# Clean code: every line here must pass (the protocol is read from msgs/).
SELF_TEST_CLEAN = """\
/* Uses the protocol without writing it again: 57344 and "BAD_REQUEST" in a
 * comment, FIRST_PARTS = 16 here too. */
#include <string.h>
#define MT__MAX_PARTS 2                  /* a concept name, not a protocol value */
#define WINDOW 16                        /* a protocol value, no concept name */
#define PART_WINDOW MESHTOPO_X_T_FIRST_PARTS
#define MT__OUT_OF_RANGE_LIMIT 255        /* OUT_OF_RANGE is not the RANGE concept */
#define PARTS(n) 16
enum { OUT_OF_RANGE_PART = 3 };
static const char *banner = "57344 bytes: BAD_REQUEST UNDECODABLE UNKNOWN_MESH OUT_OF_RANGE "
                            "TOO_LARGE";
static int file_name(const char *s)
{
    size_t n = 1023 + 1;
    if (strchr(s, '/')) return (int)n;    /* a slash, but no ".." */
    return strcmp(s, "...") == 0;
}
static void exe_dir(char *out, const char *self)
{
    const char *slash = strrchr(self, '/');
    sprintf(out, "%.*s/../libexec", (int)(slash - self), self);
}
static int dots(const char *s) { return s[0] == '.' && strcmp(s, ".") == 0; }
int check(const char *id) { return mt_msgs_mesh_id_check(id); }
static const char *one(int c) { return c ? "BAD_REQUEST" : "TOO_LARGE"; }
"""

# (file, code, [(rule, line), ...]): each planted line and what must find it.
SELF_TEST_PLANTED = [
    ("daemon/parts.h", """\
/* A second FIRST_PARTS. */
#define FOO_PARTS 16
#define MESH_ID_LIMIT (255u)
#define GAP_BYTES ((size_t)57344)
""", [("limit", 2), ("limit", 3), ("value", 4), ("limit", 4)]),
    ("daemon/send.c", """\
/* 57344 written out in code. */
#include <stddef.h>
static size_t part_bytes(void)
{
    enum { PULL_PARTS = 16 };
    static const int missing_parts = 255;
    size_t n = 0xE000; /* 57344 */
    return n + 57344 + PULL_PARTS + missing_parts + sizeof "57344";
}
""", [("limit", 5), ("limit", 6), ("value", 7), ("value", 8)]),
    ("lib/ids.c", """\
/* The mesh-id rule written again, twice. */
#include <string.h>
int lib_id_ok(const char *id)
{
    for (const char *p = id; *p; p++)
        if (*p == '/' || (p[0] == '.' && p[1] == '.')) return 0;
    return 1;
}
int other(const char *id)
{
    return strchr(id, '/') == NULL && strstr(id, "..") == NULL;
}
int mt_client_mesh_id_check(const char *id) { return other(id); }
""", [("id-rule", 3), ("id-rule", 9), ("id-rule", 13)]),
    ("tools/names.c", """\
/* A second status-code name table, and one spelled out in a function. */
static const char *const code_names[] = {
    [1] = "BAD_REQUEST", [2] = "UNDECODABLE", [3] = "UNKNOWN_MESH",
    [5] = "OUT_OF_RANGE", [7] = "TOO_LARGE",
};
const char *name_of(int c)
{
    switch (c) {
    case 1: return "BAD_REQUEST";
    case 9: return "DEFECT_REFUSED";
    case 13: return "ARCHIVE_FAILED";
    case 7: return "TOO_LARGE";
    default: return "UNDECODABLE";
    }
}
""", [("names", 2), ("names", 6)]),
    ("msgs/src/other.c", """\
/* The id rule in msgs/, but not in its home; a limit tied nowhere. */
int path_like(const char *s) { return s[0] == '/' || strcmp(s, "..") == 0; }
int mt_other_mesh_id_check(const char *id) { return mt_mesh_id_check(id); }
""", [("id-rule", 2), ("id-rule", 3)]),
    ("tools/id_limit.h", """\
/* The id limit restated with a tie of its own, outside msgs/. */
#define TOOL_MESH_ID_MAX 255
_Static_assert(MESHTOPO_X_T_MESH_ID_MAX == TOOL_MESH_ID_MAX, "not msgs/'s tie");
""", [("limit", 2)]),
]


def write(root, rel, text):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def make_tree(root, planted):
    write(root, "msgs/x_t.lcm", SELF_TEST_LCM)
    write(root, ID_RULE_HOME, SELF_TEST_HOME_ID)
    write(root, "msgs/src/mesh_id.c", SELF_TEST_ALIAS_ID)
    write(root, NAMES_HOME, SELF_TEST_HOME_NAMES)
    write(root, "daemon/clean.c", SELF_TEST_CLEAN)
    write(root, "lib/client/src/clean.c", SELF_TEST_CLEAN)
    write(root, "tests/ignored.c", "#define FOO_PARTS 16\nint n = 57344;\n")
    write(root, "build-x/ignored.c", "int n = 57344;\n")
    write(root, "lib/build-asan/ignored.c", "int n = 57344;\n")
    if planted:
        for rel, text, _ in SELF_TEST_PLANTED:
            write(root, rel, text)


def self_test():
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    script = os.path.abspath(__file__)
    with tempfile.TemporaryDirectory(prefix="meshtopo-written-once-") as tmp:
        clean, dirty, homeless = (os.path.join(tmp, n) for n in ("clean", "dirty", "homeless"))
        make_tree(clean, False)
        make_tree(dirty, True)
        make_tree(homeless, False)
        os.remove(os.path.join(homeless, ID_RULE_HOME))
        write(homeless, NAMES_HOME, "/* nothing */\n")

        lines, findings = check_tree(clean)
        check(not findings, "a clean tree passes: " + "; ".join(map(str, findings)))
        check("PART_SIZE = 57344: msgs/x_t.lcm only" in lines,
              "the clean tree's report lists PART_SIZE = 57344 as written once")
        check("KIND_ONE = 2 (enumeration): msgs/x_t.lcm only" in lines,
              "an enumeration const is listed, not taken for a limit")

        lines, findings = check_tree(dirty)
        found = {(f.path, f.rule, f.line) for f in findings}
        expected = {(rel, rule, line) for rel, _, marks in SELF_TEST_PLANTED
                    for rule, line in marks}
        for rel, rule, line in sorted(expected):
            check((rel, rule, line) in found, f"{rule} at {rel}:{line} is reported")
        extra = sorted(found - expected)
        check(not extra, f"nothing else is reported (extra: {extra})")
        check(any(l.startswith("PART_SIZE = 57344: msgs/x_t.lcm and also daemon/parts.h:4")
                  for l in lines), "the report says where PART_SIZE is written again")
        check(any(l.startswith(f"mesh-id rule: {ID_RULE_HOME} ({ID_RULE_FUNCTION}) and "
                               "also lib/ids.c:3") for l in lines),
              "the report says where the mesh-id rule is written again")

        lines, findings = check_tree(homeless)
        rules = sorted((f.path, f.rule) for f in findings)
        check(rules == [(ID_RULE_HOME, "id-rule"), (NAMES_HOME, "names")],
              f"rules missing from their homes are reported ({rules})")

        for tree, want in ((clean, 0), (dirty, 1), (homeless, 1)):
            p = subprocess.run([sys.executable, script, "--root", tree], capture_output=True,
                               text=True)
            check(p.returncode == want, f"check_written_once.py --root {os.path.basename(tree)} "
                  f"exits {want} (got {p.returncode})")
            verdict = "OK:" if want == 0 else "FAILED:"
            check(any(l.startswith(verdict) for l in p.stdout.splitlines()),
                  f"{os.path.basename(tree)}: the output says {verdict}")
        p = subprocess.run([sys.executable, script, "--root", os.path.join(tmp, "none")],
                           capture_output=True, text=True)
        check(p.returncode == 2, f"a tree without msgs/ exits 2 (got {p.returncode})")

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=os.path.normpath(
        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")))
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    return run_check(args.root)


if __name__ == "__main__":
    sys.exit(main())
