#!/usr/bin/env python3
"""Writes the type stub (__init__.pyi) of the package `rcme` from the built binding itself.

Nothing is listed by hand: functions, their overloads and argument names come from the
cv2-style signature lines of the docstrings ("name(a, b[, c]) -> retval, c"), the classes'
fields from their properties, and each field's type from the value it has in a default-built
instance (None: an array field). The types of the functions' arguments and results follow
from their names (the names OpenCV's generator would give them too).

    generate_stub.py --path <dir holding the package rcme> --out <dir>/rcme/__init__.pyi

Run by the build after linking the module; needs no NumPy.
"""

import argparse
import importlib
import re
import sys

ARRAY = "numpy.ndarray"
ARRAY_IN = "ArrayLike"
OPTIONAL_ARRAY = "numpy.ndarray | None"

# Argument names (or function.argument) -> types; a name not listed is an array input.
ARGUMENT_TYPES = {
    "params": "Params", "usacParams": "Any", "status": "int", "method": "int", "name": "str",
    "ransacReprojThreshold": "float", "confidence": "float", "maxIters": "int", "prob": "float",
    "threshold": "float", "focal": "float", "pp": "tuple[float, float]", "threads": "int",
    "cameraMatrix": "ArrayLike | None",
    "pairs": "Iterable[tuple[ArrayLike | None, ArrayLike | None]]",
    "generateScene.params": "SceneParams",
    "estimateRelativeMotionBatch.cameraMatrix": "ArrayLike | Sequence[ArrayLike | None] | None",
}
# Names of results that are not arrays (retval is typed per function below).
RESULT_TYPES = {"status": "int"}
# retval of each function; absent: an array or None.
RETVAL_TYPES = {
    "estimateRelativeMotion": "Report", "estimateRelativeMotionBatch": "list[Report]",
    "recoverPose": "int", "generateScene": "SyntheticScene", "compareMotion": "MotionError",
    "statusToString": "str", "methodName": "str", "methodFromString": "int",
    "fromUsacParams": "Params", "Params_fromUsacParams": "Params",
}
SIGNATURE = re.compile(r"^(\w+)\((.*)\)\s*->\s*(.*)$")


def parse_signature(line):
    """('name', [(arg, optional)], [results]) from a cv2-style signature line, or None."""
    m = SIGNATURE.match(line.strip())
    if not m:
        return None
    name, args, results = m.groups()
    parsed, depth = [], 0
    for token in re.findall(r"\[|\]|[^\[\],\s]+", args):
        if token == "[":
            depth += 1
        elif token != "]":
            parsed.append((token, depth > 0))
    return name, parsed, [r.strip() for r in results.split(",") if r.strip()]


def signatures(function):
    """The parsed signature lines, named as the function (Params_fromUsacParams's docstring
    is the one of Params.fromUsacParams)."""
    doc = function.__doc__ or ""
    found = [parse_signature(line) for line in doc.splitlines() if not line.startswith(".")]
    name = function.__name__
    return [(name,) + s[1:] for s in found
            if s and (s[0] == name or name.endswith("_" + s[0]))]


def docstring_body(function, name):
    """The description lines (".   ...") of every overload, for the stub's docstring."""
    lines = [line[1:].strip() for line in (function.__doc__ or "").splitlines()
             if line.startswith(".")]
    return "\n".join(lines)


def result_type(function_name, results):
    types = []
    for r in results:
        if r == "retval":
            types.append(RETVAL_TYPES.get(function_name, OPTIONAL_ARRAY))
        else:
            types.append(RESULT_TYPES.get(r, OPTIONAL_ARRAY))
    if len(types) == 1:
        return types[0]
    return "tuple[%s]" % ", ".join(types)


def argument_type(function_name, name, optional):
    t = ARGUMENT_TYPES.get(function_name + "." + name, ARGUMENT_TYPES.get(name))
    if t is None:  # an array: anything array-like, or None (an empty array, as in cv2)
        return ARRAY_IN + " | None"
    return t


def quote(text, indent):
    text = text.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    text = text.replace("\n", "\n" + indent)
    return '%s"""%s"""\n' % (indent, text) if text else ""


def function_stub(function, indent="", static=False):
    sigs = signatures(function)
    if not sigs:
        return "%sdef %s(*args: Any, **kwargs: Any) -> Any: ...\n" % (indent, function.__name__)
    out = []
    for name, args, results in sigs:
        params = ", ".join("%s: %s%s" % (a, argument_type(name, a, opt), " = ..." if opt else "")
                           for a, opt in args)
        head = ""
        if len(sigs) > 1:
            head += indent + "@overload\n"
        if static:
            head += indent + "@staticmethod\n"
        out.append("%sdef %s(%s) -> %s: ...\n" % (head + indent, name, params,
                                                 result_type(name, results)))
    body = docstring_body(function, function.__name__)
    if body and len(sigs) == 1:  # a docstring on the one definition
        out[0] = out[0][:-len(" ...\n")] + "\n" + quote(body, indent + "    ")
    return "".join(out)


def field_type(value):
    if value is None:
        return OPTIONAL_ARRAY
    return type(value).__name__


def class_stub(cls):
    out = ["class %s:\n" % cls.__name__, quote(cls.__doc__ or "", "    ")]
    instance = cls()
    fields = [n for n, v in vars(cls).items() if isinstance(v, property)]  # declaration order
    for name in fields:
        out.append("    %s: %s\n" % (name, field_type(getattr(instance, name))))
        doc = vars(cls)[name].__doc__
        if doc:
            out.append(quote(doc, "    "))
    init_doc = cls.__init__.__doc__ or ""
    if "Keyword form" in init_doc:  # Params(method=..., sigma=...)
        kwargs = ", ".join("%s: %s = ..." % (n, field_type(getattr(instance, n)).replace(
            OPTIONAL_ARRAY, ARRAY_IN + " | None")) for n in fields)
        out.append("    def __init__(self, *, %s) -> None: ...\n" % kwargs)
    else:
        out.append("    def __init__(self) -> None: ...\n")
    for name, value in sorted(vars(cls).items()):
        if isinstance(value, staticmethod) or (callable(value) and not name.startswith("_")
                                               and not isinstance(value, property)):
            out.append(function_stub(getattr(cls, name), "    ", static=True))
    return "".join(out)


def generate(module):
    out = ['"""Type stub of the package rcme, generated by generate_stub.py from the built binding."""\n\n',
           "from typing import Any, Iterable, Sequence, overload\n\n",
           "import numpy\n",
           "from numpy.typing import ArrayLike\n\n"]
    names = sorted(n for n in dir(module) if not n.startswith("_"))
    for n in names:
        v = getattr(module, n)
        if isinstance(v, int) and not isinstance(v, bool):
            out.append("%s: int\n" % n)
    out.append("\nclass error(Exception):\n    code: int\n    err: str\n    func: str\n"
               "    file: str\n    line: int\n")
    for n in names:
        v = getattr(module, n)
        if isinstance(v, type) and not issubclass(v, BaseException):
            out.append("\n" + class_stub(v))
    out.append("\n")
    for n in names:
        v = getattr(module, n)
        if callable(v) and not isinstance(v, type):
            out.append(function_stub(v))
    return "".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--path", required=True, help="folder that holds the package rcme")
    ap.add_argument("--out", required=True, help="the .pyi file to write")
    args = ap.parse_args()
    sys.path.insert(0, args.path)
    module = importlib.import_module("rcme")
    text = generate(module)
    with open(args.out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
