#!/usr/bin/env python3
"""Machine-readable description of gyro's C ABI, generated from capi/gyro.h.

Two steps, both run by the build (capi/api/CMakeLists.txt):

  describe.py probe --header gyro.h --out gyro_api_probe.c
      Parses the header and writes a C99 program that includes it and prints, as measured
      by the C compiler, the ABI version, every enumerator's value, and every struct's
      sizeof, alignment and the offset and size of each field (union members included).

  describe.py json --header gyro.h --probe probe.txt --out gyro_api.json
      Parses the header again and merges the probe's measurements into the JSON that
      bindings are generated from (the schema is in capi/api/README.md).

The parser knows the header's regular style and nothing more: it fails loudly (naming the
line) on a declaration it does not understand, so a new construct in gyro.h is noticed
here instead of being dropped from the description.
"""
import argparse
import json
import re
import sys

SCALAR_TYPES = {"void", "char", "float", "double", "int8_t", "uint8_t", "int16_t", "uint16_t",
                "int32_t", "uint32_t", "int64_t", "uint64_t", "size_t"}


class ParseError(Exception):
    pass


# ---------------------------------------------------------------- tokens

class Tok:
    __slots__ = ("kind", "text", "line")

    def __init__(self, kind, text, line):
        self.kind = kind  # 'id', 'num', 'p' (punctuation), 'doc' (/** */), 'tdoc' (/**< */)
        self.text = text
        self.line = line

    def __repr__(self):
        return f"{self.kind}:{self.text!r}@{self.line}"


def clean_doc(raw):
    """The text of a /** ... */ or /**< ... */ comment, one line per source line, dedented."""
    body = raw[3:-2]
    if body.startswith("<"):
        body = body[1:]
    lines = []
    for line in body.split("\n"):
        line = line.strip()
        if line.startswith("*"):
            line = line[1:].strip()
        lines.append(line)
    while lines and not lines[0]:
        lines.pop(0)
    while lines and not lines[-1]:
        lines.pop()
    return "\n".join(lines)


def preprocess(text):
    """Drops the preprocessor lines and the blocks of GYRO_API's definition and the C++
    guard; returns (text with those lines blanked, {macro: (value text, line)} for the
    #defines left at file level)."""
    out = []
    defines = {}
    stack = []  # True for a conditional block whose content is dropped
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        s = line.strip()
        lineno = i + 1
        full = s
        while full.endswith("\\") and i + 1 < len(lines):  # continuation lines
            i += 1
            full = full[:-1] + " " + lines[i].strip()
            out.append("")
        if full.startswith("#"):
            directive = full[1:].strip()
            word = directive.split(None, 1)[0] if directive else ""
            rest = directive[len(word):].strip()
            if word in ("if", "ifdef", "ifndef"):
                drop = ("__cplusplus" in rest or "_WIN32" in rest)
                stack.append(drop or (stack[-1] if stack else False))
            elif word in ("elif", "else"):
                if not stack:
                    raise ParseError(f"line {lineno}: #{word} without #if")
            elif word == "endif":
                if not stack:
                    raise ParseError(f"line {lineno}: #endif without #if")
                stack.pop()
            elif word == "define" and not (stack and stack[-1]):
                m = re.match(r"(\w+)\s*(.*)$", rest)
                if m.group(1) not in ("GYRO_H", "GYRO_API"):
                    defines[m.group(1)] = (m.group(2), lineno)
            elif word in ("include", "define", "undef", "pragma", "error"):
                pass
            else:
                raise ParseError(f"line {lineno}: unknown directive #{word}")
            out.append("")
        elif stack and stack[-1]:
            out.append("")
        else:
            out.append(line)
        i += 1
    return "\n".join(out), defines


TOKEN_RE = re.compile(r"""
    (?P<ws>\s+)
  | (?P<doc>/\*\*(?!/).*?\*/)
  | (?P<comment>/\*.*?\*/|//[^\n]*)
  | (?P<id>[A-Za-z_]\w*)
  | (?P<num>\d[\w.]*)
  | (?P<p><<|>>|[{}()\[\];,*=<>\-+|&~])
""", re.S | re.X)


def tokenize(text):
    toks = []
    pos = 0
    line = 1
    while pos < len(text):
        m = TOKEN_RE.match(text, pos)
        if not m:
            raise ParseError(f"line {line}: unexpected character {text[pos]!r}")
        kind = m.lastgroup
        s = m.group(kind)
        if kind == "doc":
            toks.append(Tok("tdoc" if s.startswith("/**<") else "doc", clean_doc(s), line))
        elif kind in ("id", "num", "p"):
            toks.append(Tok(kind, s, line))
        line += s.count("\n")
        pos = m.end()
    return toks


# ---------------------------------------------------------------- parser

class Parser:
    def __init__(self, toks):
        self.toks = toks
        self.i = 0

    def peek(self, k=0):
        j = self.i + k
        return self.toks[j] if j < len(self.toks) else Tok("eof", "", self.toks[-1].line if self.toks else 0)

    def next(self):
        t = self.peek()
        self.i += 1
        return t

    def expect(self, text):
        t = self.next()
        if t.text != text:
            raise ParseError(f"line {t.line}: expected {text!r}, found {t.text!r}")
        return t

    def ident(self):
        t = self.next()
        if t.kind != "id":
            raise ParseError(f"line {t.line}: expected a name, found {t.text!r}")
        return t.text

    def skip_docs(self):
        """Consumes doc comments; returns (last leading doc, [trailing docs])."""
        lead, trail = None, []
        while self.peek().kind in ("doc", "tdoc"):
            t = self.next()
            if t.kind == "doc":
                lead = t.text
            else:
                trail.append(t.text)
        return lead, trail

    # A type: [const] name {*} ; 'const' after the name is not used by the header.
    def base_type(self):
        const = False
        if self.peek().text == "const":
            self.next()
            const = True
        t = self.next()
        if t.kind != "id" or t.text in ("struct", "union", "enum"):
            raise ParseError(f"line {t.line}: expected a type name, found {t.text!r}")
        return ("const " if const else "") + t.text

    def declarator(self, base):
        """'*'* name ('[' N ']')*  ->  (name, type, dims)."""
        stars = ""
        while self.peek().text == "*":
            self.next()
            stars += "*"
        name = self.ident()
        dims = []
        while self.peek().text == "[":
            self.next()
            n = self.next()
            if n.kind != "num":
                raise ParseError(f"line {n.line}: array size must be a number, found {n.text!r}")
            dims.append(int(n.text.rstrip("uUlL")))
            self.expect("]")
        return name, base + stars, dims

    def members(self, owner):
        """Struct or union body after '{' up to and including '}'."""
        fields = []
        pending = None
        last = []  # the fields of the previous declaration, for trailing docs
        while True:
            lead, trail = self.skip_docs()
            for d in trail:
                for f in last:
                    f["doc"] = (f.get("doc", "") + "\n" + d).strip()
            if lead is not None:
                pending = lead
            t = self.peek()
            if t.text == "}":
                self.next()
                return fields
            if t.text == "union":
                self.next()
                self.expect("{")
                inner = self.members(owner + ".union")
                name = self.ident()
                self.expect(";")
                f = {"name": name, "type": "union", "members": inner}
                if pending:
                    f["doc"] = pending
                pending = None
                fields.append(f)
                last = [f]
                continue
            if t.text in ("struct", "enum"):
                raise ParseError(f"line {t.line}: nested {t.text} in {owner} is not supported")
            base = self.base_type()
            decl = []
            while True:
                name, typ, dims = self.declarator(base)
                f = {"name": name, "type": typ, "dims": dims}
                if pending:
                    f["doc"] = pending
                decl.append(f)
                if self.peek().text == ",":
                    self.next()
                    continue
                self.expect(";")
                break
            pending = None
            fields.extend(decl)
            last = decl

    def enumerators(self, enum_name):
        """Enum body after '{' up to and including '};'."""
        consts = []
        pending = None
        while True:
            lead, trail = self.skip_docs()
            if trail and consts:
                consts[-1]["doc"] = "\n".join(filter(None, [consts[-1].get("doc"), *trail]))
            if lead is not None:
                pending = lead
            t = self.peek()
            if t.text == "}":
                self.next()
                self.expect(";")
                return consts
            name = self.ident()
            c = {"name": name, "enum": enum_name, "expr": None}
            if pending:
                c["doc"] = pending
            pending = None
            consts.append(c)
            if self.peek().text == "=":
                self.next()
                expr = []
                while self.peek().text not in (",", "}"):
                    tok = self.next()
                    if tok.kind in ("doc", "tdoc"):
                        if tok.kind == "tdoc":
                            c["doc"] = "\n".join(filter(None, [c.get("doc"), tok.text]))
                        else:
                            pending = tok.text
                        continue
                    if tok.kind == "eof":
                        raise ParseError(f"line {t.line}: unterminated enum")
                    expr.append(tok.text)
                c["expr"] = re.sub(r"^- ", "-", " ".join(expr))
            if self.peek().text == ",":
                self.next()

    def params(self, fname):
        self.expect("(")
        out = []
        if self.peek().text == "void" and self.peek(1).text == ")":
            self.next()
            self.next()
            return out
        while True:
            base = self.base_type()
            name, typ, dims = self.declarator(base)
            p = {"name": name, "type": typ}
            if dims:  # an array parameter is a pointer; its declared length is kept
                if len(dims) != 1:
                    raise ParseError(f"{fname}: multi-dimensional array parameter {name}")
                p["type"] = typ + "*"
                p["array"] = dims[0]
            out.append(p)
            t = self.next()
            if t.text == ")":
                return out
            if t.text != ",":
                raise ParseError(f"line {t.line}: expected ',' or ')' in {fname}, found {t.text!r}")


def parse_header(text):
    body, defines = preprocess(text)
    p = Parser(tokenize(body))
    api = {"constants": [], "typedefs": [], "opaque": [], "structs": [], "functions": [],
           "defines": defines}
    pending = None
    prev_typedef = None  # name of a scalar typedef that the next enum block belongs to
    while p.peek().kind != "eof":
        lead, _trail = p.skip_docs()
        if lead is not None:
            pending = lead
        t = p.peek()
        if t.kind == "eof":
            break
        line = t.line
        if t.text == "typedef":
            p.next()
            if p.peek().text == "struct":
                p.next()
                tag = p.ident()
                if p.peek().text == "{":
                    p.next()
                    fields = p.members(tag)
                    name = p.ident()
                    p.expect(";")
                    if name != tag:
                        raise ParseError(f"line {line}: struct tag {tag} differs from its typedef {name}")
                    s = {"name": name, "fields": fields, "line": line}
                    if pending:
                        s["doc"] = pending
                    api["structs"].append(s)
                else:
                    name = p.ident()
                    p.expect(";")
                    if name != tag:
                        raise ParseError(f"line {line}: opaque struct tag {tag} differs from its typedef {name}")
                    api["opaque"].append(name)
                prev_typedef = None
            else:
                base = p.base_type()
                if base not in SCALAR_TYPES:
                    raise ParseError(f"line {line}: typedef of {base} is not supported")
                name = p.ident()
                p.expect(";")
                td = {"name": name, "type": base}
                if pending:
                    td["doc"] = pending
                api["typedefs"].append(td)
                prev_typedef = name
        elif t.text == "enum":
            p.next()
            if p.peek().text != "{":
                raise ParseError(f"line {line}: only anonymous enum blocks are supported")
            p.next()
            api["constants"].extend(p.enumerators(prev_typedef))
            prev_typedef = None
        elif t.text == "GYRO_API":
            p.next()
            ret = p.base_type()
            while p.peek().text == "*":
                p.next()
                ret += "*"
            name = p.ident()
            params = p.params(name)
            p.expect(";")
            f = {"name": name, "return": ret, "params": params, "doc": pending or ""}
            api["functions"].append(f)
            prev_typedef = None
        else:
            raise ParseError(f"line {line}: unsupported declaration starting with {t.text!r}")
        pending = None
    return api


# ---------------------------------------------------------------- the probe program

def probe_source(api, header_name):
    out = []
    w = out.append
    w("/* Generated by capi/api/describe.py from gyro.h: do not edit. Prints what the C")
    w(" * compiler makes of the header: values of the constants, sizes, alignments, offsets. */")
    w("#include <stddef.h>")
    w("#include <stdio.h>")
    w(f'#include "{header_name}"')
    w("")
    # alignment of a type T = offsetof(struct { char c; T x; }, x) (C99 has no _Alignof)
    types = []
    for s in api["structs"]:
        types.append(s["name"])
        for f in s["fields"]:
            for m in [f] + f.get("members", []):
                if m["type"] != "union" and m["type"] not in types:
                    types.append(m["type"])
    align_id = {}
    for k, typ in enumerate(types):
        align_id[typ] = k
        w(f"struct gyro_probe_align_{k} {{ char c; {typ} x; }};")
    w("")
    w("int main(int argc, char** argv) {")
    w("  FILE* out = stdout;")
    w("  if (argc > 1) {")
    w('    out = fopen(argv[1], "w");')
    w("    if (!out) {")
    w('      perror(argv[1]);')
    w("      return 1;")
    w("    }")
    w("  }")
    if "GYRO_ABI_VERSION" not in api["defines"]:
        raise ParseError("no #define GYRO_ABI_VERSION")
    w('  fprintf(out, "abi_version %lu\\n", (unsigned long)(GYRO_ABI_VERSION));')
    for c in api["constants"]:
        w(f'  fprintf(out, "constant {c["name"]} %lld\\n", (long long)({c["name"]}));')
    for k, typ in enumerate(types):
        w(f'  fprintf(out, "type {k} %zu %zu\\n", sizeof({typ}), offsetof(struct gyro_probe_align_{k}, x));')
    for s in api["structs"]:
        n = s["name"]
        w(f'  fprintf(out, "struct {n} %zu %zu\\n", sizeof({n}), offsetof(struct gyro_probe_align_{align_id[n]}, x));')
        for f in s["fields"]:
            paths = [f["name"]] + [f["name"] + "." + m["name"] for m in f.get("members", [])]
            for path in paths:
                w(f'  fprintf(out, "field {n} {path} %zu %zu\\n", offsetof({n}, {path}), '
                  f'sizeof((({n}*)0)->{path}));')
    w("  if (out != stdout && fclose(out) != 0) {")
    w('    perror(argv[1]);')
    w("    return 1;")
    w("  }")
    w("  return 0;")
    w("}")
    return "\n".join(out) + "\n", types


# ---------------------------------------------------------------- merging into the JSON

def read_probe(path):
    d = {"constant": {}, "type": {}, "struct": {}, "field": {}}
    with open(path) as fh:
        for line in fh:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "abi_version":
                d["abi_version"] = int(parts[1])
            elif parts[0] == "constant":
                d["constant"][parts[1]] = int(parts[2])
            elif parts[0] == "type":
                d["type"][int(parts[1])] = (int(parts[2]), int(parts[3]))
            elif parts[0] == "struct":
                d["struct"][parts[1]] = (int(parts[2]), int(parts[3]))
            elif parts[0] == "field":
                d["field"][(parts[1], parts[2])] = (int(parts[3]), int(parts[4]))
            else:
                raise ParseError(f"{path}: unknown probe line {line!r}")
    return d


def count_of(dims):
    n = 1
    for x in dims:
        n *= x
    return n


def build_json(api, probe, types):
    type_index = {t: k for k, t in enumerate(types)}
    v = probe["abi_version"]
    result = {
        "abi_version": {"major": v >> 16, "minor": v & 0xFFFF},
        "constants": [],
        "typedefs": [{"name": t["name"], "type": t["type"], **({"doc": t["doc"]} if "doc" in t else {})}
                      for t in api["typedefs"]],
        "opaque": list(api["opaque"]),
        "structs": [],
        "functions": [],
    }
    for c in api["constants"]:
        e = {"name": c["name"], "value": probe["constant"][c["name"]], "enum": c["enum"]}
        if c.get("expr") is not None:
            e["expr"] = c["expr"]
        if c.get("doc"):
            e["doc"] = c["doc"]
        result["constants"].append(e)

    def field_entry(sname, f, path):
        off, size = probe["field"][(sname, path)]
        e = {"name": f["name"], "type": f["type"], "offset": off, "size": size,
             "count": count_of(f.get("dims", []))}
        if len(f.get("dims", [])) > 1:
            e["dims"] = f["dims"]
        if f["type"] != "union":
            tsize, talign = probe["type"][type_index[f["type"]]]
            e["align"] = talign
            if tsize * e["count"] != size:
                raise ParseError(f"{sname}.{path}: parsed as {e['count']} x {f['type']} ({tsize} bytes) "
                                 f"but the compiler says {size} bytes")
        if f.get("doc"):
            e["doc"] = f["doc"]
        return e

    for s in api["structs"]:
        n = s["name"]
        size, align = probe["struct"][n]
        fields = []
        for f in s["fields"]:
            e = field_entry(n, f, f["name"])
            if f["type"] == "union":
                e["members"] = [field_entry(n, m, f["name"] + "." + m["name"]) for m in f["members"]]
                e["align"] = max(m["align"] for m in e["members"])
            fields.append(e)
        # padding the compiler inserted (gyro's convention: explicit padding fields)
        padding = []
        at = 0
        for e in fields:
            if e["offset"] > at:
                padding.append({"offset": at, "size": e["offset"] - at})
            if e["offset"] < at:
                raise ParseError(f"{n}.{e['name']}: overlaps the previous field")
            at = e["offset"] + e["size"]
        if size > at:
            padding.append({"offset": at, "size": size - at})
        entry = {"name": n, "size": size, "align": align, "fields": fields}
        if padding:
            entry["padding"] = padding
        if s.get("doc"):
            entry["doc"] = s["doc"]
        result["structs"].append(entry)

    for f in api["functions"]:
        result["functions"].append({"name": f["name"], "return": f["return"], "params": f["params"],
                                    "doc": f["doc"]})
    check_names(result)
    return result


def check_names(result):
    known = set(SCALAR_TYPES) | {t["name"] for t in result["typedefs"]} | set(result["opaque"]) | \
        {s["name"] for s in result["structs"]}

    def check(typ, where):
        base = typ.replace("const ", "").rstrip("*").strip()
        if typ != "union" and base not in known:
            raise ParseError(f"{where}: unknown type {base!r}")

    for s in result["structs"]:
        for f in s["fields"]:
            for m in [f] + f.get("members", []):
                check(m["type"], f"{s['name']}.{m['name']}")
    for f in result["functions"]:
        check(f["return"], f"{f['name']} (return)")
        for prm in f["params"]:
            check(prm["type"], f"{f['name']}({prm['name']})")
    seen = set()
    for kind in ("constants", "typedefs", "structs", "functions"):
        for e in result[kind]:
            if e["name"] in seen:
                raise ParseError(f"{e['name']} declared twice")
            seen.add(e["name"])


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mode", choices=["probe", "json", "parse"])
    ap.add_argument("--header", required=True)
    ap.add_argument("--probe", help="the probe program's output (json mode)")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    try:
        with open(a.header) as fh:
            api = parse_header(fh.read())
        src, types = probe_source(api, "gyro.h")
        if a.mode == "probe":
            text = src
        elif a.mode == "parse":  # debugging: the parse alone, no measurements
            text = json.dumps(api, indent=1) + "\n"
        else:
            if not a.probe:
                raise ParseError("json mode needs --probe")
            text = json.dumps(build_json(api, read_probe(a.probe), types), indent=1) + "\n"
    except (ParseError, KeyError) as e:
        print(f"describe.py: {a.header}: {e}", file=sys.stderr)
        return 1
    with open(a.out, "w") as fh:
        fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
