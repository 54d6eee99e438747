#!/usr/bin/env python3
"""Writes a C++ source defining ssl::console::web_assets() (adapter/web_assets.h) from the page's files.

usage: embed.py OUT.cpp FILE...   Each FILE is served at "/<its name>"; the content type follows its suffix.
"""
import sys
from pathlib import Path

TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
         ".css": "text/css; charset=utf-8", ".svg": "image/svg+xml", ".png": "image/png"}


def main():
    out, files = Path(sys.argv[1]), [Path(f) for f in sys.argv[2:]]
    lines = ['#include "services/console/adapter/web_assets.h"', "", "namespace ssl::console {", "namespace {", ""]
    entries = []
    for index, path in enumerate(files):
        if path.suffix not in TYPES:
            raise SystemExit(f"embed.py: no content type for {path}")
        data = path.read_bytes()
        body = ",".join(str(b) for b in data)
        lines.append(f"const unsigned char kAsset{index}[] = {{{body},0}};")
        entries.append(f'{{"/{path.name}", "{TYPES[path.suffix]}", std::string_view(reinterpret_cast<const char*>(kAsset{index}), {len(data)})}}')
    lines += ["", "}  // namespace", "", "std::span<const WebAsset> web_assets() {",
              "  static const WebAsset assets[] = {" + ", ".join(entries) + "};", "  return assets;", "}", "",
              "}  // namespace ssl::console", ""]
    text = "\n".join(lines)
    if not out.exists() or out.read_text() != text:
        out.write_text(text)


if __name__ == "__main__":
    main()
