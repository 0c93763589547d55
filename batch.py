"""Kezuri CAM batch entry point.

    python batch.py <command> [options]                      (the bpy wheel from PyPI)
    blender -b [file.blend] --python batch.py -- <command> [options]

Commands (``python batch.py <command> --help`` for the options):
    engrave   gouge-texture name plate (W1)
    rotary    bento-block pockets on a rotating table, C-X-Z (W2)
    stepnc    ISO 14649 (STEP-NC) workplan to G-code (W3)
    turnmill  4.5-axis turn-mill: radial/axial classification and paths, X-Z-C (W4)
    unfold    twisted quad -> flat pattern, turret-punch NC, DXF, SVG (W5)
    elbow     segmented pipe elbow -> flat patterns, DXF, SVG (W5)
    carve     3-D surface carving of a mesh: Z-level roughing, ball finishing raster
    simulate  material removal and safety checks of any NC file we can read (W6)
    profile, pocket, drill, chamfer, vcarve   one router operation on an SVG or DXF drawing (--svg /
              --dxf; vcarve also --text)
    job       a job file (TOML): several operations on one stock, one program, one check;
              --each rows.csv runs it as a template once per row (--jobs N side by side)
    demo      every workflow on its built-in sample part, each into a sub-folder of --out
    feeds     feeds and speeds of a tool in a material for an operation (JSON out; no --out)
    tools     the tool library: list, import FILE, export FILE (JSON out; no --out)

Each command writes its output files, ``report.json``, a preview PNG and ``setup-sheet.html`` (the
job's setup sheet for the operator, one self-contained page) into --out.
Exit status: 0 on success, 2 on bad input (the message says what to fix), 3 when the export gate
refuses a program the simulation finds fault with (``--allow-findings`` writes it anyway, and
``report.json`` records the override), 4 when out of memory (or the address space is capped below
what Blender's module needs to load, 1.5 GB), 130 / 143 when stopped by SIGINT (Ctrl-C) / SIGTERM.
``job --each``: the rows that could run are written; the status is 2 when a row had bad input,
else 3 when the gate refused a row.
A run writes all its files or none: everything goes into a hidden staging folder beside --out and
is moved in only when every file is written; a failure, a refusal or a stop leaves --out as it was.
"""
from __future__ import annotations

import argparse
import contextlib
import importlib.util
import json
import os
import signal
import sys

ROOT = os.path.dirname(os.path.abspath(__file__))


def import_package():
    """Import this folder as the package ``kezuri``, as Blender does (no bpy needed)."""
    if "kezuri" not in sys.modules:
        spec = importlib.util.spec_from_file_location("kezuri", os.path.join(ROOT, "__init__.py"),
                                                      submodule_search_locations=[ROOT])
        package = importlib.util.module_from_spec(spec)
        sys.modules["kezuri"] = package
        spec.loader.exec_module(package)
    return sys.modules["kezuri"]


def load_extension():
    """Import the package and register it with Blender."""
    package = import_package()
    import bpy
    if not hasattr(bpy.types.Scene, "kezuri"):
        package.register()
    return package


def script_arguments(argv: list) -> list:
    """Arguments after ``--`` when run by Blender, else everything after the script name."""
    return argv[argv.index("--") + 1:] if "--" in argv else argv[1:]


def write_report(out_dir: str, report: dict) -> str:
    from kezuri.post import write_atomic
    return write_atomic(os.path.join(out_dir, "report.json"), json.dumps(report, indent=2, sort_keys=True) + "\n")


def commands() -> dict:
    """Every workflow's batch commands, from the shell's workflow table, and ``job`` (job files)."""
    from kezuri.operators import jobbatch, shorthand
    from kezuri.operators.workflows import commands as table_commands
    return {**table_commands(), jobbatch.COMMAND.name: jobbatch.COMMAND,
            **{command.name: command for command in shorthand.COMMANDS}}


def finished(command, args) -> dict:
    """Run one batch command into ``args.out``; its report, with the setup sheet written beside it."""
    from kezuri.operators.batchio import sheet_language, write_setup_sheet
    report = command.run(args)
    if "rows" in report:            # a template's summary: each row's folder has its own sheet
        return report
    return write_setup_sheet(args.out, report, sheet_language(args, report))


def demo(args, final=lambda value: value) -> dict:
    """Every workflow on its built-in sample, each into its own sub-folder of --out; ``final`` maps
    the staged paths to where the files will be."""
    results = {}
    for name, command in commands().items():
        runs = ([(name, command.demo)] if command.demo is not None else []) + list(command.more_demos)
        for folder, line in runs:
            language = ["--language", args.language] if args.language else []
            sub = parser().parse_args([name, *line, *language, "--out", os.path.join(args.out, folder)])
            sub.final = final
            report = final(finished(command, sub))
            write_report(sub.out, report)
            results[folder] = {"files": report["files"], "preview": report.get("preview"),
                               "setup_sheet": report.get("setup_sheet")}
            print(f"{folder}: wrote {', '.join(report['files'])}")
    return {"workflow": "demo", "files": [f for r in results.values() for f in r["files"]], "workflows": results}


def language_argument(p) -> None:
    """``--language``, the setup sheet's, on every command that writes one (those with --out)."""
    from kezuri.toolpath.pictures.setupsheet import LANGUAGES
    p.add_argument("--language", choices=LANGUAGES, help="the setup sheet's language (default en, or a job file's "
                                                         "[setup] language)")


def parser() -> argparse.ArgumentParser:
    import_package()
    commands_table = commands()
    main = argparse.ArgumentParser(prog="batch.py", description="Kezuri CAM batch runs")
    subparsers = main.add_subparsers(dest="command", required=True)
    for name, command in commands_table.items():
        p = subparsers.add_parser(name, help=command.help)
        command.arguments(p)
        p.add_argument("--out", required=True, help="output folder")
        language_argument(p)
    p = subparsers.add_parser("demo", help="every workflow on its built-in sample")
    p.add_argument("--out", required=True, help="output folder")
    language_argument(p)
    from kezuri.operators import feedsbatch
    p = subparsers.add_parser(feedsbatch.NAME, help=feedsbatch.HELP)      # prints; writes nothing (no --out)
    feedsbatch.arguments(p)
    # listed for --help only: main() hands "tools" to operators/toolbatch.py before this parser runs
    subparsers.add_parser("tools", help="the tool library: list, import FILE, export FILE (printed as JSON; "
                                        "no --out)", add_help=False)
    return main


def parse(argv: list) -> argparse.Namespace:
    """The command line, refused (exit 2) where argparse lets a malformed value through: an option
    given ``--`` as its value arrives as a list."""
    main_parser = parser()
    args = main_parser.parse_args(argv)
    sub = main_parser._subparsers._group_actions[0].choices[args.command]
    for action in sub._actions:
        value = getattr(args, action.dest, None)
        if action.nargs is None and not isinstance(action, argparse._AppendAction) and isinstance(value, list):
            sub.error(f"argument {'/'.join(action.option_strings)}: expected one value, got {value!r}")
    return args


class Stopped(BaseException):
    """SIGINT or SIGTERM arrived: the run stops where it is (not an ``Exception``, so no
    ``except Exception`` on the way swallows it)."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


STOP_STATUS = {signal.SIGINT: 130, signal.SIGTERM: 143}     # 128 + the signal's number, as shells do
# the signals that arrived during the run: a Stopped raised while Python runs a finaliser is lost
# ("unraisable"; seen on a million-move simulate), so the run checks this before it writes anything
STOP_PENDING: list = []


def stop_if_pending() -> None:
    """Raise :class:`Stopped` again when a signal arrived whose Stopped was lost on the way."""
    if STOP_PENDING:
        raise Stopped(STOP_PENDING[0])


@contextlib.contextmanager
def stoppable():
    """SIGINT and SIGTERM raise :class:`Stopped` in the main thread for the block's duration; a
    second signal while the run cleans up is ignored.  The previous handlers come back after."""
    def stop(signum, frame):
        for number in STOP_STATUS:
            signal.signal(number, signal.SIG_IGN)
        STOP_PENDING.append(signum)
        raise Stopped(signum)

    STOP_PENDING.clear()

    try:
        previous = {number: signal.signal(number, stop) for number in STOP_STATUS}
    except ValueError:          # not the main thread: signals cannot be caught here
        previous = {}
    try:
        yield
    finally:
        STOP_PENDING.clear()
        for number, handler in previous.items():
            signal.signal(number, handler)


def say(message: str) -> None:
    """``kezuri: message`` on stderr, on a line of its own (after a progress bar left open)."""
    common = sys.modules.get("kezuri.operators.common")
    if common is not None and getattr(common.Progress, "line_open", False):
        print(file=sys.stderr)
        common.Progress.line_open = False
    print(f"kezuri: {message}", file=sys.stderr)


def feeds(args) -> int:
    """``batch.py feeds``: the calculator's values as JSON on stdout; bad input exits 2."""
    from kezuri.operators import feedsbatch
    from kezuri.toolpath.ir.errors import InputError
    try:
        print(json.dumps(feedsbatch.run(args), indent=2, ensure_ascii=False))
    except InputError as error:
        say(f"{error}")
        return 2
    return 0


MEMORY_STATUS = 4
# Below about 1.3 GB of address space (ulimit -v) Blender's module dies while loading, by SIGSEGV in
# its allocator, before any message can be given (measured with the bpy 5.0 wheel: 1.15 GB loads,
# 1.2-1.25 GB crash); the samples run in 2 GB.  So a smaller cap is refused before anything loads.
MIN_ADDRESS_SPACE = 1536 << 20


def address_space_cap() -> int | None:
    """The process's address-space limit in bytes (RLIMIT_AS, ``ulimit -v``), None when unlimited."""
    try:
        import resource
    except ImportError:         # not on Windows
        return None
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    return None if soft == resource.RLIM_INFINITY else soft


def main(argv: list) -> int:
    cap = address_space_cap()
    if cap is not None and cap < MIN_ADDRESS_SPACE:
        say(f"the address space is capped at {cap >> 20} MB (ulimit -v); Blender's module crashes while "
            f"loading below about 1300 MB: give the run {MIN_ADDRESS_SPACE >> 20} MB or more")
        return MEMORY_STATUS
    if script_arguments(argv)[:1] == ["tools"]:         # the tool library: no --out, no staging
        import_package()
        from kezuri.operators.toolbatch import main as tools_main
        return tools_main(script_arguments(argv)[1:])
    try:
        args = parse(script_arguments(argv))
        if args.command == "feeds":
            return feeds(args)
        with stoppable():
            try:
                load_extension()
                from kezuri.operators.compilenotice import say_when_compiling
                say_when_compiling(say)             # one line where a first run compiles the kernels
                from kezuri.operators.common import Progress
                Progress.checkpoint = stop_if_pending       # a lost stop is taken up at the next progress
                return run(args)
            except Stopped as stopped:
                name = signal.Signals(stopped.signum).name
                say(f"stopped by {name}: nothing was written")
                return STOP_STATUS[stopped.signum]
    except MemoryError:
        limit = f" (the address space is capped at {cap >> 20} MB, ulimit -v)" if cap is not None else ""
        say(f"out of memory{limit}: nothing was written; give the run more memory, or lighter settings "
            "(a coarser stepover, sample spacing or simulation cell)")
        return MEMORY_STATUS


def run(args) -> int:
    """The command into a staging folder, then every file moved into --out, or none."""
    from kezuri.operators.common import user_errors
    from kezuri.operators.gate import REFUSED_STATUS, GateRefused
    from kezuri.post.output import Staging
    try:
        staging = Staging(args.out, "--out")
    except user_errors() as error:
        say(f"{error}")
        return 2
    args.out = staging.folder
    args.final = staging.final          # where the staged paths will be (a template's rows write reports)
    try:
        if args.command == "demo":
            report = demo(args, staging.final)
        else:
            report = staging.final(finished(commands()[args.command], args))
        write_report(staging.folder, report)
        stop_if_pending()                   # nothing is moved into --out after a stop, even a lost one
        staging.commit()
    except GateRefused as error:
        say(f"{staging.final(str(error))}")
        return REFUSED_STATUS
    except user_errors() as error:
        say(f"{staging.final(str(error))}")
        return 2
    finally:
        staging.discard()
    print(f"wrote {os.path.join(staging.out, 'report.json')}")
    return int(report.get("exit_status", 0)) if isinstance(report, dict) else 0


if __name__ == "__main__":
    status = main(sys.argv)
    if status:
        sys.exit(status)
