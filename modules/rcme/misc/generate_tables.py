#!/usr/bin/env python3
"""Writes the tables of the public enums and structs from the public headers.

The public headers (include/opencv2/rcme/params.hpp and synthetic.hpp) are the one source of
the names of the enum values and of the CV_PROP_RW fields of Params, Report, SceneParams,
SyntheticScene and MotionError. This script reads them and writes, checked in:

- src/generated/enum_tables.inc: an X-macro list per public enum, the library's source of the
  values (methodName, methodFromString, validateParams);
- misc/python/standalone/generated_bindings.inc: the module constants and the field chains of
  the pybind11 module, with the header comments as docstrings.

    generate_tables.py          rewrites the generated files
    generate_tables.py --check  exits 1, writing nothing, when one of them is stale

Adding an enum value or a field is then an edit of the header and a run of this script. The
module is importable (standard library only): the Python tests read the headers with parse().
"""

import argparse
import os
import re
import sys
import textwrap

MODULE_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
HEADER_DIR = os.path.join(MODULE_DIR, "include", "opencv2", "rcme")
HEADERS = ("params.hpp", "synthetic.hpp")
STRUCTS = ("Params", "Report", "SceneParams", "SyntheticScene", "MotionError")
ENUM_TABLES = os.path.join("src", "generated", "enum_tables.inc")
BINDINGS = os.path.join("misc", "python", "standalone", "generated_bindings.inc")
COLUMNS = 100

# Comments, preprocessor lines, code and separators of a declaration's body.
TOKEN = re.compile(r"""
    (?P<trailing>//!<[^\n]*)            # documents what precedes it
  | (?P<line>//![^\n]*)                 # documents what follows it
  | (?P<block>/\*\*.*?\*/)              # documents what follows it
  | (?P<comment>//[^\n]*|/\*.*?\*/)     # not documentation
  | (?P<preprocessor>\#[^\n]*)
  | (?P<separator>[,;])
  | (?P<code>[^/#,;]+|/)
""", re.S | re.X)


class Value:
    """An enum value: name, int value, documentation."""

    def __init__(self, name, value, doc):
        self.name, self.value, self.doc = name, value, doc


class Field:
    """A CV_PROP_RW field: C++ type, name, documentation."""

    def __init__(self, type_, name, doc):
        self.type, self.name, self.doc = type_, name, doc


def clean_comment(text):
    """The text of a doxygen comment, on one line."""
    text = re.sub(r"^/\*\*|\*/$", "", text.strip())
    text = re.sub(r"^//!<?", "", text)
    return " ".join(text.split())


def declarations(body):
    """(code, documentation) of each declaration of an enum's or a struct's body, split at ','
    and ';'; the documentation is the comment before the declaration and the trailing one."""
    out, pending, code = [], [], ""
    for m in TOKEN.finditer(body):
        kind, text = m.lastgroup, m.group()
        if kind == "trailing":
            target = out[-1] if not code.strip() and out else None
            if target is not None:
                target[1].append(clean_comment(text))
            else:
                pending.append(clean_comment(text))
        elif kind in ("line", "block"):
            pending.append(clean_comment(text))
        elif kind == "separator":
            out.append((" ".join(code.split()), pending))
            pending, code = [], ""
        elif kind == "code":
            code += text
    if code.strip():
        out.append((" ".join(code.split()), pending))
    return [(c, " ".join(d)) for c, d in out if c]


def parse(headers=HEADERS):
    """({enum: [Value]}, {struct: [Field]}, [function]) of public headers (names in
    include/opencv2/rcme/), in declaration order: every enum, the CV_EXPORTS_W_SIMPLE structs'
    CV_PROP_RW fields and the CV_EXPORTS_W functions."""
    enums, structs, functions = {}, {}, []
    for name in headers:
        with open(os.path.join(HEADER_DIR, name)) as f:
            text = f.read()
        for m in re.finditer(r"^enum\s+(\w+)\s*(?:#ifndef[^\n]*\n[^#]*#endif\s*)?\{(.*?)\};",
                             text, re.S | re.M):
            values, next_value = [], 0
            for code, doc in declarations(m.group(2)):
                parts = re.fullmatch(r"(\w+)(?:\s*=\s*(-?\d+))?", code)
                if not parts:
                    raise SystemExit("%s: cannot read the enum value '%s'" % (name, code))
                if parts.group(2) is not None:
                    next_value = int(parts.group(2))
                values.append(Value(parts.group(1), next_value, doc))
                next_value += 1
            enums[m.group(1)] = values
        for m in re.finditer(r"^struct\s+CV_EXPORTS_W_SIMPLE\s+(\w+)\s*\{(.*?)\n\};", text,
                             re.S | re.M):
            fields = []
            for code, doc in declarations(m.group(2)):
                parts = re.fullmatch(r"CV_PROP_RW\s+([\w:]+)\s+(\w+)", code)
                if parts:
                    fields.append(Field(parts.group(1), parts.group(2), doc))
            structs[m.group(1)] = fields
        text = re.sub(r"/\*.*?\*/|//[^\n]*", "", text, flags=re.S)
        functions += re.findall(r"CV_EXPORTS_W\s+[\w:]+\s+(\w+)\s*\(", text)
    return enums, structs, functions


def prefix_of(values):
    """The common prefix of an enum's value names up to an underscore (METHOD_ of METHOD_*)."""
    prefix = os.path.commonprefix([v.name for v in values])
    return prefix[:prefix.rfind("_") + 1] if "_" in prefix else ""


def command_line_name(value, prefix):
    """METHOD_COV_RANSAC -> "cov-ransac": prefix dropped, lower case, underscores to dashes."""
    return value.name[len(prefix):].lower().replace("_", "-")


def macro_name(enum):
    """SamplerKind -> RCME_SAMPLER_KIND_VALUES."""
    return "RCME_%s_VALUES" % re.sub(r"(?<!^)(?=[A-Z])", "_", enum).upper()


def header_comment(comment_prefix):
    sources = " and ".join("include/opencv2/rcme/" + h for h in HEADERS)
    return ("%s Generated by modules/rcme/misc/generate_tables.py from the public headers\n"
            "%s %s.\n"
            "%s Do not edit: change the headers and run the script again.\n"
            % (comment_prefix, comment_prefix, sources, comment_prefix))


def macro_lines(lines):
    """Lines of a multi-line macro, the backslashes aligned."""
    width = max(len(line) for line in lines[:-1]) + 1
    return [line.ljust(width) + "\\" for line in lines[:-1]] + [lines[-1]]


def enum_tables(enums):
    out = [header_comment("//"),
           "// X(value, name) for each value of each public enum, in declaration order; name is "
           "the\n// value's command-line spelling: prefix dropped, lower case, dashes.\n"
           "// RCME_PUBLIC_ENUMS(X) calls X(enum, values macro) for each enum.\n"]
    for enum, values in enums.items():
        prefix = prefix_of(values)
        lines = ["#define %s(X)" % macro_name(enum)]
        lines += ['    X(%s, "%s")' % (v.name, command_line_name(v, prefix)) for v in values]
        out.append("\n" + "\n".join(macro_lines(lines)) + "\n")
    lines = ["#define RCME_PUBLIC_ENUMS(X)"]
    lines += ["    X(%s, %s)" % (enum, macro_name(enum)) for enum in enums]
    out.append("\n" + "\n".join(macro_lines(lines)) + "\n")
    return "".join(out)


def python_doc(doc):
    """A header comment as a Python docstring: doxygen markup dropped."""
    doc = re.sub(r"\s*@cite\s+\w+", "", doc)
    doc = re.sub(r"#(\w)", r"\1", doc)
    doc = re.sub(r"@p\s+", "", doc)
    return doc.replace("::", ".")


def string_literal(text, indent):
    """A C++ string literal of `text`, split into adjacent literals that fit the columns."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    width = COLUMNS - len(indent) - 3
    pieces = textwrap.wrap(escaped, width, drop_whitespace=False, break_long_words=False,
                           break_on_hyphens=False) or [""]
    return ("\n" + indent).join('"%s"' % p for p in pieces)


def enum_constant_tables(enums):
    out = ["//! Every value of each public enum, as (constant name, value).\n"]
    for enum, values in enums.items():
        out.append("const std::vector<EnumConstant> k%sConstants = {\n" % enum)
        out += ['    {"%s", %s},\n' % (v.name, v.name) for v in values]
        out.append("};\n")
    out.append("//! The tables above, for the module's constants.\n"
               "const std::vector<const std::vector<EnumConstant>*> kEnumConstants = {\n")
    out += ["    &k%sConstants,\n" % enum for enum in enums]
    out.append("};\n")
    return "".join(out)


def field_chains(enums, structs):
    out = []
    for struct in STRUCTS:
        out.append("\n//! The CV_PROP_RW fields of %s, in declaration order.\n"
                   "void addFields(Fields<%s>& fields)\n{\n    fields" % (struct, struct))
        for f in structs[struct]:
            if f.type in enums:
                call, extra = "enumInt", ", k%sConstants" % f.type
            elif f.type in ("Mat", "cv::Mat"):
                call, extra = "mat", ""
            else:
                call, extra = "plain", ""
            indent = " " * 12
            out.append('\n        .%s("%s", &%s::%s%s,\n%s%s)'
                       % (call, f.name, struct, f.name, extra, indent,
                          string_literal(python_doc(f.doc), indent)))
        out.append(";\n}\n")
    return "".join(out)


def bindings(enums, structs):
    return (header_comment("//") +
            "// Included by rcme_python.cpp after Fields and EnumConstant.\n\n" +
            enum_constant_tables(enums) + field_chains(enums, structs))


def outputs():
    enums, structs, _ = parse()
    missing = [s for s in STRUCTS if s not in structs]
    if missing:
        raise SystemExit("the headers declare no struct %s" % ", ".join(missing))
    return {ENUM_TABLES: enum_tables(enums), BINDINGS: bindings(enums, structs)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 when a generated file is stale")
    args = ap.parse_args()
    stale = []
    for path, text in outputs().items():
        full = os.path.join(MODULE_DIR, path)
        try:
            with open(full) as f:
                current = f.read()
        except FileNotFoundError:
            current = None
        if current == text:
            continue
        stale.append(path)
        if not args.check:
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w") as f:
                f.write(text)
            print("wrote modules/rcme/%s" % path)
    if args.check and stale:
        print("stale generated files (the public headers changed since they were written): %s\n"
              "run modules/rcme/misc/generate_tables.py"
              % ", ".join("modules/rcme/" + p for p in stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
