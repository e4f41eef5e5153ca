"""The fenced code blocks of README.md's "## Python" section, for the tests
that run them (python.readme, python.client)."""
import os
import re

README = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))), "README.md")


def python_section_blocks():
    """[(language, text)] of the fenced blocks of the Python section, in order."""
    with open(README, encoding="utf-8") as f:
        text = f.read()
    start = text.index("\n## Python\n")
    end = text.find("\n## ", start + 1)
    section = text[start:end if end >= 0 else len(text)]
    return re.findall(r"^```(\w+)\n(.*?)^```$", section, re.S | re.M)


def local_example():
    """The example that needs no daemon, and the output the README says it prints."""
    blocks = python_section_blocks()
    code = [b for lang, b in blocks if lang == "python" and "meshtopo.Client" not in b]
    printed = [b for lang, b in blocks if lang == "text"]
    assert len(code) == 1 and len(printed) == 1, "README's Python section changed shape"
    return code[0], printed[0]


def client_example():
    """The example that talks to meshtopod (it uses the local one's arrays)."""
    code = [b for lang, b in python_section_blocks() if lang == "python" and
            "meshtopo.Client" in b]
    assert len(code) == 1, "README's Python section has no Client example"
    return code[0]
