"""The figure scripts' angle helpers (scripts/plots/plotlib.py): phi of a negative-spin top sits near pi and wraps
at +-pi; the plots draw it unwrapped, with phi* at its 2 pi copies, so no full-height jump appears."""
import math
import os
import subprocess
import sys

import numpy as np

PLOTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts', 'plots')
sys.path.insert(0, PLOTS)

from plotlib import continuous_angle, levels_in  # noqa: E402


def wrapped(angle):
    return (np.asarray(angle) + math.pi) % (2 * math.pi) - math.pi


def test_a_direction_near_pi_is_drawn_without_jumps():
    truth = math.pi - 0.02 + 0.05 * np.sin(np.linspace(0.0, 40.0, 2000))  # wiggles across +pi
    phi = wrapped(truth)
    assert np.max(np.abs(np.diff(phi))) > math.pi  # the raw series jumps
    unwrapped = continuous_angle(phi)
    assert np.max(np.abs(np.diff(unwrapped))) < 0.01
    assert np.allclose(unwrapped - unwrapped[0], truth - truth[0], atol=1e-12)


def test_phi_star_is_drawn_at_its_copies_within_the_range():
    phi_star = wrapped(math.pi + 0.27)  # -pi + 0.27, the mirror phi* of a negative spin
    levels = levels_in(np.array([2.9, 3.5]), phi_star)
    assert len(levels) == 1 and abs(levels[0] - (phi_star + 2 * math.pi)) < 1e-12
    assert levels_in(np.array([0.0, 0.1]), 0.27) == [0.27]  # none inside: the nearest


def test_trajectory_plot_of_a_wrapping_run(tmp_path):
    t = np.linspace(0.0, 4.0, 400)
    phi = wrapped(math.pi + 0.1 * np.sin(5 * t))
    csv = tmp_path / 'run.csv'
    with open(csv, 'w') as f:
        f.write('t,contact_x,contact_y,phi,energy_residual\n')
        for k in range(len(t)):
            f.write('%r,%r,%r,%r,%r\n' % (t[k], -1e-3 * t[k], 0.0, phi[k], 1e-12))
    png = tmp_path / 'run.png'
    subprocess.run(['/usr/bin/python3', os.path.join(PLOTS, 'trajectory.py'), str(csv), str(png), '--phi-star',
                    repr(float(wrapped(math.pi - 0.27)))], check=True)
    assert png.stat().st_size > 10000
