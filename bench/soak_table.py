#!/usr/bin/env python3
"""Prints the Markdown tables of docs/reliability.md "Soak and flood" from the JSON results of bench/node_soak.py
and bench/scene_soak.py, so that the table carries the measured numbers and nothing typed by hand.

  bench/soak_table.py [--node docs/data/node_soak_flood.json docs/data/node_soak_random.json]
                      [--scenes docs/data/scene_soak.json]

Numbers are printed with 4 significant digits (RSS and counts in full).
"""
import argparse
import json
import os

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(REPO, 'docs', 'data')


def g(v, digits=4):
    """A measured number at `digits` significant digits; n/a for a missing one."""
    if v is None:
        return 'n/a'
    return str(v) if isinstance(v, int) else f'{v:.{digits}g}'


def node_row(r):
    """One node soak as a table row."""
    rejected = r['diagnostics_last'].get('rejected commands', 'n/a')
    faults = ', '.join(f'{n} {k}' for k, n in r['faults'].items()) or '0'
    return (f"| {r['mode']} | {g(r['wall_s'])} | {g(r['send_rate_median_hz'])} ({r['commands_sent']} sent, "
            f"{r['commands_invalid_sent']} invalid; {rejected} rejected) | {g(r['rate_median_hz'])} / "
            f"{g(r['rate_min_hz'])} ({r['lost_seq_holes']} lost) | {r['non_finite_messages']} | "
            f"{r['rss_first_kib']} / {r['rss_last_kib']} / {r['rss_max_kib']} | {g(r['rss_slope_kib_per_min'], 3)} | "
            f"{g(r['cpu_percent'], 3)} | {g(r['residual_max'], 3)} | {g(r['achieved_rtf_median'])} / "
            f"{g(r['achieved_rtf_min'])} | {faults} | {r['alive_ok']}/{r['alive_checks']}, max "
            f"{g(1e3 * r['alive_max_s'], 3)} ms | {g(r['loadavg_1min_mean'], 3)} (max {g(r['loadavg_1min_max'], 3)}) |")


def node_table(paths):
    lines = ['| mode | wall s | commands/s | TopState Hz median / min per 10 s | non-finite | RSS KiB first / last / max '
             '| RSS slope KiB/min after 60 s | node CPU % | residual max | achieved RTF median / min | faults (reset) '
             '| ~pause answered | load 1-min mean |',
             '|---|---|---|---|---|---|---|---|---|---|---|---|---|']
    for p in paths:
        with open(p) as f:
            lines.append(node_row(json.load(f)))
    return lines


def scene_row(r):
    """One top_sim_run as a table row."""
    if not r.get('summary'):
        return f"| {r['scene']} | {g(r['duration_s'])} | {r['status']} | {g(r['wall_s'])} | | | no summary | | | | |"
    return (f"| {r['scene']} | {g(r['duration_s'])} | {r['status']} | {g(r['wall_s'])} | {g(r['cpu_s'])} | "
            f"{r['peak_rss_kib']} | {g(r['sim_seconds'])} | {r['regime']} / {r['contact_mode']} | "
            f"{r['contact_fault_kind'] or '-'} | {g(r['energy_balance_residual'], 3)} | {r['mode_switch_count']} | "
            f"{', '.join(r['non_finite']) or 'none'} |")


def scene_table(path):
    lines = ['| scene | simulated s asked | exit | wall s | CPU s | peak RSS KiB | simulated s done | final regime / mode '
             '| fault | residual max | mode switches | non-finite |',
             '|---|---|---|---|---|---|---|---|---|---|---|---|']
    with open(path) as f:
        lines += [scene_row(r) for r in json.load(f)['runs']]
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--node', nargs='*', default=[os.path.join(DATA, f'node_soak_{m}.json') for m in ('flood', 'random')])
    ap.add_argument('--scenes', default=os.path.join(DATA, 'scene_soak.json'))
    args = ap.parse_args()
    print('\n'.join(node_table([p for p in args.node if os.path.isfile(p)])))
    print()
    if os.path.isfile(args.scenes):
        print('\n'.join(scene_table(args.scenes)))


if __name__ == '__main__':
    main()
