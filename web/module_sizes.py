#!/usr/bin/env python3
"""Which crates make the page's module as large as it is: reads a wasm file's code and data
sections and its name section (rustc writes one; wasm-bindgen --remove-name-section and
wasm-opt --strip-debug take it out, so run this on target/wasm32-unknown-unknown/wasm/
mechdraw.wasm as rustc links it) and sums the code bytes per crate (the first path
component of each function's mangled name).

    python3 web/module_sizes.py FILE.wasm [TOP]
"""
import collections, re, sys


def leb(b, i):
    """An unsigned LEB128 at b[i]: (value, next index)."""
    v = s = 0
    while True:
        x = b[i]
        i += 1
        v |= (x & 0x7F) << s
        s += 7
        if x < 0x80:
            return v, i


def sections(b):
    i = 8
    while i < len(b):
        sid = b[i]
        size, j = leb(b, i + 1)
        yield sid, b[j:j + size]
        i = j + size


def crate_of(name):
    """The crate of a Rust symbol (legacy `_ZN...E` or demangled `a::b::c` names)."""
    m = re.match(r"_ZN(\d+)", name)
    if m:
        n = int(m.group(1))
        start = m.end()
        part = name[start:start + n]
        if part.startswith("_$LT$"):
            inner = re.match(r"_\$LT\$(?:\$u5b\$)?([A-Za-z0-9_]+)", part)
            return "<" + (inner.group(1) if inner else "?") + ">"
        return part
    if "::" in name:
        return name.lstrip("<&").split("::")[0]
    return "(other) " + name[:30]


def main():
    data = open(sys.argv[1], "rb").read()
    top = int(sys.argv[2]) if len(sys.argv) > 2 else 30
    imports = 0
    bodies, names = [], {}
    data_bytes = custom = 0
    for sid, body in sections(data):
        if sid == 2:
            count, i = leb(body, 0)
            for _ in range(count):
                for _ in range(2):
                    n, i = leb(body, i)
                    i += n
                kind = body[i]
                i += 1
                if kind == 0:
                    imports += 1
                    _, i = leb(body, i)
                elif kind == 1:
                    i += 1
                    flag = body[i]
                    i += 1
                    _, i = leb(body, i)
                    if flag & 1:
                        _, i = leb(body, i)
                elif kind == 2:
                    flag = body[i]
                    i += 1
                    _, i = leb(body, i)
                    if flag & 1:
                        _, i = leb(body, i)
                else:
                    i += 2
        elif sid == 10:
            count, i = leb(body, 0)
            for _ in range(count):
                size, j = leb(body, i)
                bodies.append(size + (j - i))
                i = j + size
        elif sid == 11:
            data_bytes += len(body)
        elif sid == 0:
            n, i = leb(body, 0)
            title = body[i:i + n].decode()
            custom += len(body)
            if title == "name":
                i += n
                while i < len(body):
                    sub = body[i]
                    size, j = leb(body, i + 1)
                    if sub == 1:
                        count, k = leb(body, j)
                        for _ in range(count):
                            idx, k = leb(body, k)
                            ln, k = leb(body, k)
                            names[idx] = body[k:k + ln].decode("utf-8", "replace")
                            k += ln
                    i = j + size
    per = collections.Counter()
    for n, size in enumerate(bodies):
        per[crate_of(names.get(n + imports, "?"))] += size
    total = sum(bodies)
    print(f"{sys.argv[1]}: {len(data)} bytes; code {total}, data {data_bytes}, custom sections {custom}")
    for crate, size in per.most_common(top):
        print(f"{size:9d} {100 * size / total:5.1f} %  {crate}")


if __name__ == "__main__":
    main()
