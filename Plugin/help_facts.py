#!/usr/bin/env python3
"""Derive the stated facts of the filters' XML from its attributes.

The filters' XML (ImageShockAdvection.xml, SurfaceShockAdvection.xml,
SurfaceShockSharpen.xml) is the one place where a property's default and range are
written (default_values, IntRangeDomain/DoubleRangeDomain, EnumerationDomain,
BooleanDomain); the C++ clamps equal them (TestShockFiltersPlugin checks).
ParaView 5.11's help generator shows default_values raw (an enumeration as
"0") and drops range domains, so this script restates them, by name, as the
last line of each property's <Documentation> ("Default: ...; range ...") and
writes the property tables of docs/paraview.md from the same XML. The
results are committed; the test ShockFilters.HelpFactsUpToDate runs
`help_facts.py --check` and fails when they are stale.

After editing the XML: python3 Plugin/help_facts.py
"""
import argparse
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

HERE = pathlib.Path(__file__).resolve().parent
# The filters' proxies, in the order of the tables of docs/paraview.md.
XMLS = [HERE / name for name in ("ImageShockAdvection.xml", "SurfaceShockAdvection.xml", "SurfaceShockSharpen.xml")]
DOC = HERE.parent / "docs" / "paraview.md"
FACT_PREFIX = "Default: "
PROPERTY_TAGS = ("IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty",
                 "IdTypeVectorProperty")
# The array property has no default_values: the domain picks the active scalars.
ARRAY_DEFAULT = "the input's active scalars (point data first, then cell data)"


def number(text):
    value = float(text)
    return str(int(value)) if value.is_integer() and abs(value) < 1e15 else text


def facts(prop):
    """'Default: ...; range ...' for a property element, or None."""
    if prop.get("information_only") == "1":
        return None
    if prop.find("ArrayListDomain") is not None:
        return FACT_PREFIX + ARRAY_DEFAULT + "."
    default = prop.get("default_values")
    if default is None:
        return None
    enum = prop.find("EnumerationDomain")
    if enum is not None:
        names = {e.get("value"): e.get("text") for e in enum.findall("Entry")}
        values = ", ".join("'%s'" % e.get("text") for e in enum.findall("Entry"))
        return "%s'%s'. Values: %s." % (FACT_PREFIX, names[default], values)
    if prop.find("BooleanDomain") is not None:
        return FACT_PREFIX + ("on" if default == "1" else "off") + "."
    rng = prop.find("IntRangeDomain")
    if rng is None:
        rng = prop.find("DoubleRangeDomain")
    text = FACT_PREFIX + number(default)
    if rng is not None:
        lo, hi = rng.get("min"), rng.get("max")
        if lo is not None and hi is not None:
            text += "; range %s to %s" % (number(lo), number(hi))
        elif lo is not None:
            text += "; at least %s" % number(lo)
    return text + "."


def rewrite_xml(text):
    """The XML with each property's fact line (re)written."""
    tags = "|".join(PROPERTY_TAGS)
    block = re.compile(r"(<(%s)\b[^>]*>)(.*?)(</\2>)" % tags, re.S)

    def fix(match):
        prop = ET.fromstring(match.group(0))
        line = facts(prop)
        body = match.group(3)
        doc = re.search(r"(<Documentation>)(.*?)(\n(\s*)</Documentation>)", body, re.S)
        if line is None or doc is None:
            return match.group(0)
        indent = doc.group(4) + "  "
        lines = [l for l in doc.group(2).split("\n") if not l.strip().startswith(FACT_PREFIX)]
        lines.append(indent + line)
        new_body = body[:doc.start(2)] + "\n".join(lines) + body[doc.end(2):]
        return match.group(1) + new_body + match.group(4)

    return block.sub(fix, text)


def first_sentence(prop):
    doc = prop.find("Documentation")
    text = " ".join((doc.text or "").split()) if doc is not None else ""
    text = text.split(" " + FACT_PREFIX)[0]
    end = re.search(r"(?<!e\.g)(?<!i\.e)\.(\s|$)", text)
    return text[:end.start() + 1] if end else text


def tables(root):
    """Markdown tables: one per filter, pvpython name, default/range, meaning."""
    out = []
    for proxy in root.iter("SourceProxy"):
        out.append("### %s (`%s`)\n" % (proxy.get("label"), proxy.get("name")))
        out.append("| pvpython name | Default; range or values | Meaning |")
        out.append("| --- | --- | --- |")
        for prop in proxy:
            if prop.tag not in PROPERTY_TAGS or prop.get("information_only") == "1":
                continue
            fact = facts(prop) or ""
            fact = fact[len(FACT_PREFIX):].rstrip(".").replace("|", "\\|")
            name = prop.get("label", prop.get("name")).replace(" ", "")
            out.append("| `%s` | %s | %s |" % (name, fact, first_sentence(prop).replace("|", "\\|")))
        out.append("")
    return "\n".join(out).rstrip() + "\n"


BEGIN = "<!-- help_facts.py: begin (generated from the filters' XML in Plugin/; edit the XML) -->\n"
END = "<!-- help_facts.py: end -->\n"


def rewrite_doc(doc_text, xml_texts):
    start, stop = doc_text.find(BEGIN), doc_text.find(END)
    if start < 0 or stop < start:
        raise SystemExit("%s: markers %r ... %r not found" % (DOC, BEGIN.strip(), END.strip()))
    generated = "\n".join(tables(ET.fromstring(text)) for text in xml_texts)
    return doc_text[:start + len(BEGIN)] + "\n" + generated + "\n" + doc_text[stop:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="fail instead of writing when a file is stale")
    args = parser.parse_args()
    stale = []
    xml_old = [path.read_text() for path in XMLS]
    xml_new = [rewrite_xml(text) for text in xml_old]
    doc_old = DOC.read_text()
    doc_new = rewrite_doc(doc_old, xml_new)
    for path, old, new in list(zip(XMLS, xml_old, xml_new)) + [(DOC, doc_old, doc_new)]:
        if old != new:
            stale.append(str(path))
            if not args.check:
                path.write_text(new)
    if args.check and stale:
        print("stale, run python3 Plugin/help_facts.py: " + ", ".join(stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
