#!/usr/bin/env python3
"""The table of tests/bench/scene_suite.sh: for each scene and configuration, the last checkpoint of
`pathlab converge`'s convergence.csv, its error per sample relMSE x spp and its efficiency
1/(relMSE x s), and with a base run beside it the ratios new / base.
Arguments: SCENE=NEW_DIR[,BASE_DIR] ..."""
import csv
import sys


def last_rows(directory):
    rows = {}
    with open(f"{directory}/convergence.csv", newline="") as f:
        for row in csv.DictReader(f):
            rows[row["config"]] = row  # checkpoints are in order: the last one stays
    return rows


def figures(row):
    spp, seconds, relmse = int(row["spp"]), float(row["seconds"]), float(row["relmse"])
    return spp, seconds, relmse, relmse * spp, 1.0 / (relmse * seconds), spp / seconds


def main(args):
    with_base = any("," in a for a in args)
    head = "| scene | config | spp | s | relMSE | relMSE×spp | efficiency 1/(relMSE·s) | spp/s |"
    if with_base:
        head += " relMSE×spp new/base | spp/s new/base | efficiency new/base |"
    print(head)
    print("|---|---|" + "---:|" * (head.count("|") - 3))
    for arg in args:
        scene, dirs = arg.split("=", 1)
        runs = [last_rows(d) for d in dirs.split(",")]
        for config, row in runs[0].items():
            n = figures(row)
            line = f"| {scene} | `{config}` | {n[0]} | {n[1]:.3g} | {n[2]:.4g} | {n[3]:.4g} | {n[4]:.4g} | {n[5]:.3g} |"
            if len(runs) > 1:
                b = figures(runs[1][config])
                line += f" {n[3] / b[3]:.2f} | {n[5] / b[5]:.2f} | {n[4] / b[4]:.2f} |"
            print(line)


if __name__ == "__main__":
    main(sys.argv[1:])
