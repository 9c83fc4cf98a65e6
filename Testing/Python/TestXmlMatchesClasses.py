"""The plugin XML against the VTK classes, through the Python package.

Usage: python3 TestXmlMatchesClasses.py Plugin/ImageShockAdvection.xml Plugin/SurfaceShockAdvection.xml ...
(PYTHONPATH holding the package shockfilters).

For every settable property of every filter in the XML: its default_values
equal the value a new object of the class returns, and its range domain
equals the class's vtkSetClampMacro range (Get<Name>MinValue/MaxValue, the
macro's own accessors); an enumeration lists exactly the values the clamp
allows. FlowTime has no clamp: a negative time is an error, so its domain
must only say min 0.
"""
import sys
import xml.etree.ElementTree as ET

import shockfilters

failures = []
checked = 0


def check(condition, message):
    global checked
    checked += 1
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def number(text):
    return float(text)


proxies = [proxy for path in sys.argv[1:] for proxy in ET.parse(path).getroot().iter("SourceProxy")]
check(len(proxies) == len(sys.argv) - 1 and len(proxies) > 0,
      "one filter per XML file: %d filters in %d files" % (len(proxies), len(sys.argv) - 1))
for proxy in proxies:
    cls = getattr(shockfilters, proxy.get("class"))
    instance = cls()
    for prop in proxy:
        command = prop.get("command") or ""
        if not prop.tag.endswith("VectorProperty") or prop.get("information_only") == "1" \
                or not command.startswith("Set") or command == "SetInputArrayToProcess":
            continue
        name = command[3:]
        where = "%s.%s" % (proxy.get("name"), prop.get("name"))
        default = prop.get("default_values")
        check(default is not None and number(default) == float(getattr(instance, "Get" + name)()),
              "%s: XML default %s == class default %s" % (where, default, getattr(instance, "Get" + name)()))
        low = getattr(instance, "Get%sMinValue" % name, None)
        high = getattr(instance, "Get%sMaxValue" % name, None)
        domain = prop.find("IntRangeDomain")
        domain = domain if domain is not None else prop.find("DoubleRangeDomain")
        enum = prop.find("EnumerationDomain")
        if name == "FlowTime":
            check(low is None and domain is not None and domain.get("min") == "0" and domain.get("max") is None,
                  "%s: not clamped by the class, XML min 0 only" % where)
        elif prop.find("BooleanDomain") is not None:
            check(low is None, "%s: a boolean" % where)
        elif enum is not None:
            values = sorted(int(e.get("value")) for e in enum.findall("Entry"))
            check(low is not None and values == list(range(int(low()), int(high()) + 1)),
                  "%s: enumeration %s == clamp %s..%s" % (where, values, low and low(), high and high()))
        else:
            check(low is not None and domain is not None, "%s: clamped by the class and a range in the XML" % where)
            if low is not None and domain is not None:
                check(domain.get("min") is not None and number(domain.get("min")) == low(),
                      "%s: XML min %s == clamp %s" % (where, domain.get("min"), low()))
                check(domain.get("max") is not None and number(domain.get("max")) == high(),
                      "%s: XML max %s == clamp %s" % (where, domain.get("max"), high()))

print("%d checks, %d failed" % (checked, len(failures)))
sys.exit(1 if failures or checked < 40 else 0)
