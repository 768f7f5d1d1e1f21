#!/usr/bin/env python3
"""Tables of docs/arch-spectra.md from `rocking arch oas --t1 T1` JSON files (argv) and their
`/usr/bin/time -f "%e s wall, %U user, ..."` lines (the same name with .err): the boundary of one
record (`boundary FILE`), one row per record of the t1 check (`rows FILES`), and the totals over
the records (`summary FILES`). A collapse whose run peaked below 0.01 rad is flagged as suspect
(the collapse criterion firing while the arch rattles nearly closed, as the loop driver before
the Hermite location did); `rows` gives the smallest peak of a boundary collapse to show there is
none. `steps [--factors 0.999,1.001] FILES` sets the records of FILES (the default step) beside
their runs with `--dt-factor F`, read from DIR/dt/oas-RECORD-xF.json (DIR that of each file): one
row per record (ratio, verdict and boundary points below the rule at each step, the relative
change of the ratio and the boundary points moved against the default step), then the totals per
step and the flips."""
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


def step_set(path, factors):
    """The record at the default step (path) and at each factor (DIR/dt/oas-RECORD-xF.json)."""
    d = load(path)
    base = path[:path.rfind('/') + 1] if '/' in path else ''
    other = [load(f"{base}dt/oas-{d[0]['record']}-x{f}.json") for f in factors]
    return [d] + other


def shown(row):
    """A row of sets (×1 first, then the factors) in the order of the columns: the first factor, ×1, the others."""
    return row[1:2] + row[:1] + row[2:]


def verdict(d):
    return 'yes' if d['check']['conservative'] else 'no'


def ratio_of(d):
    return None if d['t1'] is None else d['t1'] / d['check']['t1']


def rel(r, r1):
    return None if r is None or r1 is None else abs(r / r1 - 1)


def steps(args):
    factors = ['0.999', '1.001']
    if args[0] == '--factors':
        factors, args = args[1].split(','), args[2:]
    names = [f'×{f}' for f in factors[:1]] + ['×1'] + [f'×{f}' for f in factors[1:]]
    sets = [step_set(p, factors) for p in args]
    print(f"| record | single-block t₁ (s) | ratio {' / '.join(names)} | conservative {' / '.join(names)} | boundary points below the rule {' / '.join(names)} | verdict flips | change of the ratio against ×1 {' / '.join(f'×{f}' for f in factors)} | boundary points moved (of {len(sets[0][0][0]['levels'])}) {' / '.join(f'×{f}' for f in factors)} |")
    print('|---|---:|---:|---|---:|---|---:|---:|')
    for s in sets:
        ds = [x[0] for x in s]
        r1 = ratio_of(ds[0])
        ch = [rel(ratio_of(d), r1) for d in ds[1:]]
        flip = 'yes' if len({d['check']['conservative'] for d in ds}) > 1 else ''
        moved = [sum(a['size'] != b['size'] for a, b in zip(ds[0]['levels'], d['levels'])) for d in ds[1:]]
        print(f"| {ds[0]['record']} | {ds[0]['check']['t1']:.4f} | {' / '.join(fmt(ratio_of(d), '{:.2f}') for d in shown(ds))} | "
              f"{' / '.join(verdict(d) for d in shown(ds))} | {' / '.join(str(d['check']['violations']) for d in shown(ds))} | {flip} | "
              f"{' / '.join(fmt(None if c is None else 100 * c, '{:.1f} %') for c in ch)} | {' / '.join(map(str, moved))} |")
    print()
    n = len(sets)
    for i, name in enumerate(['×1'] + [f'×{f}' for f in factors]):
        ds = [s[i][0] for s in sets]
        rs = sorted(r for r in (ratio_of(d) for d in ds) if r is not None)
        nc = sum(not d['check']['conservative'] for d in ds)
        cpu = sum(s[i][3] or 0 for s in sets)
        wall = sum(s[i][2] or 0 for s in sets)
        print(f"{name}: not conservative on {nc} of {n}; ratio min {rs[0]:.2f}, median {statistics.median(rs):.2f}, max {rs[-1]:.2f}, above 1.5 on {sum(r > 1.5 for r in rs)}; "
              f"{sum(d['check']['violations'] for d in ds)} boundary points below the rule; wall {wall:.0f} s, CPU {cpu:.0f} s")
    for i, f in enumerate(factors, 1):
        flips = [s[0][0]['record'] for s in sets if s[0][0]['check']['conservative'] != s[i][0]['check']['conservative']]
        ch = sorted((rel(ratio_of(s[i][0]), ratio_of(s[0][0])), s[0][0]['record']) for s in sets
                    if ratio_of(s[i][0]) is not None and ratio_of(s[0][0]) is not None)
        same = sum(c == 0 for c, _ in ch)
        moved = sum(a['size'] != b['size'] for s in sets for a, b in zip(s[0][0]['levels'], s[i][0]['levels']))
        pts = sum(len(s[0][0]['levels']) for s in sets)
        print(f"×{f} against ×1: verdict flips on {len(flips)} {flips}; ratio unchanged on {same}, relative change median {100 * statistics.median(c for c, _ in ch):.1f} %, "
              f"largest {100 * ch[-1][0]:.1f} % ({ch[-1][1]}), above 5 % on {sum(c > 0.05 for c, _ in ch)}, above 18 % on {sum(c > 0.18 for c, _ in ch)}; "
              f"boundary points moved {moved} of {pts}")
    any_flip = [s[0][0]['record'] for s in sets if len({x[0]['check']['conservative'] for x in s}) > 1]
    nc_all = sum(all(not x[0]['check']['conservative'] for x in s) for s in sets)
    c_all = sum(all(x[0]['check']['conservative'] for x in s) for s in sets)
    print(f"verdict the same at every step on {n - len(any_flip)} of {n} (not conservative at all: {nc_all}, conservative at all: {c_all}); flips on {any_flip}")
    nc = [sum(not s[i][0]['check']['conservative'] for s in sets) for i in range(len(factors) + 1)]
    mx = [max(ratio_of(s[i][0]) for s in sets if ratio_of(s[i][0]) is not None) for i in range(len(factors) + 1)]
    holds = all(c > n / 2 for c in nc) and all(m <= 2.1 for m in mx)
    print(f"record-set conclusion (not conservative on most records, ratio at most about 2, here <= 2.1) at every step: {'holds' if holds else 'does not hold'} "
          f"(not conservative on {', '.join(map(str, nc))}; largest ratio {', '.join(f'{m:.2f}' for m in mx)}, in the order ×1, {', '.join('×' + f for f in factors)})")


if __name__ == '__main__':
    if sys.argv[1] == 'boundary':
        boundary(sys.argv[2])
    elif sys.argv[1] == 'steps':
        steps(sys.argv[2:])
    elif sys.argv[1] == 'summary':
        summary(sys.argv[2:])
    else:
        rows(sys.argv[2:])
