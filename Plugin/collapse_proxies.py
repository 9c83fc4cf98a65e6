"""Collapse server-manager XML proxy inheritance (base_proxygroup/base_proxyname).

Usage: python3 collapse_proxies.py INPUT.xml OUTPUT.xml [--drop-group GROUP]...

ParaView resolves proxy inheritance when it loads the XML (see
vtkSIProxyDefinitionManager::GetCollapsedProxyDefinition), but its help
generator (paraview_client_documentation) reads the XML as written: the help
page of a derived proxy would list only its own properties, and the abstract
base proxies would get pages of their own. This script writes the definitions
the way ParaView collapses them, so that the plugin embeds, and documents,
complete proxies:

- the base's elements come first, then the derived proxy's;
- a derived property with override="1" replaces the base property of the same
  name where it stands (so the panel order is kept); any other name clash is
  an error, as it is for ParaView;
- a derived <Documentation> replaces the base one;
- the derived proxy keeps its own attributes, without the base_* ones.

Groups named with --drop-group (abstract bases) are left out of the output.
"""
import argparse
import copy
import sys
import xml.etree.ElementTree as ET


def property_name(element):
    if element.tag.endswith("Property") and element.get("name"):
        return element.get("name")
    return None


def collapse(definitions, group, name, chain=()):
    key = (group, name)
    if key in chain:
        sys.exit("collapse_proxies: inheritance cycle through %s/%s" % key)
    if key not in definitions:
        sys.exit("collapse_proxies: no base proxy %s/%s" % key)
    element = definitions[key]
    base_group, base_name = element.get("base_proxygroup"), element.get("base_proxyname")
    if not (base_group and base_name):
        return copy.deepcopy(element)

    result = collapse(definitions, base_group, base_name, chain + (key,))
    result.tag = element.tag
    result.attrib.clear()
    result.attrib.update({k: v for k, v in element.attrib.items()
                          if k not in ("base_proxygroup", "base_proxyname")})
    inherited = {property_name(child): child for child in result if property_name(child)}
    for child in element:
        child = copy.deepcopy(child)
        own = property_name(child)
        if own and own in inherited:
            if child.get("override") != "1":
                sys.exit("collapse_proxies: %s/%s redefines property %s without override=\"1\""
                         % (group, name, own))
            position = list(result).index(inherited[own])
            result.remove(inherited[own])
            result.insert(position, child)
            continue
        if child.tag == "Documentation":
            for old in result.findall("Documentation"):
                result.remove(old)
        result.append(child)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--drop-group", action="append", default=[])
    arguments = parser.parse_args()

    root = ET.parse(arguments.input).getroot()
    definitions = {}
    for group in root.findall("ProxyGroup"):
        for proxy in group:
            if proxy.get("name"):
                definitions[(group.get("name"), proxy.get("name"))] = proxy

    output = ET.Element(root.tag, root.attrib)
    output.text = "\n  "
    for group in root.findall("ProxyGroup"):
        if group.get("name") in arguments.drop_group:
            continue
        collapsed_group = ET.SubElement(output, "ProxyGroup", group.attrib)
        collapsed_group.text = "\n    "
        collapsed_group.tail = "\n  "
        for proxy in group:
            if proxy.get("name"):
                collapsed = collapse(definitions, group.get("name"), proxy.get("name"))
                collapsed.tail = "\n    "
                collapsed_group.append(collapsed)
    ET.ElementTree(output).write(arguments.output, encoding="utf-8", xml_declaration=False)


if __name__ == "__main__":
    main()
