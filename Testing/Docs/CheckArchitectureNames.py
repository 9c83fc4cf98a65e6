"""Every code name cited in backticks in docs/architecture.md exists in the code.

Usage: python3 CheckArchitectureNames.py SOURCE_DIR [FILE.md]
(FILE.md defaults to SOURCE_DIR/docs/architecture.md.)

Each `backticked` span outside fenced blocks is read as:
- an XML element (`<Tag attr="value" ...>`): some element of Plugin/*.xml has
  that tag and those attribute values;
- a file path (a name with a / or ending .h, .cxx, .xml, .py, .cmake, .md,
  .txt, .sh; `Name.{h,cxx}` means both): it exists in the repository (a bare
  file name anywhere in it; paths under build/ are not checked);
- a command-line option (`--time`): the program's sources spell it "--time";
- code names: identifiers joined by ::, . or -> (`shock::AdvectionParameters`,
  `GridSteps.TheFlowIsTheSameForEverySlabSize`, `GetFlowTime()`): each part
  that looks like a code name (CamelCase, vtk..., lowerCamel, snake_case,
  CONSTANT_CASE, or any part joined by ::) occurs as a word in some file under
  Filters/, IO/, Plugin/, Applications/ or Testing/.
Spans of several words (shell commands, expressions) are checked word by word
the same way; plain lowercase words, numbers and formulas are not code names.

Prints each missing name with its line; exit 1 if any is missing, else 0.
"""
import os
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

CODE_DIRS = ("Filters", "IO", "Plugin", "Applications", "Testing")
TEXT_SUFFIXES = {".h", ".hxx", ".cxx", ".cpp", ".c", ".txt", ".cmake", ".py", ".xml", ".in",
                 ".module", ".plugin", ".sh", ".json"}
PATH_SUFFIXES = (".h", ".cxx", ".xml", ".py", ".cmake", ".md", ".txt", ".sh")
FENCE = re.compile(r"^ *```.*?^ *```[ \t]*$", re.M | re.S)
SPAN = re.compile(r"`([^`\n]+)`")
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
SKIPPED_DIRS = {".git", "__pycache__"}


def skipped_dir(name):
    return name in SKIPPED_DIRS or name == "build" or name.startswith("build-")


def code_words(root):
    """Every identifier-like word of the text files under CODE_DIRS."""
    words = set()
    for top in CODE_DIRS:
        for folder, dirs, files in os.walk(root / top):
            dirs[:] = [d for d in dirs if not skipped_dir(d)]
            for name in files:
                path = pathlib.Path(folder) / name
                if path.suffix in TEXT_SUFFIXES or name == "CMakeLists.txt":
                    words.update(WORD.findall(path.read_text(errors="replace")))
    return words


def file_names(root):
    """The base names of every file of the repository (build trees left out)."""
    names = set()
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if not skipped_dir(d)]
        names.update(files)
    return names


def looks_like_code_name(part, joined):
    """Whether an identifier is a code name rather than a plain word."""
    if not IDENTIFIER.match(part) or len(part) < 2:
        return False
    if joined:  # a part of a::b or a.b is a name even when plain (shock::, .advection)
        return True
    return (part.startswith("vtk") or "_" in part or any(c.isupper() for c in part[1:])
            or (part[0].isupper() and any(c.islower() for c in part)))


def expand_braces(text):
    """`MeshOrder.{h,cxx}` -> [MeshOrder.h, MeshOrder.cxx]."""
    match = re.search(r"\{([^{}]*)\}", text)
    if not match:
        return [text]
    return [expanded for choice in match.group(1).split(",")
            for expanded in expand_braces(text[:match.start()] + choice + text[match.end():])]


def is_path(word):
    core = word.rstrip("*")
    return "/" in core or any(core.endswith(s) for s in PATH_SUFFIXES) or "}" in core and "{" in core


class Checker:
    def __init__(self, root):
        self.root = root
        self.words = code_words(root)
        self.names = file_names(root)
        self.xml = []
        for path in sorted((root / "Plugin").glob("*.xml")):
            self.xml.append(ET.parse(path).getroot())
        self.options = "\n".join(p.read_text(errors="replace")
                                 for p in (root / "Applications").rglob("*")
                                 if p.is_file() and p.suffix in TEXT_SUFFIXES)

    def path_missing(self, word):
        """The parts of a file path that do not exist ([] when all do)."""
        missing = []
        for path in expand_braces(word.rstrip(".,;:")):
            if path.startswith("build/"):
                continue  # the build tree is not part of the repository
            if "/" in path.rstrip("/"):
                found = (list(self.root.glob(path)) if "*" in path else
                         [self.root / path] if (self.root / path).exists() else [])
            else:
                found = [path] if path.rstrip("/") in self.names or (self.root / path).exists() else []
            if not found:
                missing.append(path)
        return missing

    def xml_missing(self, span):
        match = re.match(r"<\s*([A-Za-z_][\w.-]*)", span)
        if not match:
            return []
        tag = match.group(1)
        attributes = dict(re.findall(r'([\w.-]+)="([^"]*)"', span))
        for root in self.xml:
            for element in root.iter(tag):
                if all(element.get(k) == v for k, v in attributes.items()):
                    return []
        return [span]

    def names_missing(self, token):
        """Code names of one word (a::b, a.b, a->b, f(), x=) that occur nowhere."""
        token = re.sub(r"\(.*\)$", "", token.strip(".,;:!?"))  # f() / f(args)
        token = token.rstrip("=").rstrip(".,;:")
        if token.startswith("--"):
            option = re.match(r"--[A-Za-z0-9-]+", token)
            if option and ('"%s"' % option.group(0)) not in self.options:
                return [option.group(0)]
            return []
        parts = re.split(r"::|->|\.", token)
        joined = len(parts) > 1 and "::" in token
        return [part for part in parts
                if looks_like_code_name(part, joined) and part not in self.words]

    def check(self, span):
        """The missing names of one backticked span."""
        span = span.strip()
        if span.startswith("<"):
            return self.xml_missing(span)
        missing = []
        for word in span.split():
            if is_path(word) and not word.startswith("-") and "::" not in word:
                missing += self.path_missing(word)
            elif word.startswith("--"):
                missing += self.names_missing(word)
            else:
                for token in re.findall(r"[A-Za-z_][\w:.>-]*(?:\(\))?=?", word):
                    missing += self.names_missing(token)
        return missing


def spans(text):
    """(line, span) of every backticked span outside fenced blocks."""
    blanked = FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), text)
    for match in SPAN.finditer(blanked):
        yield blanked.count("\n", 0, match.start()) + 1, match.group(1)


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        return 2
    root = pathlib.Path(sys.argv[1]).resolve()
    document = pathlib.Path(sys.argv[2]) if len(sys.argv) == 3 else root / "docs" / "architecture.md"
    checker = Checker(root)
    missing = 0
    checked = 0
    for line, span in spans(document.read_text()):
        checked += 1
        for name in checker.check(span):
            missing += 1
            print("%s:%d: `%s`: %s not found in the code" % (document.name, line, span, name))
    print("%d spans checked, %d names missing" % (checked, missing))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
