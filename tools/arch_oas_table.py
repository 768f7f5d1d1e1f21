#!/usr/bin/env python3
"""Tables of docs/arches.md 3b from `rocking arch oas --t1 T1` JSON files (argv) and their
`/usr/bin/time` lines (the same name with .err): the boundary of one record, and one row per
record of the t1 check. A collapse whose run peaked below 0.01 rad is flagged as suspect (the
loop driver's collapse criterion firing while the arch rattles nearly closed)."""
import json
import sys

SUSPECT = 0.01


def load(path):
    d = json.load(open(path))
    peaks = {(c['level'], c['radius']): c['peak_angle'] for c in d['runs']['collapses']}
    wall = cpu = None
    try:
        for line in open(path[:-5] + '.err'):
            if 's wall,' in line and 'user' in line:
                parts = line.split()
                wall, cpu = float(parts[0]), float(parts[3])
    except OSError:
        pass
    return d, peaks, wall, cpu


def clean_t1(d, peaks):
    """1/f over the boundary points whose run peaked at or above SUSPECT: an upper bound of the
    f_min a driver without the suspect collapses would give, so a lower bound of its t1."""
    fs = [l['f'] for l in d['levels'] if l['f'] is not None and peaks[(l['level'], l['size'])] >= SUSPECT]
    return 1 / min(fs) if fs else None


def boundary(path):
    d, peaks, _, _ = load(path)
    for l in d['levels']:
        if l['size'] is None:
            failed = sum(1 for f in d['runs']['failures'] if f['level'] == l['level'])
            note = f"none ({l['simulations']} runs, {failed} failed)" if failed else 'none'
            print(f"| {l['level']:g} | {note} | | | |")
        else:
            pk = peaks[(l['level'], l['size'])]
            flag = ' (suspect)' if pk < SUSPECT else ''
            print(f"| {l['level']:g} | {l['size']:.2f} | {l['p']:.4f} | {l['f']:.3f} | {pk:.2e}{flag} |")


def fmt(x, f='{:.3f}'):
    return '—' if x is None else f.format(x)


def rows(paths):
    print('| record | single-block t₁ (s) | arch t₁ = 1/f_min (s) | level, R at f_min | arch t₁ without suspect collapses (lower bound, s) | boundary points violating the rule | conservative | runs (failed) | wall / CPU (s) |')
    print('|---|---:|---:|---|---:|---:|---|---:|---:|')
    for p in paths:
        d, peaks, wall, cpu = load(p)
        c = d['check']
        r = d['runs']
        runs = r['collapsed'] + r['survived'] + len(r['failures'])
        at = '—' if d['f_min'] is None else f"{d['level_at_f_min']:g}, {d['size_at_f_min']:.1f} m"
        print(f"| {d['record']} | {c['t1']:.4f} | {fmt(d['t1'])} | {at} | {fmt(clean_t1(d, peaks))} | {c['violations']} | {'yes' if c['conservative'] else 'no'} | {runs} ({len(r['failures'])}) | {fmt(wall, '{:.0f}')} / {fmt(cpu, '{:.0f}')} |")


if __name__ == '__main__':
    if sys.argv[1] == 'boundary':
        boundary(sys.argv[2])
    else:
        rows(sys.argv[2:])
