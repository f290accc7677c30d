"""Writes hatchery/kinds.py from the node schemas: ``python -m hatchery._generate [PATH]``.

The file is committed; a test checks that it matches what the schemas give now, as
docs/nodes.md is checked against ``hatchery nodes --markdown``.
"""

from __future__ import annotations

import keyword
import sys
import textwrap
from typing import Any, Dict, List

from . import nodes

_TYPES = {
    "float": "float",
    "int": "int",
    "bool": "bool",
    "color": "Tuple[float, float, float, float]",
    "vec3": "Tuple[float, float, float]",
    "path": "str",
    "text": "str",
}


def _kind_text(p: Dict[str, Any]) -> str:
    k = p["kind"]
    if k in ("float", "int"):
        text = f"{k} in [{p['min']:g}, {p['max']:g}]"
        return text + ", or data-relative text" if p["relative"] else text
    if k == "choice":
        return "one of " + ", ".join(repr(c) for c in p["choices"])
    return {"color": "RGBA in [0, 1]", "vec3": "(x, y, z)"}.get(k, k)


def _annotation(p: Dict[str, Any]) -> str:
    if p["kind"] == "choice":
        return "Literal[" + ", ".join(repr(c) for c in p["choices"]) + "]"
    t = _TYPES[p["kind"]]
    return f"Union[{t}, str]" if p["relative"] else t


def _wrap(text: str, indent: str) -> List[str]:
    text = text.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    return textwrap.wrap(" ".join(text.split()), width=96, initial_indent=indent, subsequent_indent=indent + "    ") or [indent]


def generate() -> str:
    kinds = nodes()
    out = [
        '"""The node kinds of hatchery, one class each: its documentation, ports and parameters.',
        "",
        "Generated from the node schemas by ``python -m hatchery._generate``; do not edit.",
        "``help(hatchery.kinds.Silhouette)`` reads a kind's documentation; the class attributes",
        "are the parameters' defaults, typed (usable with ``Graph.set``).",
        '"""',
        "",
        "from typing import Literal, Tuple, Union",
        "",
        "Kind = Literal[",
    ]
    out += [f"    {k['kind']!r}," for k in sorted(kinds, key=lambda k: k["kind"])]
    out += ["]", '"""Every node kind\'s name."""', ""]
    for k in sorted(kinds, key=lambda k: k["kind"]):
        out += ["", f"class {k['kind']}:"]
        doc = _wrap(k["doc"], "    ")
        doc[0] = '    """' + doc[0][4:]
        out += doc + [""]
        for title, ports in (("Inputs", k["inputs"]), ("Outputs", k["outputs"])):
            if ports:
                out.append(f"    {title}:")
                for p in ports:
                    extra = "" if title == "Outputs" else (", required" if p["required"] else ", optional")
                    out += _wrap(f"{p['name']} ({p['type']}{extra}): {p['doc']}", "        ")
                out.append("")
        if k["params"]:
            out.append("    Parameters:")
            for p in k["params"]:
                out += _wrap(f"{p['name']} ({_kind_text(p)}; default {p['default']!r}): {p['doc']}", "        ")
            out.append("")
        out.append('    """')
        out.append("")
        out.append(f"    kind = {k['kind']!r}")
        out.append(f"    category = {k['category']!r}")
        for p in k["params"]:
            # A parameter named like a Python keyword (`global`) gets a trailing underscore.
            name = p["name"] + ("_" if keyword.iskeyword(p["name"]) else "")
            out.append(f"    {name}: {_annotation(p)} = {p['default']!r}")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    text = generate()
    if len(sys.argv) > 1:
        with open(sys.argv[1], "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
