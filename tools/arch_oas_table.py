#!/usr/bin/env python3
"""Tables of docs/arch-spectra.md from `rocking arch oas --t1 T1` JSON files (argv) and their
`/usr/bin/time -f "%e s wall, %U user, ..."` lines (the same name with .err): the boundary of one
record (`boundary FILE`), one row per record of the t1 check (`rows FILES`), and the totals over
the records (`summary FILES`). A collapse whose run peaked below 0.01 rad is flagged as suspect
(the collapse criterion firing while the arch rattles nearly closed, as the loop driver before
the Hermite location did); `rows` gives the smallest peak of a boundary collapse to show there is
none."""
import json
import statistics
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
    print('| record | single-block t₁ (s) | arch t₁ = 1/f_min (s) | ratio | level, R at f_min | boundary points violating the rule | conservative | smallest peak of a boundary collapse (rad) | runs (failed) | wall / CPU (s) |')
    print('|---|---:|---:|---:|---|---:|---|---:|---:|---:|')
    for p in paths:
        d, peaks, wall, cpu = load(p)
        c = d['check']
        r = d['runs']
        runs = r['collapsed'] + r['survived'] + len(r['failures'])
        at = '—' if d['f_min'] is None else f"{d['level_at_f_min']:g}, {d['size_at_f_min']:.1f} m"
        ratio = None if d['t1'] is None else d['t1'] / c['t1']
        bpk = [peaks[(l['level'], l['size'])] for l in d['levels'] if l['size'] is not None]
        low = min(bpk) if bpk else None
        flag = ' (suspect)' if low is not None and low < SUSPECT else ''
        print(f"| {d['record']} | {c['t1']:.4f} | {fmt(d['t1'])} | {fmt(ratio, '{:.2f}')} | {at} | {c['violations']} | {'yes' if c['conservative'] else 'no'} | {fmt(low)}{flag} | {runs} ({len(r['failures'])}) | {fmt(wall, '{:.0f}')} / {fmt(cpu, '{:.0f}')} |")


def summary(paths):
    ds = [load(p) for p in paths]
    ratios = sorted((d['t1'] / d['check']['t1'], d['record']) for d, _, _, _ in ds if d['t1'] is not None)
    cons = sum(d['check']['conservative'] for d, _, _, _ in ds)
    runs = sum(d['runs']['collapsed'] + d['runs']['survived'] + len(d['runs']['failures']) for d, _, _, _ in ds)
    failed = [(d['record'], f) for d, _, _, _ in ds for f in d['runs']['failures']]
    kinds = {}
    for _, f in failed:
        k = f['message'].split(' at t =')[0]
        kinds[k] = kinds.get(k, 0) + 1
    edge = sum(1 for d, _, _, _ in ds if d['size_at_f_min'] is not None and d['size_at_f_min'] in (max(d['sizes']), min(d['sizes'])))
    suspect = sum(1 for d, peaks, _, _ in ds for v in peaks.values() if v < SUSPECT)
    print(f"{len(ds)} records: conservative on {cons}, not on {len(ds) - cons}")
    print(f"arch t1 / single-block t1: min {ratios[0][0]:.2f} ({ratios[0][1]}), median {statistics.median(r for r, _ in ratios):.2f}, max {ratios[-1][0]:.2f} ({ratios[-1][1]}); above 1: {sum(r > 1 for r, _ in ratios)}, above 1.5: {sum(r > 1.5 for r, _ in ratios)}")
    print(f"f_min at the grid's largest or smallest radius: {edge}; collapses peaking below {SUSPECT} rad: {suspect}")
    print(f"runs {runs}, failed {len(failed)} on {len({r for r, _ in failed})} records: {kinds}")
    print(f"wall {sum(w for _, _, w, _ in ds if w):.0f} s, CPU {sum(c for _, _, _, c in ds if c):.0f} s")


if __name__ == '__main__':
    if sys.argv[1] == 'boundary':
        boundary(sys.argv[2])
    elif sys.argv[1] == 'summary':
        summary(sys.argv[2:])
    else:
        rows(sys.argv[2:])
