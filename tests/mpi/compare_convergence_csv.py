#!/usr/bin/env python3
"""compare_convergence_csv.py ONE.csv JOB.csv RANKS: the convergence.csv of one process and of a
RANKS-rank MPI job with the same sample budget describe the same run. Every checkpoint at the same
sample count, with the same camera samples and rays (the ranks' counts add up to one process's),
and the same errors to 1e-4 relative (the same samples, summed in another order, printed to six
digits); the times differ. The job's CSV has a `ranks` column of RANKS when RANKS > 1, one
process's none. Prints what differs and exits 1."""
import csv, sys

one_path, job_path, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3])
one, job = list(csv.DictReader(open(one_path))), list(csv.DictReader(open(job_path)))
problems = []
if "ranks" in one[0]:
    problems.append("one process's CSV has a ranks column")
if ranks > 1 and any(r.get("ranks") != str(ranks) for r in job):
    problems.append(f"the job's rows do not all say ranks = {ranks}")
if ranks == 1 and "ranks" in job[0]:
    problems.append("a one-rank job's CSV has a ranks column")
if len(one) != len(job):
    problems.append(f"{len(one)} checkpoints against {len(job)}")
exact = ("config", "spp", "camera_samples", "rays")
close = ("rmse", "relmse", "mape", "twobuffer_mse", "twobuffer_relmse")
for i, (a, b) in enumerate(zip(one, job)):
    for key in exact:
        if a[key] != b[key]:
            problems.append(f"row {i + 1} ({a['config']}, {a['spp']} spp): {key} {a[key]} against {b[key]}")
    for key in close:
        x, y = float(a[key] or 0), float(b[key] or 0)
        if abs(x - y) > 1e-4 * max(abs(x), abs(y)) + 1e-12:
            problems.append(f"row {i + 1} ({a['config']}, {a['spp']} spp): {key} {x} against {y}")
print("\n".join(problems[:10]))
sys.exit(1 if problems else 0)
