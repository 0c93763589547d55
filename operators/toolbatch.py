"""``batch.py tools``: the tool library from the command line, every answer printed as JSON.

    batch.py tools list
    batch.py tools import FILE [--format kezuri|tbl|fusion|freecad] [--units mm|inch] [--replace]
    batch.py tools export FILE [--format kezuri|tbl|fusion|freecad] [--units mm|inch]

The library is the user's (:mod:`.toolstore`; ``KEZURI_TOOL_LIBRARY`` names another file).  An
import merges the file's tools in; a number the library has already, as another tool, is refused
naming both unless ``--replace``, and then nothing is imported.  The format comes from ``--format``
or the file's extension (.toml, .tbl, .json / .tools, .fctl); ``--units`` is a tool table's (LinuxCNC's
table does not say).  Exit status 0, or 2 on bad input with the message on stderr.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

from ..toolpath.tooling import formats, store
from ..toolpath.tooling.library import ToolLibraryError
from . import toolstore


def parser() -> argparse.ArgumentParser:
    main = argparse.ArgumentParser(prog="batch.py tools", description="the tool library (printed as JSON)")
    commands = main.add_subparsers(dest="action", required=True)
    commands.add_parser("list", help="every tool of the library")
    for name, text in (("import", "merge a tool file into the library"), ("export", "write the library to a file")):
        p = commands.add_parser(name, help=text)
        p.add_argument("file")
        p.add_argument("--format", choices=formats.NAMES, help="default: from the file's extension")
        p.add_argument("--units", choices=tuple(("mm", "inch")), default="mm",
                       help="a LinuxCNC tool table's units (default mm)")
        if name == "import":
            p.add_argument("--replace", action="store_true", help="tools of the file replace the library's "
                                                                  "of the same number")
    return main


def listing(library, path: str) -> dict:
    return {"library": path, "tools": [tool.as_dict() for tool in library]}


def run(args) -> dict:
    path = toolstore.library_path()
    library = store.load(path)
    if args.action == "list":
        return listing(library, path)
    target = os.path.abspath(args.file)
    if args.action == "import":
        incoming, notes = formats.read_import(args.file, args.format, args.units)
        merged, added, replaced = library.merged(incoming, args.replace, source=args.file)
        if merged != library:
            store.save(path, merged)
        return {"library": path, "imported": args.file, "added": list(added), "replaced": list(replaced),
                "unchanged": [n for n in incoming.numbers() if n not in added and n not in replaced],
                "notes": notes, "tools": len(merged)}
    if target == os.path.abspath(path) or target.startswith(os.path.abspath(path) + ".bak"):
        raise ToolLibraryError(f"{args.file} is the tool library itself (or its backup); export to another file")
    fmt = formats.format_of(args.file, args.format)
    written = [store.write_export(name, text) for name, text in formats.files_for(args.file, library, fmt, args.units)]
    return {"library": path, "exported": args.file, "format": fmt, "tools": len(library), "files": written}


def main(argv: list) -> int:
    args = parser().parse_args(argv)
    try:
        report = run(args)
    except ToolLibraryError as error:
        print(f"kezuri: {error}", file=sys.stderr)
        return 2
    print(json.dumps(report, indent=2, ensure_ascii=False))
    return 0
