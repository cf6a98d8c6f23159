#!/usr/bin/env python3
"""The side-by-side table (scripts/side-by-side.sh): texplore against Mitsuba 3, from the rounds in WORK.

usage: side_by_side_table.py WORK ROUNDS

Per configuration: the median over rounds of each round's best time (the fastest of its timed
renders, as the peers' harness reports it), the RMSE against Mitsuba's reference (16384 spp for
the sphere, 8192 for the mesh; linear, over all W x H x 3 values), samples per second; then the
time to reach RMSE 0.009 and 0.003 (the fastest configuration at or below it, over every
sampler of each renderer) and the ratios texplore / Mitsuba; the per-spp ratio is against
Mitsuba's fastest sampler at that spp.
Standard library only.
"""
import csv
import glob
import json
import statistics
import sys

work, rounds = sys.argv[1], int(sys.argv[2])
rows = {}  # (renderer, config) -> {"times": [...], "rmse": [...], "samples": n}
for r in range(1, rounds + 1):
    for path in sorted(glob.glob(f"{work}/round-{r}-mitsuba-*.json")):
        mi = json.load(open(path))
        for row in mi["rows"]:
            key = ("Mitsuba 3 llvm", f"{mi['sampler']} {row['spp']} spp", row["spp"])
            e = rows.setdefault(key, {"times": [], "rmse": [], "samples": 640 * 480 * row["spp"]})
            e["times"].append(row["best"])
            e["rmse"].append(row["rmse"])
    for path in sorted(glob.glob(f"{work}/tx-round-{r}-*/report.csv")):
        for row in csv.DictReader(open(path)):
            spp = int(row["spp"])
            key = ("texplore", f"{row['mode']} {spp} spp", spp)
            e = rows.setdefault(key, {"times": [], "rmse": [], "samples": float(row["samples_per_s"]) * float(row["time_ms_median"]) / 1e3})
            e["times"].append(float(row["time_ms_min"]) / 1e3)
            e["rmse"].append(float(row["rmse_linear"]))

def med(v):
    return statistics.median(v)

print(f"Medians over {rounds} alternating rounds (each round: the best of its timed renders).\n")
print("| renderer | configuration | time | RMSE | M samples/s | time / Mitsuba's fastest at this spp |")
print("|---|---|--:|--:|--:|--:|")
# Mitsuba's fastest sampler at each spp: every ratio is against its best configuration.
mi_time = {}
for k, v in rows.items():
    if k[0].startswith("Mitsuba"):
        mi_time[k[2]] = min(mi_time.get(k[2], float("inf")), med(v["times"]))
for key in sorted(rows, key=lambda k: (k[0] != "Mitsuba 3 llvm", k[1].split()[0], k[2])):
    v = rows[key]
    t = med(v["times"])
    ratio = ""
    if key[0] == "texplore" and key[2] in mi_time and "bilinear" in key[1]:
        ratio = f"{t / mi_time[key[2]]:.2f}x"
    print(f"| {key[0]} | {key[1]} | {t * 1e3:.1f} ms | {med(v['rmse']):.5f} | {v['samples'] / t / 1e6:.1f} | {ratio} |")

print("\n| target | Mitsuba 3 llvm (fastest) | texplore (fastest) | texplore / Mitsuba |")
print("|---|---|---|--:|")
for target in (0.009, 0.003):
    best = {}
    for key, v in rows.items():
        t, e = med(v["times"]), med(v["rmse"])
        if e <= target and (key[0] not in best or t < best[key[0]][0]):
            best[key[0]] = (t, key[1])
    cells = []
    for who in ("Mitsuba 3 llvm", "texplore"):
        cells.append(f"{best[who][0] * 1e3:.1f} ms ({best[who][1]})" if who in best else "not reached")
    ratio = ""
    if len(best) == 2:
        ratio = f"{best['texplore'][0] / best['Mitsuba 3 llvm'][0]:.2f}x"
    print(f"| RMSE <= {target} | {cells[0]} | {cells[1]} | {ratio} |")
