#!/usr/bin/env python3
"""Plots time per particle of one RK4 cloth step against n, as an SVG, from BenchmarkDotNet's CSV export.

Usage: python3 benchmarks/plot.py [--results DIR] [--c-reference FILE] [--out docs/benchmarks-time-per-particle.svg]

Reads DIR/*ClothStepBenchmarks-report.csv (DIR defaults to BenchmarkDotNet.Artifacts/results), takes the
'RK4 step' rows and their computed 'ns/particle' column, and draws it against n on a log2 axis. With
--c-reference, also draws the C reference (the output of benchmarks/reference-c/run.sh saved to a file).
Standard library only (no matplotlib on the build machines).
"""
import argparse
import csv
import glob
import math
import os
import sys


def read_library(results_dir):
    paths = glob.glob(os.path.join(results_dir, "*ClothStepBenchmarks-report.csv"))
    if not paths:
        sys.exit(f"error: no *ClothStepBenchmarks-report.csv in {results_dir}; run the benchmarks first")
    points = []
    with open(paths[0], newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            if row.get("Method") != "'RK4 step'" and row.get("Method") != "RK4 step":
                continue
            value = row.get("ns/particle", "NA")
            try:
                points.append((int(row["N"]), float(value.replace(",", ""))))
            except ValueError:
                sys.exit(f"error: no ns/particle value for n = {row.get('N')}: {value!r}")
    return sorted(points)


def read_c_reference(path):
    points = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            fields = line.split()
            if len(fields) >= 5 and fields[0].isdigit():
                points.append((int(fields[0]), float(fields[3])))
    return sorted(points)


def svg(series, title):
    width, height = 640, 400
    left, right, top, bottom = 70, 20, 40, 50
    ns = sorted({n for _, pts, _ in series for n, _ in pts})
    ys = [y for _, pts, _ in series for _, y in pts]
    x_min, x_max = math.log2(min(ns)), math.log2(max(ns))
    if x_max == x_min:
        x_max = x_min + 1
    y_max = max(ys) * 1.15
    step = 10 ** math.floor(math.log10(y_max / 5))
    for m in (1, 2, 5, 10):
        if y_max / (m * step) <= 8:
            step *= m
            break

    def px(n):
        return left + (math.log2(n) - x_min) / (x_max - x_min) * (width - left - right)

    def py(y):
        return height - bottom - y / y_max * (height - top - bottom)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="22" text-anchor="middle" font-size="14">{title}</text>']
    y = 0.0
    while y <= y_max:
        out.append(f'<line x1="{left}" y1="{py(y):.1f}" x2="{width - right}" y2="{py(y):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{left - 6}" y="{py(y) + 4:.1f}" text-anchor="end">{y:g}</text>')
        y += step
    for n in ns:
        out.append(f'<line x1="{px(n):.1f}" y1="{top}" x2="{px(n):.1f}" y2="{height - bottom}" stroke="#eee"/>')
        out.append(f'<text x="{px(n):.1f}" y="{height - bottom + 16}" text-anchor="middle">{n}</text>')
    out.append(f'<line x1="{left}" y1="{height - bottom}" x2="{width - right}" y2="{height - bottom}" stroke="black"/>')
    out.append(f'<line x1="{left}" y1="{top}" x2="{left}" y2="{height - bottom}" stroke="black"/>')
    out.append(f'<text x="{(left + width - right) / 2}" y="{height - 12}" text-anchor="middle">'
               f'n (cloth of n x n particles, log scale)</text>')
    out.append(f'<text x="16" y="{(top + height - bottom) / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {(top + height - bottom) / 2})">ns per particle per RK4 step</text>')
    for index, (name, pts, colour) in enumerate(series):
        path = " ".join(f"{px(n):.1f},{py(v):.1f}" for n, v in pts)
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for n, v in pts:
            out.append(f'<circle cx="{px(n):.1f}" cy="{py(v):.1f}" r="3.5" fill="{colour}"/>')
        ly = top + 10 + 18 * index
        out.append(f'<line x1="{left + 12}" y1="{ly}" x2="{left + 36}" y2="{ly}" stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{left + 42}" y="{ly + 4}">{name}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", default="BenchmarkDotNet.Artifacts/results")
    parser.add_argument("--c-reference", help="a saved output of benchmarks/reference-c/run.sh")
    parser.add_argument("--title", default="RK4 cloth step: time per particle")
    parser.add_argument("--out", default="docs/benchmarks-time-per-particle.svg")
    args = parser.parse_args()
    series = [("ParticlePhysics (C#)", read_library(args.results), "#1f77b4")]
    if args.c_reference:
        series.append(("C reference (gcc -O3)", read_c_reference(args.c_reference), "#d62728"))
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(svg(series, args.title))
    for name, pts, _ in series:
        print(name + ": " + ", ".join(f"n={n}: {v:g} ns/particle" for n, v in pts))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
