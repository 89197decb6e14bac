#!/usr/bin/python3
"""Bodies of shapes side by side: runs each scene with two top_sim_run binaries, interleaved (base, head, base,
head, ...), and prints the median CPU seconds of each, their ratio, and whether the summaries agree (docs/performance.md,
"Bodies of shapes"). Build the base with `git worktree add /tmp/base REV` and a plain CMake build there.

    bench/shapes_side_by_side.py BASE_BIN HEAD_BIN [--runs 3] [SCENE ...]

A scene is a name from config/scenes or a path; the default list is the shipped scenes of bodies of shapes."""
import argparse
import json
import statistics
import subprocess
import sys

SCENES = ['euler_disk', 'tippe_top_stem', 'tippe_top_contensou', 'top_life']


def run(binary, scene):
    out = subprocess.run([binary, scene, '--summary', '-'], capture_output=True, text=True)
    if out.returncode not in (0,):
        lines = out.stderr.strip().splitlines()
        return None, 'exit %d: %s' % (out.returncode, (lines[-1] if lines else '')[:80])
    d = json.loads(out.stdout)
    return d, None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('base')
    ap.add_argument('head')
    ap.add_argument('scenes', nargs='*', default=SCENES)
    ap.add_argument('--runs', type=int, default=3)
    a = ap.parse_intermixed_args()
    print('| scene | base CPU [s] | head CPU [s] | head / base | simulated base, head [s] | steps base, head |')
    print('|---|---|---|---|---|---|')
    for scene in a.scenes:
        cpu = {'base': [], 'head': []}
        last = {}
        for _ in range(a.runs):
            for which, binary in (('base', a.base), ('head', a.head)):
                d, err = run(binary, scene)
                if err:
                    last[which] = err
                    continue
                cpu[which].append(d['cpu_seconds'])
                last[which] = d
        if not cpu['base'] or not cpu['head']:
            print('| %s | %s | %s | - | - | - |' % (scene, last.get('base') if not cpu['base'] else '-',
                                                      last.get('head') if not cpu['head'] else '-'))
            continue
        b, h = statistics.median(cpu['base']), statistics.median(cpu['head'])
        print('| %s | %.4f | %.4f | %.3f | %.6f, %.6f | %d, %d |' % (
            scene, b, h, h / b, last['base']['sim_seconds'], last['head']['sim_seconds'],
            last['base']['steps'], last['head']['steps']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
