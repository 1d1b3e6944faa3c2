#!/usr/bin/env python3
"""Where the bytes of a wasm module go: raw and gzipped size per part of ksmcmc.

A development tool, not part of the build (BENCHMARKS.md, "The WebAssembly package", has the
tables it made). It needs a module that still has its function names and twiggy's dominator
tree of it (`cargo install twiggy`), e.g. for the mapper module:

    CARGO_PROFILE_WASM_RELEASE_STRIP=none CARGO_TARGET_DIR=target/names cargo build --lib \
      --profile wasm-release --target wasm32-unknown-unknown --no-default-features --features wasm-mapper
    wasm-opt -O3 -g --strip-dwarf --enable-simd --enable-bulk-memory --enable-nontrapping-float-to-int \
      --enable-sign-ext --enable-mutable-globals --enable-reference-types --enable-multivalue \
      target/names/wasm32-unknown-unknown/wasm-release/ksmcmc.wasm -o names.wasm
    wasm-bindgen --keep-debug --target web --out-dir target/names/bg names.wasm
    twiggy dominators -f json target/names/bg/names_bg.wasm > dom.json
    python3 scripts/wasm-sizes.py target/names/bg/names_bg.wasm dom.json

Each function goes to a part by its own name (`ksmcmc::mln::learn::...` is MLN learning); a
generic one (`core::slice::sort`, `hashbrown`, serde's `PhantomData` seeds...) goes to the part
of the nearest function that dominates it in the call graph (twiggy's dominator tree), or to
"shared generic code" when several parts call it. The gzipped figure of a part is its function
bodies concatenated and gzipped alone: a guide to what leaving it out saves, not an exact share.
"""

import gzip
import json
import re
import sys

# (part, pattern on the demangled name); the first match wins.
PARTS = [
    ("table-top", r"ksmcmc::(tabletop|render::tabletop|wasm::tabletop)"),
    ("synthetic maps", r"ksmcmc::(floorplan::synth|wasm::synth|wasm::Synthetic)"),
    ("MLN learning", r"ksmcmc::mln::(learn|lbfgs)|learn_from_worlds|wasm::knowledge::learn"),
    ("exports: GeoJSON/SVG/GLB/3D", r"ksmcmc::(floorplan::(geojson|georef)|render::(svg|glb|model3d)|wasm::model3d)"),
    ("routes", r"ksmcmc::(floorplan::route|wasm::route)"),
    ("report, graph/rooms JSON", r"ksmcmc::floorplan::(report|export)"),
    ("room layer", r"ksmcmc::floorplan::(rooms|room_layer|room_types|topology|outline)"),
    ("MLN inference + knowledge", r"ksmcmc::(mln|floorplan::knowledge|wasm::knowledge)"),
    ("edits", r"ksmcmc::floorplan::edits"),
    ("floor-plan chain + vision", r"ksmcmc::(floorplan|vision|geometry)"),
    ("map readers (grid)", r"ksmcmc::grid"),
    ("render (tiny-skia, font)", r"ksmcmc::render|tiny_skia"),
    ("png/deflate", r"\b(png|fdeflate|miniz_oxide|crc32fast|adler2?|simd_adler32)::"),
    ("serde_json", r"serde_json::|serde_wasm_bindgen"),
    ("std fmt/panics", r"core::(fmt|panicking|num::flt2dec|str::)|alloc::fmt|std::panicking|console_error_panic_hook|::fmt::|core::result::unwrap_failed|core::option::expect_failed"),
    ("wasm-bindgen glue", r"wasm_bindgen|js_sys|web_sys|ksmcmc::wasm|^export |__wbg|__wbindgen"),
    ("allocator", r"dlmalloc|__rust_(alloc|dealloc|realloc)"),
    ("libm/compiler-builtins", r"libm::|compiler_builtins"),
]
COMPILED = [(p, re.compile(r)) for p, r in PARTS]


def part_of(name):
    for part, pattern in COMPILED:
        if pattern.search(name):
            return part
    return None


def leb(b, i):
    result = shift = 0
    while True:
        byte = b[i]
        i += 1
        result |= (byte & 0x7F) << shift
        shift += 7
        if byte < 0x80:
            return result, i


def name_map(b, i, end):
    names = {}
    count, i = leb(b, i)
    for _ in range(count):
        idx, i = leb(b, i)
        n, i = leb(b, i)
        names[idx] = b[i : i + n].decode("utf-8", "replace")
        i += n
    return names


def parse(path):
    """Function bodies and data segments, each as (name, bytes)."""
    b = open(path, "rb").read()
    i, imported, bodies, datas, fnames, dnames = 8, 0, [], [], {}, {}
    while i < len(b):
        sid = b[i]
        size, i = leb(b, i + 1)
        start, end = i, i + size
        if sid == 2:  # imports: count the imported functions
            count, j = leb(b, i)
            for _ in range(count):
                for _ in range(2):
                    n, j = leb(b, j)
                    j += n
                kind = b[j]
                j += 1
                if kind == 0:
                    _, j = leb(b, j)
                    imported += 1
                elif kind == 1:
                    j += 1
                    flags, j = leb(b, j + 0)
                    _, j = leb(b, j)
                    if flags & 1:
                        _, j = leb(b, j)
                elif kind == 2:
                    flags, j = leb(b, j)
                    _, j = leb(b, j)
                    if flags & 1:
                        _, j = leb(b, j)
                elif kind == 3:
                    j += 2
        elif sid == 10:
            count, j = leb(b, i)
            for _ in range(count):
                n, j = leb(b, j)
                bodies.append(b[j : j + n])
                j += n
        elif sid == 11:
            count, j = leb(b, i)
            for _ in range(count):
                flags, j = leb(b, j)
                if flags == 2:
                    _, j = leb(b, j)
                if flags != 1:  # the offset: i32.const N or global.get G, then end
                    _, j = leb(b, j + 1)
                    j += 1
                n, j = leb(b, j)
                datas.append(b[j : j + n])
                j += n
        elif sid == 0:
            n, j = leb(b, i)
            if b[j : j + n] == b"name":
                j += n
                while j < end:
                    sub = b[j]
                    size2, j = leb(b, j + 1)
                    if sub == 1:
                        fnames = name_map(b, j, j + size2)
                    elif sub == 9:
                        dnames = name_map(b, j, j + size2)
                    j += size2
        i = end
    funcs = [(fnames.get(imported + k, f"func[{imported + k}]"), body) for k, body in enumerate(bodies)]
    data = [(f'data segment "{dnames.get(k, k)}"', d) for k, d in enumerate(datas)]
    return funcs, data


def dominated_parts(tree):
    """name -> part, generic names taking the part of their nearest named dominator."""
    out = {}

    def walk(node, inherited):
        own = part_of(node["name"])
        part = own or inherited
        out[node["name"]] = part
        for child in node.get("children", []):
            walk(child, part)

    for top in tree["items"][0].get("children", []):
        walk(top, None)
    return out


def main(wasm, dom):
    funcs, data = parse(wasm)
    parts = dominated_parts(json.load(open(dom)))
    by_part = {}
    for name, body in funcs:
        part = parts.get(name) or part_of(name) or "shared generic code (std, hashbrown, serde)"
        by_part.setdefault(part, []).append(body)
    for name, d in data:
        by_part.setdefault("data (.rodata: tables, strings)", []).append(d)
    total_raw = sum(len(x) for v in by_part.values() for x in v)
    rows = sorted(((sum(map(len, v)), len(gzip.compress(b"".join(v), 9)), p, len(v)) for p, v in by_part.items()), reverse=True)
    print(f"| part | items | raw kB | gzipped alone kB |")
    print(f"|---|---:|---:|---:|")
    for raw, gz, p, n in rows:
        print(f"| {p} | {n} | {raw / 1000:.1f} | {gz / 1000:.1f} |")
    print(f"| **code + data** | | **{total_raw / 1000:.1f}** | |")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: wasm-sizes.py MODULE_WITH_NAMES.wasm TWIGGY_DOMINATORS.json (see the docstring)")
    main(*sys.argv[1:3])
