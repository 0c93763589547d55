"""``batch.py job FILE.toml [--each rows.csv [--jobs N]]``: a job file (:mod:`.jobfile`), or a
template run once per row of a CSV (:mod:`.jobtemplate`)."""
from __future__ import annotations

import os

from . import gate, jobfile, jobtemplate
from .batchio import number
from .workflow import BatchCommand


def batch_arguments(p):
    import argparse

    p.add_argument("file", help="the job file (TOML): [setup] and [[operations]]")
    p.add_argument("--post", help="the post (default: the job file's, else the scene's)")
    p.add_argument("--each", metavar="CSV", help="a template's rows: the job once per row, {{column}} in the job "
                   "file replaced by the row's value, each row into its own sub-folder of --out")
    p.add_argument("--jobs", type=number("--jobs", 1, 64, integer=True), default=1,
                   help="with --each: rows run side by side in this many worker processes (default 1)")
    p.add_argument("--base-dir", help=argparse.SUPPRESS)      # a template's row: where its paths start
    gate.allow_findings_argument(p)


def batch(args) -> dict:
    if args.each:
        return jobtemplate.batch_rows(args)
    if args.jobs != 1:
        raise jobfile.JobFileError("--jobs is for the rows of --each")
    return jobfile.write_job(args.file, args.out, args.post, args.allow_findings, base_dir=args.base_dir)


def sample_jobs() -> tuple:
    """The demo's job runs: every job file in samples/jobs, a template (a .toml with a .csv of the
    same name beside it) once per row: (sub-folder, command line) pairs."""
    folder = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "jobs")
    runs = []
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else ():
        stem, extension = os.path.splitext(name)
        if extension != ".toml":
            continue
        rows = os.path.join(folder, stem + ".csv")
        line = (os.path.join(folder, name),) + (("--each", rows) if os.path.isfile(rows) else ())
        runs.append((f"jobs/{stem}", line))
    return tuple(runs)


COMMAND = BatchCommand("job", "a job file (TOML): several operations on one stock, one program (--each: a "
                       "template per CSV row)", batch_arguments, batch, demo=None, more_demos=sample_jobs())
