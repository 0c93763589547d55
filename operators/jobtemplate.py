"""Templates for a batch of parts: ``batch.py job FILE.toml --each rows.csv [--jobs N]``.

The job file is a template: ``{{column}}`` stands for the row's value of that column.  Inside a
quoted TOML string the value is put in as text (quotes and backslashes escaped, so a name with
``"`` stays one string); outside quotes it must be a TOML number or true/false (a seed, a depth).
Each row runs the whole job into its own sub-folder of --out (``001-<first value>``), all of that
row's files or none; a row that fails is reported and the others go on; ``report.json`` at the top
sums up every row.  With ``--jobs N`` the rows run in N worker processes side by side.
"""
from __future__ import annotations

import concurrent.futures
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

from ..toolpath.engines.textfile import named, os_reason
from .jobentry import JobFileError

PLACEHOLDER = re.compile(r"\{\{\s*([^{}\s]+)\s*\}\}")
NUMBER = re.compile(r"^[+-]?(\d[\d_]*)(\.\d[\d_]*)?([eE][+-]?\d+)?$|^(true|false)$")
CONTROL = re.compile(r"[\x00-\x1f\x7f]")
SLUG_BAD = re.compile(r'[\\/:*?"<>|\x00-\x1f\s]+')
MAX_ROWS = 100_000


def read_rows(path: str) -> tuple:
    """(columns, rows as dicts) of a CSV with a header line (UTF-8, an Excel BOM allowed)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as stream:
            table = list(csv.reader(stream))
    except FileNotFoundError:
        raise JobFileError(f"--each {path}: no such file") from None
    except IsADirectoryError:
        raise JobFileError(f"--each {path}: a folder, not a CSV file") from None
    except OSError as error:
        raise JobFileError(named(f"--each {path}", os_reason(error))) from None
    except UnicodeDecodeError:
        raise JobFileError(f"--each {path}: not UTF-8 text (save the CSV as UTF-8)") from None
    except csv.Error as error:
        raise JobFileError(f"--each {path}: not a CSV file ({error})") from None
    table = [row for row in table if any(cell.strip() for cell in row)]
    if not table:
        raise JobFileError(f"--each {path}: empty; the first line names the columns")
    columns = [name.strip() for name in table[0]]
    for name in columns:
        if not name:
            raise JobFileError(f"--each {path}: line 1 has an empty column name")
        if columns.count(name) > 1:
            raise JobFileError(f"--each {path}: line 1 names the column {name!r} twice")
    if len(table) < 2:
        raise JobFileError(f"--each {path}: no rows under the header line")
    if len(table) - 1 > MAX_ROWS:
        raise JobFileError(f"--each {path}: {len(table) - 1} rows; at most {MAX_ROWS} in one run")
    rows = []
    for line, row in enumerate(table[1:], 2):
        if len(row) != len(columns):
            raise JobFileError(f"--each {path}: line {line} has {len(row)} values for {len(columns)} columns")
        rows.append(dict(zip(columns, (cell.strip() for cell in row))))
    return columns, rows


def render(template: str, row: dict, where: str) -> str:
    """The template with the row's values put in (see the module docstring)."""
    out, at = [], 0
    for match in PLACEHOLDER.finditer(template):
        column = match.group(1)
        line_start = template.rfind("\n", 0, match.start()) + 1
        quoted, comment = context(template[line_start:match.start()])
        out.append(template[at:match.start()])
        at = match.end()
        if comment:                     # a comment: left as written
            out.append(match.group(0))
            continue
        if column not in row:
            line = template.count("\n", 0, match.start()) + 1
            raise JobFileError(f"{where}: the job file's line {line} asks for {{{{{column}}}}}, a column the CSV "
                               f"does not have ({', '.join(row)})")
        value = row[column]
        if quoted:                      # inside a basic string: the value as text
            out.append(CONTROL.sub(lambda c: f"\\u{ord(c.group(0)):04x}",
                                   value.replace("\\", "\\\\").replace('"', '\\"')))
        elif NUMBER.match(value):
            out.append(value)
        else:
            raise JobFileError(f"{where}: column {column} = {value!r} is not a number, and the job file uses it "
                               "outside quotes (as a number)")
    out.append(template[at:])
    return "".join(out)


def context(before: str) -> tuple:
    """(inside a basic string, inside a comment) at the end of ``before``, a line's start."""
    quoted = escaped = False
    for char in before:
        if quoted:
            if escaped:
                escaped = False
            elif char == "\\":
                escaped = True
            elif char == '"':
                quoted = False
        elif char == '"':
            quoted = True
        elif char == "#":
            return False, True
    return quoted, False


def folder_of(index: int, row: dict, width: int) -> str:
    first = next(iter(row.values()), "")
    slug = SLUG_BAD.sub("_", first).strip("._")[:40]
    return f"{index:0{width}d}" + (f"-{slug}" if slug else "")


def batch_rows(args) -> dict:
    from . import jobfile

    try:
        with open(args.file, encoding="utf-8-sig") as stream:     # a BOM (Notepad's UTF-8) dropped
            template = stream.read()
    except FileNotFoundError:
        raise JobFileError(f"job file {args.file}: no such file") from None
    except IsADirectoryError:
        raise JobFileError(f"job file {args.file}: a folder, not a job file") from None
    except OSError as error:
        raise JobFileError(named(f"job file {args.file}", os_reason(error))) from None
    except UnicodeDecodeError:
        raise JobFileError(f"job file {args.file}: not UTF-8 text") from None
    columns, rows = read_rows(args.each)
    width = max(3, len(str(len(rows))))
    base_dir = os.path.dirname(os.path.abspath(args.file))
    work = []
    for index, row in enumerate(rows, 1):
        where = f"--each {os.path.basename(args.each)}: row {index}"
        folder = folder_of(index, row, width)
        try:
            text = render(template, row, where)
            jobfile.read(args.file, text)        # every row's job file is checked before any work
        except JobFileError as error:
            work.append((index, folder, None, str(error) if str(error).startswith("--each") else f"{where}: {error}"))
            continue
        work.append((index, folder, text, None))
    started = time.perf_counter()
    results = {}
    runnable = [item for item in work if item[2] is not None]
    if not runnable:        # a template no row can run (not TOML, say): refused, nothing written
        message = work[0][3]
        if len(work) > 1:
            message = f"{message} (and {len(work) - 1} more row(s) refused)"
        raise JobFileError(message)
    for index, folder, _, message in work:
        if message is not None:
            results[index] = {"row": index, "folder": None, "status": "bad input", "message": message}
            print_row(results[index], len(rows))        # its reason on stderr too, not only in report.json
    if args.jobs > 1 and len(runnable) > 1:
        with tempfile.TemporaryDirectory(prefix="kezuri-rows-") as rows_dir, \
                concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            futures = {pool.submit(run_child, args, rows_dir, base_dir, index, folder, text): index
                       for index, folder, text, _ in runnable}
            for future in concurrent.futures.as_completed(futures):
                results[futures[future]] = future.result()
                print_row(results[futures[future]], len(rows))
    else:
        for index, folder, text, _ in runnable:
            results[index] = run_here(args, base_dir, index, folder, text)
            print_row(results[index], len(rows))
    for result in results.values():
        if result["folder"] is not None:
            relocate(os.path.join(args.out, result["folder"], "report.json"), getattr(args, "final", None))
    summary = [results[index] for index in sorted(results)]
    failed = [r for r in summary if r["status"] != "written"]
    status = 0 if not failed else (2 if any(r["status"] == "bad input" for r in failed) else 3)
    print(f"kezuri: {len(summary) - len(failed)} of {len(summary)} rows written"
          + (f"; failed: {', '.join(str(r['row']) for r in failed)}" if failed else ""), file=sys.stderr)
    return {"workflow": "job", "template": os.path.abspath(args.file), "rows_file": os.path.abspath(args.each),
            "columns": columns, "rows": summary,
            "files": [os.path.join(args.out, f) for r in summary for f in r.get("files", ())], "written": len(summary) - len(failed), "failed": len(failed),
            "seconds": round(time.perf_counter() - started, 3), "exit_status": status}


def relocate(path: str, final) -> None:
    """A row's report with the paths it names where the run's files will end up (``final``: the
    batch run's staging map; None: they are there already)."""
    import json

    from ..post import write_atomic
    if final is None:
        return
    with open(path, encoding="utf-8") as stream:
        report = json.load(stream)
    write_atomic(path, json.dumps(final(report), indent=2, sort_keys=True) + "\n")


def print_row(result: dict, count: int) -> None:
    text = result["status"] if result["status"] == "written" else f"{result['status']}: {result['message']}"
    print(f"row {result['row']}/{count}: {text}", file=sys.stderr)


def run_here(args, base_dir, index, folder, text) -> dict:
    """One row in this process, all its files or none (its own staging inside --out)."""
    from ..post.output import Staging
    from . import jobfile
    from .batchio import sheet_language, write_setup_sheet
    from .common import user_errors
    from .gate import GateRefused

    out = os.path.join(args.out, folder)
    staging = Staging(out, "--out")
    try:
        report = jobfile.write_job(args.file, staging.folder, args.post, args.allow_findings, text=text,
                                   base_dir=base_dir)
        report = staging.final(write_setup_sheet(staging.folder, report, sheet_language(args, report)))
        write_row_report(staging.folder, report)
        staging.commit()
    except GateRefused as error:
        return {"row": index, "folder": None, "status": "refused", "message": staging.final(str(error))}
    except user_errors() as error:
        return {"row": index, "folder": None, "status": "bad input", "message": staging.final(str(error))}
    finally:
        staging.discard()
    return {"row": index, "folder": folder, "status": "written", "message": "",
            "cycle_time_s": report["cycle_time_s"], "files": [os.path.relpath(f, args.out) for f in report["files"]]}


def write_row_report(folder: str, report: dict) -> None:
    import json

    from ..post import write_atomic
    write_atomic(os.path.join(folder, "report.json"), json.dumps(report, indent=2, sort_keys=True) + "\n")


def run_child(args, rows_dir, base_dir, index, folder, text) -> dict:
    """One row in a worker process: ``batch.py job <row's file> --out <its folder>``."""
    import json

    path = os.path.join(rows_dir, f"{folder}.toml")
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(text)
    out = os.path.join(args.out, folder)
    command = [*interpreter(), "job", path, "--base-dir", base_dir, "--out", out]
    if args.post:
        command += ["--post", args.post]
    if args.allow_findings:
        command.append("--allow-findings")
    if getattr(args, "language", None):
        command += ["--language", args.language]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode == 0:
        with open(os.path.join(out, "report.json"), encoding="utf-8") as stream:
            report = json.load(stream)
        return {"row": index, "folder": folder, "status": "written", "message": "",
                "cycle_time_s": report["cycle_time_s"],
                "files": [os.path.relpath(f, args.out) for f in report["files"]]}
    shutil.rmtree(out, ignore_errors=True)
    lines = [line for line in done.stderr.splitlines() if line.startswith("kezuri: ")]
    message = lines[-1].removeprefix("kezuri: ") if lines else done.stderr.strip()[-500:]
    status = {2: "bad input", 3: "refused"}.get(done.returncode, f"failed (exit {done.returncode})")
    return {"row": index, "folder": None, "status": status, "message": message}


def interpreter() -> list:
    """How to start batch.py again: this Python with the bpy wheel, or Blender in the background."""
    import bpy

    script = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "batch.py")
    binary = getattr(bpy.app, "binary_path", "") or ""
    if binary and os.path.basename(binary).lower().startswith("blender") and os.path.isfile(binary):
        return [binary, "-b", "--factory-startup", "--python", script, "--"]
    return [sys.executable, script]
