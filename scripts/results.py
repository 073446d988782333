#!/usr/bin/env python3
"""docs/results.md, made by running the benchmarks and pipeline runs that produce its figures.

    scripts/results.py --list                 the sections, their commands and when each was last made
    scripts/results.py tracer kernels         runs those sections again and rebuilds docs/results.md
    scripts/results.py --all                  runs every section (about an hour on 2 cores)
    scripts/results.py --check                exit 1 if docs/results.md is not the assembly of the
                                              recorded sections (a hand edit, a stale assembly)

Each section is one command, run in a fresh scratch directory (projects are copied there, so runs,
datasets and references never land in the checkout). What it printed is recorded verbatim in
docs/results/<id>.md with the command, the UTC date, the commit (with "+changes" when the tree had
uncommitted changes), the CPU, the core count and the load average when it started. docs/results.md
is those records in the order below under a fixed introduction; it is written whole (temporary file,
then rename). A section that fails keeps its previous record and the script exits non-zero.

Environment: RRF_BUILD_DIR (default build/) holds the programs; the GUI sections need xvfb-run.
"""
import argparse
import datetime
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RECORDS = os.path.join(ROOT, "docs", "results")
RESULTS = os.path.join(ROOT, "docs", "results.md")


class Section:
    """One figure-producing command. `keep` limits what is recorded of a long output: "all", or
    "tail:N" (its last N lines) plus the files named in `files` (relative to the scratch
    directory), which are recorded whole."""

    def __init__(self, ident, title, about, command, keep="all", files=()):
        self.ident, self.title, self.about, self.command = ident, title, about, command
        self.keep, self.files = keep, files


# $BUILD: the build directory; $ROOT: the checkout. Commands run in the scratch directory.
PIPELINE_TAIL = "tail:14"
SECTIONS = [
    Section("tracer", "Path tracer against plain Embree on the same rays",
            "The tracer's rays, logged and replayed through rtcIntersect1 / rtcOccluded1, against the "
            "tracer itself, for 1 and 2 threads in one run (issue 28 item 4: tracer/Embree >= 0.8).",
            "$BUILD/bench_render"),
    Section("kernels", "Network kernels against the machine's GEMM",
            "Adam training and batched inference of the default, best and wide networks on every kernel "
            "the CPU supports, each as a fraction of the same run's float GEMM rate (issue 28 item 1).",
            "$BUILD/bench_nn --quick"),
    Section("ensemble", "Merged ensembles: dense against member by member",
            "Forward passes of K-member ensembles both ways, one thread, a 256x256 frame's samples.",
            "$BUILD/bench_ensemble --quick"),
    Section("direct", "Exact direct light per frame",
            "The exact direct light at 256x256 against the estimator it replaced, with each one's error "
            "against converged references (issue 28 item 2: <= 60 ms at 256 samples on 2 cores).",
            "$BUILD/bench_direct --quick"),
    Section("predict", "CPU prediction against the path tracer",
            "G-buffer, networks and exact direct light per 256x256 frame, and the path-traced ground "
            "truth of the same frame in the same run.",
            "$BUILD/bench_predict --quick"),
    Section("generate", "Data generator throughput and memory",
            "Records, path samples and rays per second of the data generator against the renderer, and "
            "the default Cornell-box dataset's peak memory and file size.",
            "$BUILD/bench_generate"),
    Section("frames", "Workbench frame times under Xvfb",
            "The UI thread's frame times idle, rendering, training and dragging the light (llvmpipe: the "
            "GPU is the CPU), 1280x720 (issue 29: light drag <= 50 ms, idle <= 20 ms).",
            "$ROOT/bench/bench_frames.sh $BUILD/rrf-workbench 1280x720"),
    Section("pipeline-cornell-default", "The default pipeline on the Cornell box, from a fresh copy",
            "`rrf pipeline` with the project's settings, first rendering its held-out references, then "
            "again with the references it stored (issue 28 item 3: <= 60 s at <= 0.04 held-out with "
            "stored references). Errors are global relative RMSE at two held-out lights, raw and "
            "corrected for the references' own noise.",
            "cp -r $ROOT/projects/cornell-box P && $BUILD/rrf pipeline P/project.json --out first "
            "&& $BUILD/rrf pipeline P/project.json --out stored",
            keep=PIPELINE_TAIL, files=("first/held_out/held_out.txt", "stored/held_out/held_out.txt")),
    Section("pipeline-cornell-best", "The best preset on the Cornell box, from a fresh copy",
            "As above with `--preset best` (issue 28 item 3: <= 4 min at <= 0.015 held-out with stored "
            "references).",
            "cp -r $ROOT/projects/cornell-box P && $BUILD/rrf pipeline P/project.json --preset best --out first "
            "&& $BUILD/rrf pipeline P/project.json --preset best --out stored",
            keep=PIPELINE_TAIL, files=("first/held_out/held_out.txt", "stored/held_out/held_out.txt")),
    Section("pipeline-glossy-default", "The default pipeline on the glossy box, from a fresh copy",
            "The glossy Cornell box (Phong walls and boxes, caustics through its ceiling's gather) with "
            "the project's settings, references rendered by the estimator the scene asks for.",
            "cp -r $ROOT/projects/cornell-glossy P && $BUILD/rrf pipeline P/project.json --out first",
            keep=PIPELINE_TAIL, files=("first/held_out/held_out.txt",)),
    Section("pipeline-glossy-best", "The best preset on the glossy box, from a fresh copy",
            "As above with `--preset best`.",
            "cp -r $ROOT/projects/cornell-glossy P && $BUILD/rrf pipeline P/project.json --preset best --out first",
            keep=PIPELINE_TAIL, files=("first/held_out/held_out.txt",)),
]

INTRO = """# Results

Every figure below was produced by the command above it, on the machine, date and commit it names,
and recorded by `scripts/results.py` (docs/results/<section>.md; this file is their assembly, checked
by the CTest `results_assembled`). To measure a section again: `scripts/results.py <section>`;
`scripts/results.py --list` shows what each runs and when it last ran. Ratios within one run (tracer
over Embree, kernels over the GEMM, prediction over path tracing) are the figures to compare across
machines; absolute times move with the machine and its load. Errors are held-out global relative RMSE
against references whose own noise is stated beside them (docs/design.md §14, §15).

Measurements recorded by hand before this script existed (sessions 1-18) are in
[results-history.md](results-history.md), with the commands they name.
"""

HEADER = re.compile(r"^<!-- results: (?P<meta>.*) -->$")


def record_path(ident):
    return os.path.join(RECORDS, ident + ".md")


def git(*args):
    return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True).stdout.strip()


def commit_label():
    label = git("rev-parse", "--short", "HEAD") or "unknown"
    # The records themselves are not the code that made them: a tree whose only changes are
    # records (an earlier invocation's) is still the commit.
    changed = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":(exclude)docs/results.md",
                  ":(exclude)docs/results")
    return label + ("+changes" if changed else "")


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def clean_output(text):
    """Progress lines redraw themselves with carriage returns: keep what each line ended as (split on
    newlines only: str.splitlines would split at every carriage return too)."""
    return "\n".join(line.split("\r")[-1] for line in text.split("\n")).strip("\n")


def command_text(section):
    """The command as a record shows it (one step a line)."""
    return section.command.replace(" && ", " &&\n  ")


def kept(section, text):
    if section.keep.startswith("tail:"):
        lines = text.split("\n")
        n = int(section.keep[5:])
        return ("[... %d earlier lines]\n" % (len(lines) - n) if len(lines) > n else "") + "\n".join(lines[-n:])
    return text


def write_whole(path, text):
    directory = os.path.dirname(path)
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".results-")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def run_section(section, build, commit):
    scratch = tempfile.mkdtemp(prefix="rrf-results-")
    env = dict(os.environ, BUILD=build, ROOT=ROOT, XDG_DATA_HOME=os.path.join(scratch, "xdg-data"),
               XDG_CONFIG_HOME=os.path.join(scratch, "xdg-config"))
    load = os.getloadavg()
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    print("results: %s: %s" % (section.ident, section.command), flush=True)
    t0 = time.monotonic()
    try:
        proc = subprocess.run(["bash", "-c", "set -o pipefail; " + section.command], cwd=scratch, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
        seconds = time.monotonic() - t0
        output = clean_output(proc.stdout)
        if proc.returncode != 0:
            print(output[-4000:])
            print("results: %s failed (exit %d); its previous record stays" % (section.ident, proc.returncode))
            return False
        parts = [kept(section, output)]
        for name in section.files:
            path = os.path.join(scratch, name)
            if not os.path.isfile(path):
                print("results: %s did not write %s; its previous record stays" % (section.ident, name))
                return False
            with open(path, errors="replace") as f:
                parts.append("--- %s\n%s" % (name, f.read().strip("\n")))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    meta = "%s | %s | %s, %d cores, load %.1f %.1f %.1f | %.0f s" % (
        started, commit, cpu_name(), os.cpu_count() or 0, load[0], load[1], load[2], seconds)
    body = "\n\n".join(parts).replace("```", "'''")
    text = ("<!-- results: %s -->\n## %s\n\n%s\n\n```sh\n%s\n```\n\n%s, commit %s; %s, %d cores, load average "
            "%.1f at the start; %.0f s.\n\n```text\n%s\n```\n") % (
        meta, section.title, section.about, command_text(section), started, commit,
        cpu_name(), os.cpu_count() or 0, load[0], seconds, body)
    write_whole(record_path(section.ident), text)
    print("results: %s recorded (%.0f s)" % (section.ident, seconds), flush=True)
    return True


def assembly():
    """docs/results.md as the recorded sections make it: the introduction, then each section's record
    in SECTIONS order, or a line saying it has not been measured by this script yet."""
    out = [INTRO]
    for s in SECTIONS:
        path = record_path(s.ident)
        if os.path.isfile(path):
            with open(path) as f:
                out.append(f.read().strip("\n") + "\n")
        else:
            out.append("## %s\n\nNot measured by this script yet: `scripts/results.py %s`.\n" % (s.title, s.ident))
    return "\n".join(out)


def last_made(ident):
    path = record_path(ident)
    if not os.path.isfile(path):
        return "never"
    with open(path) as f:
        m = HEADER.match(f.readline().rstrip("\n"))
    return m.group("meta") if m else "unreadable record"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sections", nargs="*", help="section ids to run again (see --list)")
    ap.add_argument("--all", action="store_true", help="run every section")
    ap.add_argument("--list", action="store_true", help="list the sections")
    ap.add_argument("--check", action="store_true", help="check docs/results.md against the records")
    args = ap.parse_args()
    known = {s.ident: s for s in SECTIONS}
    if args.list:
        for s in SECTIONS:
            print("%-26s %s\n%-26s last: %s" % (s.ident, s.command, "", last_made(s.ident)))
        return 0
    if args.check:
        with open(RESULTS) as f:
            if f.read() != assembly():
                print("docs/results.md is not the assembly of docs/results/*.md: run scripts/results.py "
                      "(with no sections it only reassembles) instead of editing it by hand")
                return 1
        for s in SECTIONS:
            path = record_path(s.ident)
            if os.path.isfile(path):
                with open(path) as f:
                    if "```sh\n%s\n```" % command_text(s) not in f.read():
                        print("docs/results/%s.md was not made by its section's command (%s): run "
                              "scripts/results.py %s" % (s.ident, s.command, s.ident))
                        return 1
        for name in (os.listdir(RECORDS) if os.path.isdir(RECORDS) else []):
            if name.endswith(".md") and name[:-3] not in known:
                print("docs/results/%s belongs to no section of scripts/results.py" % name)
                return 1
        return 0
    unknown = [i for i in args.sections if i not in known]
    if unknown:
        print("results: unknown section(s) %s; known: %s" % (", ".join(unknown), ", ".join(known)))
        return 2
    build = os.path.abspath(os.environ.get("RRF_BUILD_DIR", os.path.join(ROOT, "build")))
    chosen = SECTIONS if args.all else [known[i] for i in args.sections]
    # The commit is read once, before any record is rewritten (a rewritten record is a change).
    commit = commit_label()
    ok = all([run_section(s, build, commit) for s in chosen])
    write_whole(RESULTS, assembly())
    print("results: %s assembled" % os.path.relpath(RESULTS, ROOT))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
