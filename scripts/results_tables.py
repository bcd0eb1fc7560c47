#!/usr/bin/python3
"""The Markdown tables of docs/results.md, read from the folders `relume eval` wrote.

Usage: scripts/results_tables.py OUT_DIR NAME...   (OUT_DIR/NAME/ holds one eval's files and,
from scripts/eval_all.sh, OUT_DIR/NAME/refit/*.json, compress reports at 0 entries.)
Prints, per field: Eq. 16 by residual entries for every configuration and method, the CPCA / L1
ratio at the primary configuration (all functions and both classes), the refit at 0 entries as
the containers store it, relighting speed and error per residual cap, rate against distortion,
the residual's sparseness at a few thresholds and the compression times; then one row of
headline findings per field.
"""
import csv
import json
import os
import sys

METHODS = ("l1", "l1-refit", "cpca", "cpca-mean")


def read_csv(folder, name):
    with open(os.path.join(folder, name), newline="") as stream:
        return list(csv.DictReader(stream))


def number(text, digits):
    """A CSV cell with `digits` decimals; an empty cell (an empty class) as "n/a"."""
    return f"{float(text):.{digits}f}" if text not in ("", "nan") else "n/a"


def table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(str(cell) for cell in row) + " |")


def primary(summary):
    """The (clusters, terms) of the eval's primary configuration."""
    return tuple(int(v) for v in summary["settings"]["primary"].split("x"))


def primary_rows(folder, name, summary):
    """The rows of one CSV at the primary configuration."""
    clusters, terms = primary(summary)
    return [r for r in read_csv(folder, name)
            if int(r["clusters"]) == clusters and int(r["terms"]) == terms]


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
    clusters, terms = primary(summary)
    rows = primary_rows(folder, "error_ratio.csv", summary)
    print(f"\nCPCA error / relume error at {clusters} x {terms} (above 1: relume is better);"
          f" classes: {summary['classes']['diffuse']} mostly diffuse,"
          f" {summary['classes']['specular_or_shadowed']} mostly specular or shadowed functions")
    table(["entries", "method", "all", "diffuse", "specular/shadowed"],
          [[r["entries"], r["method"], number(r["ratio_all"], 3),
            number(r["ratio_diffuse"], 3), number(r["ratio_specular"], 3)] for r in rows])
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
    clusters, terms = primary(summary)
    rows = primary_rows(folder, "rate_distortion.csv", summary)
    print(f"\nRate against distortion at {clusters} x {terms}, as stored")
    table(["method", "entries", "bytes/pixel", "Eq. 16", "PSNR mask (dB)"],
          [[r["method"], r["entries"], f"{float(r['bytes_per_pixel']):.2f}",
            f"{float(r['error_masked']):.5f}", f"{float(r['psnr_mask']):.2f}"] for r in rows])


def sparseness_table(folder, summary):
    clusters, terms = primary(summary)
    rows = primary_rows(folder, "sparseness.csv", summary)
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


def findings(out, names):
    """One row per field at its primary configuration: the headline of docs/results.md."""
    print("\n### Findings at each field's primary configuration")
    rows = []
    for name in names:
        folder = os.path.join(out, name)
        with open(os.path.join(folder, "eval.json")) as stream:
            summary = json.load(stream)
        clusters, terms = primary(summary)
        ratios = {(r["method"], int(r["entries"])): float(r["ratio_all"])
                  for r in primary_rows(folder, "error_ratio.csv", summary)}
        wins = sorted(e for (m, e), ratio in ratios.items() if m == "l1" and ratio > 1)
        refit = [f"{ratios[('l1-refit', e)]:.3f}" if ("l1-refit", e) in ratios else "n/a"
                 for e in (0, 1)]
        choice = "n/a"
        reports = {}
        for label in ("cpca", "l1-refit-choose"):
            path = os.path.join(folder, "refit", label + ".json")
            if os.path.exists(path):
                with open(path) as stream:
                    reports[label] = json.load(stream)["error_masked"]
        if len(reports) == 2:
            choice = f"{100 * (reports['l1-refit-choose'] / reports['cpca'] - 1):+.2f}%"
        relit = {}
        for r in read_csv(folder, "relighting.csv"):
            relit.setdefault(int(r["cap"]), {})[r["method"]] = float(r["relit_error"])
        better = [str(cap) for cap, at in sorted(relit.items()) if at["l1"] < at["cpca"]]
        rows.append([name, f"{clusters} x {terms}", f"{100 * (1 - ratios[('l1', 0)]):.1f}%",
                     str(wins[0]) if wins else "none", " / ".join(refit), choice,
                     ", ".join(better) or "none"])
    table(["field", "configuration", "CPCA lower at 0 entries by",
           "first entries where relume L1 is lower", "l1-refit ratio at 0 / 1 entries",
           "l1-refit-choose vs CPCA at 0 entries, as stored",
           "caps where relume's relit image is closer"], rows)


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
    findings(out, sys.argv[2:])


if __name__ == "__main__":
    main()
