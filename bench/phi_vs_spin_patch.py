#!/usr/bin/env python3
"""d phi*/d omega with a finite contact (issue 32 part 6, physics.md section 12, the paper's open question).

For each shipped top on its plane (aluminium/PMMA, steel/steel, wood/steel, as in docs/results.md's Fig. 4) and
each inclination and start spin, run `top_sim_run` from the point contact's exact sleeping state with
  - `point`:    no patch (the adiabatic reference, phi* analytic),
  - `hertz`:    `contact: {patch_radius: hertz}` (exact drilling law),
  - `elliptic`: the same patch with Leine & Glocker's elliptic law,
let the start transient relax, and take the mean direction of travel `phi` and the mean spin over the last half
of the run. The run lasts `DURATION_PER_SPIN * spin` seconds: the precession relaxes over a time proportional to
the spin (physics.md section 5), so every spin gets the same relaxation in scaled time. d phi/d omega is the slope
of a straight-line fit of phi against the window's mean spin, per top, inclination and contact.

  bench/phi_vs_spin_patch.py [--bin build/bin/top_sim_run] [--json docs/data/phi_vs_spin_patch.json]
                             [--spins 50,100,...] [--alphas 0.09,0.15] [--refit]

Writes the raw per-run numbers and the fits to the JSON file; prints a table. Exit 0 whatever the figures.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The tops on the planes of docs/results.md's Fig. 4 (the paper's wooden top ran on its own plane; ours on steel).
PAIRS = [('aluminium', 'pmma'), ('steel', 'steel'), ('wood', 'steel')]
CONTACTS = {
    'point': None,
    'hertz': '{patch_radius: hertz, drilling_law: exact}',
    'elliptic': '{patch_radius: hertz, drilling_law: elliptic}',
}
# Air drag, the one term of physics.md section 12 with a speed scale of its own (degree 1 in the velocities), for
# the wooden top only (the paper's non-adiabatic top): Stokes' laminar drag of a sphere of radius AIR_RADIUS in air,
# force 6 pi eta r, torque 8 pi eta r^3 (a lower bound: a real top's wake is not laminar), and the force x1000 (the
# torque kept: x1000 spins the top down within the run) to show the mechanism's sign and scaling. AIR_RADIUS is ASSUMED (a 3 cm body; config/tops/wood.yaml gives no size).
AIR_VISCOSITY = 1.81e-5  # Pa s, air at 20 C
AIR_RADIUS = 0.015  # m
STOKES_DRAG = 6 * 3.141592653589793 * AIR_VISCOSITY * AIR_RADIUS
STOKES_SPIN_DRAG = 8 * 3.141592653589793 * AIR_VISCOSITY * AIR_RADIUS ** 3
AIR = {'air_stokes': 1.0, 'air_drag_x1000': 1000.0}  # factor on the force only
AIR_TOPS = ('wood',)
# Seconds simulated per rad/s of start spin: 0.5 keeps the Hertz patch's spin-down within a few per cent of
# the spin in the window (aluminium on PMMA loses the most) while leaving tens of precession periods to average.
DURATION_PER_SPIN = 0.5
MIN_DURATION = 30.0  # s: the slowest spins still get many precession periods
RATE = 20.0  # Hz of the CSV: well above the precession, below the nutation we do not need


def yaml_numbers(path):
    # The flat `key: number` lines of a shipped top or plane file (enough for mass and the elastic constants).
    out = {}
    for line in open(path):
        key, _, rest = line.partition(':')
        try:
            out[key.strip()] = float(rest.split('#')[0])
        except ValueError:
            pass
    return out


def sleeping_patch(top, plane, alpha):
    # Hertz radius a and lever 3 pi a / 16 of physics.md section 12 at the sleeping state's N = m g cos(alpha).
    t = yaml_numbers(os.path.join(REPO, 'config', 'tops', top + '.yaml'))
    p = yaml_numbers(os.path.join(REPO, 'config', 'planes', plane + '.yaml'))
    e_star = 1.0 / ((1 - t['poisson_ratio'] ** 2) / t['young_modulus'] + (1 - p['poisson_ratio'] ** 2) / p['young_modulus'])
    n = t['mass'] * 9.81 * math.cos(alpha)  # plane.gravity's default
    a = (3 * n * t['tip_radius'] / (4 * e_star)) ** (1.0 / 3.0)
    return {'top': top, 'plane': plane, 'alpha': alpha, 'E_star': e_star, 'N': n, 'a': a,
            'Rbar': 3 * math.pi * a / 16, 'Rbar_over_R': 3 * math.pi * a / 16 / t['tip_radius']}


def scene_text(top, plane, alpha, spin, contact, duration, air=0.0):
    lines = ['description: phi vs spin with a finite contact (bench/phi_vs_spin_patch.py)',
             'top: %s' % top, 'plane: {inclination: %r}' % alpha, 'friction: %s' % plane,
             'initial: {start: stationary, spin: %r}' % spin, 'duration: %r' % duration]
    if contact:
        lines.append('contact: %s' % contact)
    if air:
        lines.append('air: {drag: %r, spin_drag: %r}' % (air * STOKES_DRAG, STOKES_SPIN_DRAG))
    return '\n'.join(lines) + '\n'


def run_one(binary, scenes_dir, top, plane, alpha, spin, cname):
    duration = max(MIN_DURATION, DURATION_PER_SPIN * spin)
    stem = '%s_%s_a%g_w%g_%s' % (top, plane, alpha, spin, cname)
    path = os.path.join(scenes_dir, stem + '.yaml')
    with open(path, 'w') as f:
        air = AIR.get(cname, 0.0)
        f.write(scene_text(top, plane, alpha, spin, CONTACTS['hertz'] if air else CONTACTS[cname], duration, air))
    csv_path = os.path.join(scenes_dir, stem + '.csv')
    t0 = time.time()
    proc = subprocess.run([binary, path, '--csv', csv_path, '--rate', str(RATE), '--summary', '-', '--quiet'],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    wall = time.time() - t0
    rec = {'top': top, 'plane': plane, 'alpha': alpha, 'spin0': spin, 'contact': cname, 'duration': duration,
           'exit': proc.returncode, 'wall_s': wall}
    try:
        summ = json.loads(proc.stdout)
    except ValueError:
        rec['error'] = proc.stderr.strip()[-400:]
        return rec
    rec.update({'phi_star_point': summ.get('phi_star'), 'regime': summ.get('regime'),
                'contact_fault': summ.get('contact_fault_kind'), 'cpu_s': summ.get('cpu_seconds')})
    rows = list(csv.DictReader(open(csv_path)))
    os.remove(csv_path)  # the raw series are large; the JSON keeps the window statistics
    t_end = float(rows[-1]['t'])
    win = [r for r in rows if float(r['t']) >= 0.5 * t_end]
    phis = [float(r['phi']) for r in win]
    spins = [float(r['spin']) for r in win]
    n = len(phis)
    mean = sum(phis) / n
    # Halves of the window: their difference says whether phi still drifts (relaxation or spin-down).
    h = n // 2
    rec.update({'t_end': t_end, 'phi': mean, 'phi_std': (sum((p - mean) ** 2 for p in phis) / n) ** 0.5,
                'phi_first_half': sum(phis[:h]) / h, 'phi_second_half': sum(phis[h:]) / (n - h),
                'spin_mean': sum(spins) / n, 'spin_start_window': spins[0], 'spin_end': spins[-1],
                'slip': float(win[-1]['s']), 'N': float(win[-1]['N'])})
    return rec


def linfit(xs, ys):
    # Least squares y = a + b x, with the slope's standard error (residual scatter, n - 2 dof).
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - b * mx
    res = [y - a - b * x for x, y in zip(xs, ys)]
    se = (sum(r * r for r in res) / (n - 2) / sxx) ** 0.5 if n > 2 else float('nan')
    return a, b, se, max(abs(r) for r in res)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--bin', default=os.path.join(REPO, 'build', 'bin', 'top_sim_run'))
    ap.add_argument('--json', default=os.path.join(REPO, 'docs', 'data', 'phi_vs_spin_patch.json'))
    ap.add_argument('--spins', default='50,100,150,200,250,300,350,400')
    ap.add_argument('--alphas', default='0.09,0.15')
    ap.add_argument('--refit', action='store_true', help='no runs: refit and rewrite the runs already in --json')
    args = ap.parse_args()
    spins = [float(s) for s in args.spins.split(',')]
    alphas = [float(a) for a in args.alphas.split(',')]
    if args.refit:
        old = json.load(open(args.json))
        return report(args, old['runs'], sorted({r['alpha'] for r in old['runs']}), old.get('commit', '?'))
    tmp = tempfile.mkdtemp(prefix='phi_vs_spin_')
    # Scenes resolve `top: NAME` in the config/ folder next to their own folder: point it at this checkout's.
    os.symlink(os.path.join(REPO, 'config'), os.path.join(tmp, 'config'))
    scenes_dir = os.path.join(tmp, 'scenes')
    os.mkdir(scenes_dir)
    runs = []
    for top, plane in PAIRS:
        for alpha in alphas:
            names = list(CONTACTS) + (list(AIR) if top in AIR_TOPS else [])
            for cname in names:
                for spin in spins:
                    rec = run_one(args.bin, scenes_dir, top, plane, alpha, spin, cname)
                    runs.append(rec)
                    print('%-9s %-5s a=%.2f w0=%5.0f %-8s phi=%s std=%s spin=%s %s' % (
                        top, plane, alpha, spin, cname, rec.get('phi'), rec.get('phi_std'), rec.get('spin_mean'),
                        rec.get('regime')), flush=True)
    git = subprocess.run(['git', '-C', REPO, 'rev-parse', '--short', 'HEAD'], stdout=subprocess.PIPE,
                         universal_newlines=True).stdout.strip()
    return report(args, runs, alphas, git)


def report(args, runs, alphas, git):
    # The fits per top, inclination and contact; writes the JSON and prints the table.
    fits = []
    for top, plane in PAIRS:
        for alpha in alphas:
            for cname in list(CONTACTS) + list(AIR):
                ok = [r for r in runs if r['top'] == top and r['alpha'] == alpha and r['contact'] == cname
                      and 'phi' in r and not r['contact_fault']]  # a fallen top has no drift angle
                if len(ok) < 3:
                    continue
                a, b, se, worst = linfit([r['spin_mean'] for r in ok], [r['phi'] for r in ok])
                fits.append({'top': top, 'plane': plane, 'alpha': alpha, 'contact': cname, 'n': len(ok),
                             'dphi_domega': b, 'dphi_domega_se': se, 'intercept': a, 'max_residual': worst,
                             'phi_range': max(r['phi'] for r in ok) - min(r['phi'] for r in ok),
                             'phi_star_point': ok[0]['phi_star_point']})
    out = {'generator': 'bench/phi_vs_spin_patch.py', 'commit': git, 'binary': args.bin,
           'duration_per_spin_s': DURATION_PER_SPIN, 'min_duration_s': MIN_DURATION, 'csv_rate_hz': RATE,
           'window': 'last half of the run', 'air_stokes': {'drag': STOKES_DRAG, 'spin_drag': STOKES_SPIN_DRAG,
                                                            'radius_assumed': AIR_RADIUS, 'viscosity': AIR_VISCOSITY},
           'patches': [sleeping_patch(t, p, a) for t, p in PAIRS for a in alphas], 'runs': runs, 'fits': fits}
    with open(args.json, 'w') as f:
        json.dump(out, f, indent=1)
    print('\n%-9s %-5s %5s %-8s %14s %10s %12s %12s' % ('top', 'plane', 'alpha', 'contact', 'dphi/dw [s]', 'se',
                                                       'phi range', 'phi(200)'))
    for ft in fits:
        print('%-9s %-5s %5.2f %-8s %14.3e %10.1e %12.3e %12.6f' % (
            ft['top'], ft['plane'], ft['alpha'], ft['contact'], ft['dphi_domega'], ft['dphi_domega_se'],
            ft['phi_range'], ft['intercept'] + 200 * ft['dphi_domega']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
