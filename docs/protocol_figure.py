#!/usr/bin/env python3
"""Draws docs/protocol.svg: the full-model protocol's body rates and specific force over time.

Usage: imucal simulate --config configs/protocol-sim.yaml --seed 1 --out /tmp/p
       python3 docs/protocol_figure.py /tmp/p/imu.csv docs/protocol.svg
"""
import csv
import math
import sys

W, H, LEFT, RIGHT = 900, 445, 60, 20
PANELS = [("body rate [deg/s]", 0, 180.0 / math.pi, 130), ("specific force [g]", 3, 1 / 9.80665, 1.2)]
COLOURS = ["#d62728", "#2ca02c", "#1f77b4"]
# The protocol's steps (configs/protocol-sim.yaml): start, end, label.
STEPS = [(5, 11, "flat: turn"), (13, 15, "nose up"), (17, 23, "turn"), (25, 27, "flat"), (29, 31, "right side"),
         (33, 39, "turn"), (41, 43, "flat"), (45, 47, "tail down"), (49, 55, "turn"), (57, 59, "flat"),
         (61, 63, "left side"), (65, 71, "turn")]


def main(imu_csv, out_svg):
    rows = list(csv.DictReader(open(imu_csv)))
    t = [float(r["t"]) for r in rows]
    cols = ["gx", "gy", "gz", "ax", "ay", "az"]
    data = {c: [float(r[c]) for r in rows] for c in cols}
    t_end = t[-1]
    x_of = lambda s: LEFT + (W - LEFT - RIGHT) * s / t_end
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           '<text x="60" y="16" font-size="14">Full-model protocol: five 360 deg turns, each about the axis then vertical (73 s)</text>']
    panel_h, top0 = 170, 30
    for p, (title, first, scale, limit) in enumerate(PANELS):
        top = top0 + p * (panel_h + 25)
        y_of = lambda v: top + panel_h / 2 - (panel_h / 2) * v / limit
        for a, b, label in STEPS:
            out.append(f'<rect x="{x_of(a):.1f}" y="{top}" width="{x_of(b) - x_of(a):.1f}" height="{panel_h}" fill="#eeeeee"/>')
            if p == 0:
                out.append(f'<text x="{(x_of(a) + x_of(b)) / 2:.1f}" y="{top + 12}" text-anchor="middle" font-size="10">{label}</text>')
        out.append(f'<rect x="{LEFT}" y="{top}" width="{W - LEFT - RIGHT}" height="{panel_h}" fill="none" stroke="black"/>')
        out.append(f'<line x1="{LEFT}" x2="{W - RIGHT}" y1="{y_of(0):.1f}" y2="{y_of(0):.1f}" stroke="#999" stroke-dasharray="3,3"/>')
        out.append(f'<clipPath id="panel{p}"><rect x="{LEFT}" y="{top}" width="{W - LEFT - RIGHT}" height="{panel_h}"/></clipPath>')
        for v in (-round(limit / 2, -1 if limit > 10 else 1), round(limit / 2, -1 if limit > 10 else 1)):
            out.append(f'<text x="{LEFT - 5}" y="{y_of(v) + 4:.1f}" text-anchor="end">{v:g}</text>')
        out.append(f'<text x="14" y="{top + panel_h / 2}" transform="rotate(-90 14 {top + panel_h / 2})" text-anchor="middle">{title}</text>')
        for k in range(3):
            c = cols[first + k]
            pts = " ".join(f"{x_of(t[i]):.1f},{y_of(data[c][i] * scale):.1f}" for i in range(0, len(t), 10))
            out.append(f'<polyline points="{pts}" fill="none" stroke="{COLOURS[k]}" stroke-width="1.2" clip-path="url(#panel{p})"/>')
            out.append(f'<text x="{W - RIGHT - 60 + 20 * k}" y="{top + panel_h - 6}" fill="{COLOURS[k]}">{"xyz"[k]}</text>')
    axis_y = top0 + 2 * panel_h + 25 + 16
    for s in range(0, int(t_end) + 1, 10):
        out.append(f'<text x="{x_of(s):.1f}" y="{axis_y}" text-anchor="middle">{s}</text>')
    out.append(f'<text x="{(LEFT + W) / 2}" y="{axis_y + 16}" text-anchor="middle">time [s] (shaded: moving)</text>')
    out.append("</svg>")
    open(out_svg, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
