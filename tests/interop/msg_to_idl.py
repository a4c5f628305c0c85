#!/usr/bin/env python3
"""Writes one plain IDL file from ROS 2 .msg packages, for fastddsgen -typeros2.

Usage: msg_to_idl.py --out FILE.idl [--types PKG/TYPE,...] PACKAGE_DIR [PACKAGE_DIR ...]

Each PACKAGE_DIR is a ROS 2 interface package (its name is the folder's name) whose messages are
in <dir>/msg/*.msg. The IDL follows the mapping of ROS 2's rosidl_adapter (msg -> idl), but
*without* the `dds_` module and the `_` suffix: `fastddsgen -typeros2` adds both itself (given
them already, it mangles the names twice). Every struct comes after the structs it uses;
constants go into `module <Type>_Constants`, as rosidl does. With --types, only those messages
and the ones they use are written (less generated C++ to compile).

This is the interop test's own reading of the .msg files, independent of hubrt's IDL and its
drift check (firmware/msgs), so that the two vendors' type descriptions come from different
places and a disagreement shows up as a failed match or a bad sample.
"""

import argparse
import pathlib
import re
import sys

# ROS 2 primitive types -> IDL 4 (rosidl_adapter's MSG_TYPE_TO_IDL).
PRIMITIVES = {
    "bool": "boolean", "byte": "octet", "char": "uint8",
    "float32": "float", "float64": "double",
    "int8": "int8", "uint8": "uint8", "int16": "int16", "uint16": "uint16",
    "int32": "int32", "uint32": "uint32", "int64": "int64", "uint64": "uint64",
}
# IDL keywords a field name could hit; such a name is written as an escaped identifier (_name).
IDL_KEYWORDS = {
    "abstract", "any", "alias", "attribute", "bitfield", "bitmask", "bitset", "boolean", "case",
    "char", "component", "connector", "const", "consumes", "context", "custom", "default",
    "double", "exception", "emits", "enum", "eventtype", "factory", "false", "finder", "fixed",
    "float", "getraises", "getter", "home", "import", "in", "inout", "interface", "local",
    "long", "manages", "map", "mirrorport", "module", "multiple", "native", "object", "octet",
    "oneway", "out", "primarykey", "private", "port", "porttype", "provides", "public",
    "publishes", "raises", "readonly", "setraises", "setter", "sequence", "short", "string",
    "struct", "supports", "switch", "true", "truncatable", "typedef", "typeid", "typename",
    "typeprefix", "unsigned", "union", "uses", "valuebase", "valuetype", "void", "wchar",
    "wstring", "int8", "uint8", "int16", "int32", "int64", "uint16", "uint32", "uint64",
}
NAME = re.compile(r"^[a-zA-Z][a-zA-Z0-9_]*$")
TYPE = re.compile(r"^(?P<base>[A-Za-z][A-Za-z0-9_/]*)(?:<=(?P<strbound>\d+))?"
                  r"(?P<array>\[(?P<arrbound><=)?(?P<size>\d*)\])?$")


class MsgError(Exception):
    pass


class Field:
    def __init__(self, base, string_bound, array, array_bounded, array_size, name):
        self.base, self.string_bound, self.name = base, string_bound, name
        self.array, self.array_bounded, self.array_size = array, array_bounded, array_size


class Message:
    def __init__(self, package, name):
        self.package, self.name = package, name
        self.fields, self.constants = [], []

    @property
    def full_name(self):
        return f"{self.package}/{self.name}"


def strip_comment(line):
    # A '#' inside a quoted constant value is text, not a comment.
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "#":
            return line[:i]
    return line


def parse_type(text, package, where):
    m = TYPE.match(text)
    if not m:
        raise MsgError(f"{where}: cannot read the type '{text}'")
    base = m.group("base")
    if m.group("strbound") and base not in ("string", "wstring"):
        raise MsgError(f"{where}: only strings take a bound (<=N), not '{base}'")
    if base not in PRIMITIVES and base not in ("string", "wstring"):
        if "/" not in base:
            base = f"{package}/{base}"
        elif base.count("/") != 1:
            raise MsgError(f"{where}: the type '{text}' is not <package>/<Type>")
    strbound = int(m.group("strbound")) if m.group("strbound") else None
    size = int(m.group("size")) if m.group("size") else None
    if m.group("array") and m.group("arrbound") and size is None:
        raise MsgError(f"{where}: a bounded array needs its bound: '{text}'")
    return Field(base, strbound, bool(m.group("array")), bool(m.group("arrbound")), size, None)


def parse_message(path, package):
    msg = Message(package, path.stem)
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        where = f"{path}:{number}"
        line = strip_comment(raw).strip()
        if not line:
            continue
        type_text, _, rest = line.partition(" ")
        rest = rest.strip()
        if not rest:
            raise MsgError(f"{where}: a field needs a type and a name: '{line}'")
        field = parse_type(type_text, package, where)
        if "=" in rest.split(" ")[0]:  # a constant: TYPE NAME=VALUE
            name, _, value = rest.partition("=")
            name, value = name.strip(), value.strip()
            if field.array or not NAME.match(name):
                raise MsgError(f"{where}: bad constant '{line}'")
            msg.constants.append((field, name, value))
            continue
        name = rest.split()[0]  # a third token is a default value: not on the wire
        if not NAME.match(name):
            raise MsgError(f"{where}: bad field name '{name}'")
        field.name = name
        msg.fields.append(field)
    return msg


def idl_scalar(field):
    if field.base in PRIMITIVES:
        return PRIMITIVES[field.base]
    if field.base in ("string", "wstring"):
        return f"{field.base}<{field.string_bound}>" if field.string_bound else field.base
    package, name = field.base.split("/")
    return f"{package}::msg::{name}"


def idl_member(field):
    name = f"_{field.name}" if field.name.lower() in IDL_KEYWORDS else field.name
    scalar = idl_scalar(field)
    if not field.array:
        return f"{scalar} {name};"
    if field.array_bounded:
        return f"sequence<{scalar}, {field.array_size}> {name};"
    if field.array_size is None:
        return f"sequence<{scalar}> {name};"
    return f"{scalar} {name}[{field.array_size}];"


def idl_constant(field, name, value):
    if field.base in ("string", "wstring"):
        text = value
        if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
            text = text[1:-1]
        escaped = text.replace("\\", "\\\\").replace('"', '\\"')
        return f'const {field.base} {name} = "{escaped}";'
    if field.base == "bool":
        return f"const boolean {name} = {'TRUE' if value.lower() in ('true', '1') else 'FALSE'};"
    if field.base not in PRIMITIVES:
        raise MsgError(f"constant {name}: a constant must be a primitive or a string")
    return f"const {PRIMITIVES[field.base]} {name} = {value};"


def ordered(messages, roots=None):
    """Every message (or those in `roots` and what they use) after the messages its fields use."""
    done, out, visiting = set(), [], set()

    def visit(msg):
        if msg.full_name in done:
            return
        if msg.full_name in visiting:
            raise MsgError(f"{msg.full_name} contains itself")
        visiting.add(msg.full_name)
        for field in msg.fields:
            if field.base in PRIMITIVES or field.base in ("string", "wstring"):
                continue
            if field.base not in messages:
                raise MsgError(f"{msg.full_name}.{field.name}: unknown type {field.base}")
            visit(messages[field.base])
        visiting.discard(msg.full_name)
        done.add(msg.full_name)
        out.append(msg)

    for name in sorted(roots if roots else messages):
        if name not in messages:
            raise MsgError(f"--types: no message {name}")
        visit(messages[name])
    return out


def write_idl(messages, sources, roots=None):
    lines = ["// Generated by tests/interop/msg_to_idl.py from: " + ", ".join(sources) + ". Do not edit.",
             "// Plain module names: fastddsgen -typeros2 adds ROS 2's dds_ module and _ suffix.", ""]
    for msg in ordered(messages, roots):
        lines.append(f"module {msg.package} {{ module msg {{")
        if msg.constants:
            lines.append(f"  module {msg.name}_Constants {{")
            lines += [f"    {idl_constant(*c)}" for c in msg.constants]
            lines.append("  };")
        lines.append(f"  struct {msg.name} {{")
        members = [idl_member(f) for f in msg.fields] or ["uint8 structure_needs_at_least_one_member;"]
        lines += [f"    {m}" for m in members]
        lines += ["  };", "}; };", ""]
    return "\n".join(lines)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, type=pathlib.Path)
    parser.add_argument("--types", default="", help="comma-separated PKG/TYPE: only these and what they use")
    parser.add_argument("packages", nargs="+", type=pathlib.Path)
    args = parser.parse_args(argv)
    messages = {}
    try:
        for package_dir in args.packages:
            files = sorted((package_dir / "msg").glob("*.msg"))
            if not files:
                raise MsgError(f"{package_dir}: no msg/*.msg")
            for path in files:
                msg = parse_message(path, package_dir.name)
                messages[msg.full_name] = msg
        roots = [t for t in args.types.split(",") if t]
        text = write_idl(messages, [p.name for p in args.packages], roots)
    except (MsgError, OSError, UnicodeDecodeError) as error:
        print(f"msg_to_idl: {error}", file=sys.stderr)
        return 1
    args.out.parent.mkdir(parents=True, exist_ok=True)
    # Written only when it changes, so that an unchanged .msg does not regenerate the C++.
    if not args.out.exists() or args.out.read_text(encoding="utf-8") != text:
        args.out.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
