#!/usr/bin/env python3
"""Executed standard SOC of a SUMO one-shot run (default: the demo config/small_warehouse.yaml)
under several planning budgets and seeds, with a planner setting off (the baseline) and on,
in the same run.

For each budget (planner.budget_ms values, or planner.expansions values with budget_ms 0,
deterministic) and planner.seed it writes a copy of the config with absolute paths, runs
rtlacam-sumo, and reads metrics.json (soc: the standard SOC of the executed plan, soc_lb).
It prints soc/LB per run, the mean per budget, the ratio on/off, and the ratio to a best
known SOC (--best; 244 for the demo: long full-horizon LaCAM* + LNS, docs/closed_loop_bench.md).

  python3 scripts/demo_soc_bench.py --bin build/apps/rtlacam-sumo --ms 1 10 100 --seeds 0 1 2
  python3 scripts/demo_soc_bench.py --bin build/apps/rtlacam-sumo --expansions 10 100 1000
  (--key planner.dive: the setting compared, false then true)
"""
import argparse, json, os, re, subprocess, sys, tempfile


def run(args, cfg_text, budget_ms, expansions, seed, value, work):
    text = cfg_text
    key = args.key.split('.')[-1]
    extra = f"  {key}: {value}\n  seed: {seed}\n  budget_ms: {budget_ms}\n  expansions: {expansions}\n"
    # planner: section: drop its seed/budget_ms/expansions/<key> lines, append ours
    lines, out, inside = text.splitlines(), [], False
    for ln in lines:
        if re.match(r'^\S', ln):
            if inside:
                out.append(extra.rstrip('\n'))
            inside = ln.startswith('planner:')
        if inside and re.match(rf'^\s+(seed|budget_ms|expansions|{key}):', ln):
            continue
        out.append(ln)
    if inside:
        out.append(extra.rstrip('\n'))
    base = os.path.dirname(os.path.abspath(args.config))
    text = '\n'.join(out) + '\n'
    text = re.sub(r'(net|additional):\s*(\.\./\S+)', lambda m: f"{m.group(1)}: {os.path.normpath(os.path.join(base, m.group(2)))}", text)
    d = os.path.join(work, f"{budget_ms}_{expansions}_{seed}_{value}")
    text = re.sub(r'dir:\s*\S+', f'dir: {d}', text)
    path = d + '.yaml'
    with open(path, 'w') as f:
        f.write(text)
    r = subprocess.run([args.bin, path], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{args.bin} {path}: exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}")
    m = json.load(open(os.path.join(d, 'metrics.json')))
    if not m.get('solved'):
        sys.exit(f"{path}: not solved")
    return m['soc'], m['soc_lb']


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--bin', required=True, help='rtlacam-sumo')
    ap.add_argument('--config', default=os.path.join(os.path.dirname(__file__), '..', 'config', 'small_warehouse.yaml'))
    ap.add_argument('--ms', type=float, nargs='*', default=[], help='planner.budget_ms values')
    ap.add_argument('--expansions', type=int, nargs='*', default=[], help='planner.expansions values (budget_ms 0)')
    ap.add_argument('--seeds', type=int, nargs='+', default=[0, 1, 2])
    ap.add_argument('--key', default='planner.dive', help='boolean planner setting compared (false: baseline)')
    ap.add_argument('--best', type=float, default=244, help='best known SOC of the instance')
    args = ap.parse_args()
    if not args.ms and not args.expansions:
        ap.error('give --ms and/or --expansions')
    cfg_text = open(args.config).read()
    budgets = [(ms, 0) for ms in args.ms] + [(0, e) for e in args.expansions]
    with tempfile.TemporaryDirectory() as work:
        print(f"{'budget':>14} {'seed':>4} {'off soc/LB':>10} {'on soc/LB':>10} {'on/off':>7} {'on/best':>8}")
        for ms, e in budgets:
            label = f"{ms:g} ms" if e == 0 else f"{e} exp"
            offs, ons = [], []
            for s in args.seeds:
                off, lb = run(args, cfg_text, ms, e, s, 'false', work)
                on, _ = run(args, cfg_text, ms, e, s, 'true', work)
                offs.append(off)
                ons.append(on)
                print(f"{label:>14} {s:>4} {off / lb:>10.3f} {on / lb:>10.3f} {on / off:>7.3f} {on / args.best:>8.3f}", flush=True)
            mo, mn = sum(offs) / len(offs), sum(ons) / len(ons)
            print(f"{label + ' mean':>14} {'':>4} {mo / lb:>10.3f} {mn / lb:>10.3f} {mn / mo:>7.3f} {mn / args.best:>8.3f}", flush=True)


if __name__ == '__main__':
    main()
