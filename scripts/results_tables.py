#!/usr/bin/python3
"""The Markdown tables of docs/results.md, read from the folders `relume eval` wrote.

Usage: scripts/results_tables.py OUT_DIR NAME...   (OUT_DIR/NAME/ holds one eval's files and,
from scripts/eval_all.sh, OUT_DIR/NAME/refit/*.json, compress reports at 0 entries.)
Prints, per field: Eq. 16 by residual entries for every configuration and method, the CPCA / L1
ratio at the primary configuration (all functions and both classes), the refit at 0 entries as
the containers store it, relighting speed and error per residual cap, rate against distortion,
the residual's sparseness at a few thresholds and the compression times.
"""
import csv
import json
import os
import sys

METHODS = ("l1", "l1-refit", "cpca", "cpca-mean")


def read_csv(folder, name):
    with open(os.path.join(folder, name), newline="") as stream:
        return list(csv.DictReader(stream))


def table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(str(cell) for cell in row) + " |")


def error_table(folder):
    rows = read_csv(folder, "error_vs_entries.csv")
    entries = sorted({int(r["entries"]) for r in rows if not r["refit_for"]})
    configs = sorted({(int(r["clusters"]), int(r["terms"])) for r in rows})
    print("\nEq. 16 error (all stored functions) by residual entries; l1-refit is one run per"
          " budget, measured at that budget")
    out = []
    for clusters, terms in configs:
        for method in METHODS:
            at = {int(r["entries"]): float(r["error_all"]) for r in rows
                  if r["method"] == method and int(r["clusters"]) == clusters
                  and int(r["terms"]) == terms}
            if at:
                out.append([f"{clusters} x {terms}", method] +
                           [f"{at[e]:.5f}" if e in at else "" for e in entries])
    table(["clusters x terms", "method"] + [str(e) for e in entries], out)


def ratio_table(folder, summary):
    clusters, terms = (int(v) for v in summary["settings"]["primary"].split("x"))
    rows = [r for r in read_csv(folder, "error_ratio.csv")
            if int(r["clusters"]) == clusters and int(r["terms"]) == terms]
    print(f"\nCPCA error / relume error at {clusters} x {terms} (above 1: relume is better);"
          f" classes: {summary['classes']['diffuse']} mostly diffuse,"
          f" {summary['classes']['specular_or_shadowed']} mostly specular or shadowed functions")
    table(["entries", "method", "all", "diffuse", "specular/shadowed"],
          [[r["entries"], r["method"], f"{float(r['ratio_all']):.3f}",
            f"{float(r['ratio_diffuse']):.3f}", f"{float(r['ratio_specular']):.3f}"]
           for r in rows])
    difference = summary["error_difference"]
    print(f"\nPer-pixel map at {difference['entries']} entries: relume's error is lower at"
          f" {100 * difference['fraction_where_relume_is_better']:.1f}% of"
          f" {difference['pixels']} pixels")


def refit_table(folder):
    refit = os.path.join(folder, "refit")
    if not os.path.isdir(refit):
        return
    print("\n64 x 4 without residual, as stored (compress report error_masked)")
    out = []
    for label in ("l1", "cpca", "l1-refit", "l1-refit-choose"):
        path = os.path.join(refit, label + ".json")
        if os.path.exists(path):
            with open(path) as stream:
                report = json.load(stream)
            out.append([label, f"{report['error_masked']:.6f}", f"{report['seconds']:.1f}"])
    table(["method", "Eq. 16", "seconds"], out)


def relighting_table(folder):
    rows = read_csv(folder, "relighting.csv")
    print(f"\nRelighting ({rows[0]['clusters']} x {rows[0]['terms']}, {rows[0]['device']}):"
          " frames/s of relight(), relit image error under the map, Eq. 16 as stored")
    table(["method", "cap", "frames/s", "relit error", "Eq. 16"],
          [[r["method"], r["cap"], f"{float(r['frames_per_second']):.0f}",
            f"{float(r['relit_error']):.5f}", f"{float(r['error_masked']):.5f}"] for r in rows])


def rate_table(folder, summary):
    clusters, terms = (int(v) for v in summary["settings"]["primary"].split("x"))
    rows = [r for r in read_csv(folder, "rate_distortion.csv")
            if int(r["clusters"]) == clusters and int(r["terms"]) == terms]
    print(f"\nRate against distortion at {clusters} x {terms}, as stored")
    table(["method", "entries", "bytes/pixel", "Eq. 16", "PSNR mask (dB)"],
          [[r["method"], r["entries"], f"{float(r['bytes_per_pixel']):.2f}",
            f"{float(r['error_masked']):.5f}", f"{float(r['psnr_mask']):.2f}"] for r in rows])


def sparseness_table(folder, summary):
    clusters, terms = (int(v) for v in summary["settings"]["primary"].split("x"))
    rows = [r for r in read_csv(folder, "sparseness.csv")
            if int(r["clusters"]) == clusters and int(r["terms"]) == terms]
    wanted = (0.001, 0.01, 0.1)
    print(f"\nFraction of the full residual's entries with |e| <= threshold x the function's norm"
          f" ({clusters} x {terms})")
    out = []
    for method in METHODS:
        at = {float(r["threshold"]): float(r["fraction_at_or_below"]) for r in rows
              if r["method"] == method}
        if at:
            cells = [min(at, key=lambda t: abs(t - w)) for w in wanted]
            out.append([method] + [f"{at[t]:.3f}" for t in cells])
    table(["method"] + [f"{w:g}" for w in wanted], out)


def time_table(folder):
    rows = read_csv(folder, "compression_time.csv")
    print("\nCompression time (seconds to make the model from the prepared rows)")
    table(["method", "clusters x terms", "refit for", "seconds", "iterations"],
          [[r["method"], f"{r['clusters']} x {r['terms']}", r["refit_for"],
            f"{float(r['seconds']):.1f}", r["iterations"]] for r in rows])


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: results_tables.py OUT_DIR NAME...")
    out = sys.argv[1]
    for name in sys.argv[2:]:
        folder = os.path.join(out, name)
        with open(os.path.join(folder, "eval.json")) as stream:
            summary = json.load(stream)
        field = summary["field"]
        print(f"\n### {name}: {field['width']}x{field['height']}, {field['lights']} lights,"
              f" {field['stored_functions']} stored functions ({summary['seconds']:.0f} s)")
        error_table(folder)
        ratio_table(folder, summary)
        refit_table(folder)
        relighting_table(folder)
        rate_table(folder, summary)
        sparseness_table(folder, summary)
        time_table(folder)


if __name__ == "__main__":
    main()
