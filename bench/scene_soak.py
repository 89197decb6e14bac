#!/usr/bin/env python3
"""Long-run benchmark of the physics core (issue 11, soak): every scene for an hour of simulated time, as fast as
the CPU allows, and the 5000 rad/s hopping scene for 10 s.

Why: the unit tests run seconds of simulated time; a leak, a NaN, a step size that collapses or a run that
never ends shows only over long runs. Each run is `top_sim_run SCENE --duration S --quiet --summary FILE` under
`/usr/bin/time -v` and `timeout`; per run it reports the wall time, CPU time (user + system), peak RSS, exit
status, the final regime and contact mode, the fault (exit 3 ends a run early with a named fault: a result, not
a harness failure), the energy-balance residual (max over the run, relative) and the number of contact-mode
switches. A timeout (exit 124) or a non-finite final state (the summary writes NaN as null) is a finding.

  bench/scene_soak.py [--bin build/bin/top_sim_run] [--duration 3600] [--timeout 1800]
                      [--hopping-duration 10] [--scenes default,hopping] [--json FILE]

Exit status 0 whatever the figures (a benchmark reports, it does not assert), also when a run writes no summary
(reported with its exit status); non-zero only when the harness itself fails (no top_sim_run, no time report).
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Final-state fields of the summary that are numbers in every finite run (null = not finite).
FINAL_NUMBERS = ['t', 'alpha', 'position', 'velocity', 'f_hat', 'omega', 'spin', 'slip', 'phi']


def parse_time_v(path):
    """User + system CPU [s], peak RSS [KiB] and the exit status from GNU time's -v report."""
    fields = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.strip().rpartition(': ')
            fields[key] = value
    return {'cpu_s': float(fields['User time (seconds)']) + float(fields['System time (seconds)']),
            'peak_rss_kib': int(fields['Maximum resident set size (kbytes)']),
            'exit_status': int(fields['Exit status'])}


def null_numbers(summary):
    """Names of the summary's numbers that are null (not finite): the final state and the residual."""
    final = summary.get('final', {})
    names = [f'final.{k}' for k in FINAL_NUMBERS
             if final.get(k) is None or (isinstance(final[k], list) and None in final[k])]
    if summary.get('energy_balance_residual') is None:
        names.append('energy_balance_residual')
    return names


def from_summary(path):
    """The figures this benchmark reports from a top_sim_run summary (empty when none was written)."""
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        return {'summary': False}
    with open(path) as f:
        s = json.load(f)
    return {'summary': True, 'sim_seconds': s['sim_seconds'], 'core_cpu_s': s['cpu_seconds'],
            'steps': s['steps'], 'regime': s['regime'], 'contact_mode': s['contact_mode'],
            'contact_fault_kind': s['contact_fault_kind'], 'contact_fault': s['contact_fault'],
            'energy_balance_residual': s['energy_balance_residual'],
            'mode_switch_count': s['mode_switch_count'], 'mode_seconds': s['mode_seconds'],
            'non_finite': null_numbers(s)}


def run_scene(args, scene, duration, work):
    """One top_sim_run under time -v and timeout; returns its figures and the command that reproduces it."""
    name = os.path.splitext(os.path.basename(scene))[0]
    summary, timing = os.path.join(work, f'{name}_{duration:g}.json'), os.path.join(work, f'{name}_{duration:g}.time')
    run = [args.bin, os.path.relpath(scene, REPO), '--duration', f'{duration:g}', '--quiet', '--summary', summary]
    command = ['/usr/bin/time', '-v', '-o', timing, 'timeout', '-k', '30', f'{args.timeout:g}'] + run
    load0, t0 = os.getloadavg()[0], time.monotonic()
    proc = subprocess.run(command, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    result = {'scene': name, 'duration_s': duration, 'wall_s': wall, 'status': proc.returncode,
              'timed_out': proc.returncode == 124, 'stderr_tail': proc.stderr[-2000:],
              'loadavg_1min_before': load0, 'loadavg_1min_after': os.getloadavg()[0],
              'reproduce': ' '.join([os.path.relpath(args.bin, REPO)] + run[1:-1] + ['-'])}
    result.update(parse_time_v(timing))
    result.update(from_summary(summary))
    return result


def one_line(r):
    """A run as one line of text, for the log."""
    if not r.get('summary'):
        return f"{r['scene']} {r['duration_s']:g} s: exit {r['status']} after {r['wall_s']:.1f} s wall, no summary"
    return (f"{r['scene']} {r['duration_s']:g} s: exit {r['status']}, wall {r['wall_s']:.2f} s, CPU {r['cpu_s']:.2f} s, "
            f"peak RSS {r['peak_rss_kib']} KiB, simulated {r['sim_seconds']:.6g} s, regime {r['regime']}, "
            f"mode {r['contact_mode']}, fault {r['contact_fault_kind']}, residual {r['energy_balance_residual']:.3g}, "
            f"mode switches {r['mode_switch_count']}, non-finite {r['non_finite'] or 'none'}")


def scene_list(args):
    """The scenes to run: all of config/scenes, or those named by --scenes."""
    scenes = sorted(glob.glob(os.path.join(REPO, 'config', 'scenes', '*.yaml')))
    if args.scenes:
        wanted = args.scenes.split(',')
        scenes = [s for s in scenes if os.path.splitext(os.path.basename(s))[0] in wanted]
    return scenes


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--bin', default=os.path.join(REPO, 'build', 'bin', 'top_sim_run'))
    ap.add_argument('--duration', type=float, default=3600.0, help='simulated seconds per scene')
    ap.add_argument('--timeout', type=float, default=1800.0, help='wall seconds before a run counts as a hang')
    ap.add_argument('--hopping-duration', type=float, default=10.0,
                    help='simulated seconds of the extra hopping run (0 = none)')
    ap.add_argument('--scenes', help='comma-separated scene names (default: all of config/scenes)')
    ap.add_argument('--json', help='write every run as JSON here')
    ap.add_argument('--work', help='where summaries and time reports go (default: a new /tmp directory)')
    args = ap.parse_args()
    if not os.access(args.bin, os.X_OK):
        sys.exit(f'scene_soak: {args.bin} is not an executable: build it first (docs/building.md, plain CMake build)')
    work = args.work or tempfile.mkdtemp(prefix='top_sim_scene_soak.')
    os.makedirs(work, exist_ok=True)
    runs = [(s, args.duration) for s in scene_list(args)]
    if args.hopping_duration > 0:
        runs.append((os.path.join(REPO, 'config', 'scenes', 'hopping.yaml'), args.hopping_duration))
    results = []
    for scene, duration in runs:
        results.append(run_scene(args, scene, duration, work))
        print(one_line(results[-1]), flush=True)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'command': 'bench/scene_soak.py ' + ' '.join(sys.argv[1:]), 'runs': results}, f, indent=1)
    print(f'scene_soak: {len(results)} runs, summaries in {work}')


if __name__ == '__main__':
    main()
