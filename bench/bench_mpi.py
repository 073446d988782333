#!/usr/bin/env python3
"""Scaling of `rrf generate` and `rrf train` over MPI ranks, and of whole `rrf sweep` and `rrf pipeline` runs (issue 17; docs/cluster.md).

Runs each stage on the bundled Cornell box once as 1 rank and once as 2 ranks (`mpirun -n`), every
rank with one worker thread (`--threads 1`), so that on a 2-core machine the two runs compare one core
with two. Prints per stage the wall time of both runs, the speed-up and the per-rank compute times the
ranks log ("rank k/n: ... in X s"), then projects the time at 200 ranks for the seed report's
7 million records with this model (stated again in the output):

  T(P) = S0 + s*R + c*R/P * b + k*R*(P-1)/P

  R   records; the measured run's, or 7e6 for the projection
  S0  constant serial seconds: start-up, scene and BVH (the CPU seconds of mpirun and rrf for a run of
      8 cells x 1 direction)
  s   serial seconds per record on rank 0: the CPU seconds of the 1-rank run (mpirun and rrf) outside
      its logged compute, less S0 (reading, grouping and writing the dataset, or loading the dataset
      and writing the models)
  c   compute seconds per record of one rank with one thread: the CPU seconds the 1-rank run logs for
      its work (CPU, not wall: on a shared machine the wall time also holds other jobs' share)
  b   imbalance: the busiest rank's CPU seconds over the ranks' mean, measured at 2 ranks
  k   seconds per record of sending the other ranks' parts to rank 0 and joining them (the
      "gathered and joined" time rank 0 logs at 2 ranks, over the R/2 records it received): every
      record but rank 0's own crosses once, whatever P; MPI's start-up and per-message latency
      (milliseconds for 200 ranks) are left out

For training, whole objects go to ranks, so at P >= objects the compute term is the largest object's
share of the records: c*R*max_share*b_obj (b_obj = 1), not c*R/P; the projection says so. Epochs are fixed
(--epochs) so that both runs do the same work; a real run stops each network at its error goal.

Load balance of generation, measured: the same grid as two equal cell counts (`--shard 0/2`, `1/2`, run
one after the other with one thread each) against the ranks' cost-balanced ranges; the imbalance is the
busier part's CPU seconds over the mean of the two.

Whole commands, wall time of 1 rank against 2 (each rank one thread): a hidden-size sweep of three
points (reference at a fixed spp, the path tracer's series and the points as tasks on the ranks, longest
first by estimated seconds) and a pipeline (ground truth by interleaved rows, data by cells, networks by
objects, two held-out references by lights), each on a fresh copy of the project; the sweep's CSV is
compared without its timing columns, the pipeline's dataset and ground truth byte for byte. The
sweep's ranks log the CPU seconds of their tasks: the busiest over the mean measures the cost model.

Usage: bench/bench_mpi.py [--rrf build/rrf] [--mpirun mpirun] [--grid 10,10,10] [--dirs 300] [--spp 16]
                          [--epochs 60]
Keep the defaults on a shared 2-core machine: the whole bench takes about three minutes.
"""
import argparse
import csv
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

RECORDS_TARGET = 7e6  # the seed report's 7 M records
RANKS_TARGET = 200    # Ren et al.'s cluster of 200 PCs


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, env):
    """Runs cmd; returns its wall seconds, its output and the CPU seconds of it and its processes."""
    start, cpu = time.monotonic(), child_cpu()
    p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - start
    if p.returncode != 0:
        sys.exit("bench_mpi: failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-4000:]))
    run.cpu = child_cpu() - cpu
    return wall, p.stdout


def rank_times(log, pattern):
    return [float(t) for t in re.findall(pattern, log)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rrf", default=os.path.join(here, "..", "build", "rrf"))
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--grid", default="10,10,10")
    ap.add_argument("--dirs", default="300")
    ap.add_argument("--spp", default="16")
    ap.add_argument("--epochs", default="60")
    a = ap.parse_args()
    project = os.path.join(here, "..", "projects", "cornell-box", "project.json")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_btl_vader_single_copy_mechanism="none", OMPI_MCA_btl="self,vader")

    def mpi(n, args):
        return [a.mpirun, "--oversubscribe", "--bind-to", "none", "-n", str(n), a.rrf] + args

    tmp = tempfile.mkdtemp(prefix="bench_mpi_")
    # Fixed paths per record (--max-spp = --spp): the cost model balances the fixed part only.
    sampling = ["--grid", a.grid, "--dirs", a.dirs, "--spp", a.spp, "--max-spp", a.spp, "--threads", "1"]
    print("bench_mpi: Cornell box, grid %s x %s directions x %s spp; train %s epochs; %d cores, load %s"
          % (a.grid, a.dirs, a.spp, a.epochs, os.cpu_count(), open("/proc/loadavg").read().split()[0]))

    # S0: the constant part of one process (start-up, scene, BVH, a near-empty dataset).
    run(mpi(1, ["generate", project, "--grid", "2,2,2", "--dirs", "1", "--spp", "1", "--max-spp", "1",
                "--threads", "1", "--out", os.path.join(tmp, "tiny.rrfd")]), env)
    s0 = run.cpu

    stages = []
    # ---- generate ----
    data = os.path.join(tmp, "one.rrfd")
    w1, log1 = run(mpi(1, ["generate", project] + sampling + ["--out", data]), env)
    cpu1 = run.cpu
    records = int(re.search(r"^(\d+) records in ", log1, re.M).group(1))
    c1 = float(re.search(r"^\d+ records in [\d.]+ s \(([\d.]+) s CPU", log1, re.M).group(1))
    w2, log2 = run(mpi(2, ["generate", project] + sampling + ["--out", os.path.join(tmp, "two.rrfd")]), env)
    r2 = rank_times(log2, r"rank \d/2: \d+ records in [\d.]+ s \(([\d.]+) s CPU")
    j2 = float(re.search(r"gathered and joined 2 parts in ([\d.]+) s", log2).group(1))
    same = open(data, "rb").read() == open(os.path.join(tmp, "two.rrfd"), "rb").read()
    stages.append(("generate", w1, c1, w2, r2, j2, records, None, same, cpu1))
    # Equal cell counts, as --shard k/n splits (and as the ranks would without the cost model).
    equal = []
    for k in (0, 1):
        _, logk = run(mpi(1, ["generate", project] + sampling + ["--shard", "%d/2" % k,
                                                                 "--out", os.path.join(tmp, "shard%d.rrfd" % k)]), env)
        equal.append(float(re.search(r"^\d+ records in [\d.]+ s \(([\d.]+) s CPU", logk, re.M).group(1)))

    # ---- train ----
    net = ["--epochs", a.epochs, "--threads", "1", "--log-every", "0"]
    tw1, tlog1 = run(mpi(1, ["train", project, "--data", data] + net + ["--out", os.path.join(tmp, "m1")]), env)
    tcpu1 = run.cpu
    tc1 = float(re.search(r"^trained in [\d.]+ s \(([\d.]+) s CPU", tlog1, re.M).group(1))
    tw2, tlog2 = run(mpi(2, ["train", project, "--data", data] + net + ["--out", os.path.join(tmp, "m2")]), env)
    tr2 = rank_times(tlog2, r"rank \d/2: trained \d+ networks in [\d.]+ s \(([\d.]+) s CPU")
    tj2 = float(re.search(r"gathered and joined 2 parts in ([\d.]+) s", tlog2).group(1))
    # Each object's records, from the generator's per-object lines: objects are the unit ranks train.
    shares = [int(n) for n in re.findall(r"^\s+object \d+ \S+\s+(\d+) records", log1, re.M)]
    max_share = max(shares) / sum(shares) if shares else 1.0
    stages.append(("train", tw1, tc1, tw2, tr2, tj2, records, max_share, None, tcpu1))

    # ---- whole commands: sweep and pipeline ----
    def fresh_project(name):
        d = os.path.join(tmp, name)
        os.makedirs(d)
        for f in ("project.json", "scene.json"):
            shutil.copy(os.path.join(os.path.dirname(project), f), d)
        return os.path.join(d, "project.json")

    def csv_without_times(path):
        rows = list(csv.reader(open(path)))
        keep = [i for i, name in enumerate(rows[0]) if "seconds" not in name]
        return [[r[i] for i in keep] for r in rows]

    data_flags = ["--grid", "6,6,6", "--dirs", "60", "--data-spp", "8", "--epochs", a.epochs, "--threads", "1"]
    sweep = ["sweep", project, "--what", "hidden", "--values", "5", "10,5", "20,10", "--width", "48", "--height", "48",
             "--reference-spp", "64", "--trainer", "adam"] + data_flags
    sw1, _ = run(mpi(1, sweep + ["--out", os.path.join(tmp, "s1")]), env)
    sw2, slog2 = run(mpi(2, sweep + ["--out", os.path.join(tmp, "s2")]), env)
    same_sweep = csv_without_times(os.path.join(tmp, "s1", "sweep_hidden.csv")) == \
        csv_without_times(os.path.join(tmp, "s2", "sweep_hidden.csv"))
    shares = re.findall(r"^rank \d/2: sweep (.*?): ([\d.]+)% of the estimated", slog2, re.M)
    sweep_cpu = rank_times(slog2, r"rank \d/2: ran \d+ sweep task\(s\) in [\d.]+ s \(([\d.]+) s CPU")
    pipe = ["--width", "48", "--height", "48", "--spp", "64", "--held-out", "2", "--noise", "0.2", "--spp-cap", "64",
            "--trainer", "adam"] + data_flags
    pw1, _ = run(mpi(1, ["pipeline", fresh_project("p1")] + pipe + ["--out", os.path.join(tmp, "o1")]), env)
    pw2, _ = run(mpi(2, ["pipeline", fresh_project("p2")] + pipe + ["--out", os.path.join(tmp, "o2")]), env)
    same_pipe = all(open(os.path.join(tmp, "o1", f), "rb").read() == open(os.path.join(tmp, "o2", f), "rb").read()
                    for f in ("dataset.rrfd", "ground_truth/global.exr", "held_out/light_1/reference_global.exr"))

    print("\n%-9s %9s %9s %8s  %-26s %s" % ("stage", "1 rank s", "2 ranks s", "speed-up", "rank CPU s (1 | 2)",
                                            "output"))
    for name, w1_, c1_, w2_, r2_, _, _, _, same_, _ in stages:
        print("%-9s %9.2f %9.2f %7.2fx  %-26s %s" % (
            name, w1_, w2_, w1_ / w2_, "%.2f | %s" % (c1_, " ".join("%.2f" % t for t in r2_)),
            "" if same_ is None else ("bytes identical" if same_ else "BYTES DIFFER")))

    print("%-9s %9.2f %9.2f %7.2fx  %-26s %s" % ("sweep", sw1, sw2, sw1 / sw2, "-",
                                                 "rows identical but times" if same_sweep else "ROWS DIFFER"))
    print("%-9s %9.2f %9.2f %7.2fx  %-26s %s" % ("pipeline", pw1, pw2, pw1 / pw2, "-",
                                                 "bytes identical" if same_pipe else "BYTES DIFFER"))
    print("  sweep shares at 2 ranks (estimated seconds, longest first): " +
          "; ".join("%s %s%%" % (what, pct) for what, pct in shares))
    if sweep_cpu:
        print("  sweep tasks' CPU s per rank at 2 ranks: %s (busiest / mean %.3f)" % (
            " ".join("%.2f" % t for t in sweep_cpu), max(sweep_cpu) / (sum(sweep_cpu) / len(sweep_cpu))))

    mean = lambda v: sum(v) / len(v)
    print("\nload balance of generate at 2 ranks (busiest part / mean, CPU s): equal cell counts %.3f (%.2f, %.2f), "
          "cost-balanced ranges %.3f (%.2f, %.2f)" % (max(equal) / mean(equal), equal[0], equal[1],
                                                        max(r2) / mean(r2), r2[0], r2[1]))

    print("\nprojection to %d ranks for %.0f M records: T(P) = S0 + s*R + c*R/P*b + k*R*(P-1)/P" %
          (RANKS_TARGET, RECORDS_TARGET / 1e6))
    print("  S0 = %.2f s (start-up, scene, BVH: a run of 8 cells x 1 direction, CPU s of mpirun and rrf)" % s0)
    print("  all terms in CPU seconds of one core (on this shared machine wall times also hold other jobs' share)")
    for name, w1_, c1_, w2_, r2_, j2_, recs, share, _, cpu1_ in stages:
        serial1 = max(cpu1_ - c1_, 0.0)
        s = max(serial1 - s0, 0.0) / recs
        c = c1_ / recs
        b = max(r2_) / (sum(r2_) / len(r2_)) if r2_ and sum(r2_) > 0 else 1.0
        k = j2_ / (recs / 2)
        R, P = RECORDS_TARGET, RANKS_TARGET
        t1 = s0 + s * R + c * R
        if share is None:
            compute = c * R / P * b
            rule = "c*R/P*b"
        else:
            compute = c * R * share
            rule = "c*R*max_share (objects, not ranks, bound training: largest object %.1f%% of the records)" % (
                100 * share)
        comm = k * R * (P - 1) / P
        tp = s0 + s * R + compute + comm
        print("  %-8s s = %.3g s/record, c = %.3g s/record, b = %.3f, k = %.3g s/record; compute term %s" % (
            name, s, c, b, k, rule))
        print("  %-8s T(1) = %.0f s, T(%d) = %.0f s (speed-up %.1fx; serial part %.0f s)" % (
            name, t1, P, tp, t1 / tp, s0 + s * R + comm))
    print("\n(measured on a machine shared with other jobs; 1 thread per rank; temporary files in %s, removed)" % tmp)
    subprocess.run(["rm", "-rf", tmp])


if __name__ == "__main__":
    main()
