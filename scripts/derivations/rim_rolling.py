#!/usr/bin/env python3
"""Checks the rim contact's kinematics of docs/design/contact_shapes.md: a thin disc rolling without slipping on a
level plane, its contact point r_p - r_cm = d f - rho e with e = (n - (n.f) f)/|n - (n.f) f|. Rolling, d/dt v_p = 0
with v_p = v_cm + w x r_p, gives a_cm + w' x r_p + w x r_p' = 0, where r_p' = d f' - rho e' is the rate of the
vector r_p (the contact point runs along the rim). From the steady state of physics.md section 13 (centre at rest,
Omega^2 a sin(beta) = 4 g) the disc must stay there; 5 % more Omega must leave it. RK4, numpy only:
    /usr/bin/python3 scripts/derivations/rim_rolling.py"""
import numpy as np

n = np.array([0.0, 0.0, 1.0])
g = 9.81


def e_and_rate(f, fdot):
    c = n @ f
    s = np.sqrt(1.0 - c * c)
    e = (n - c * f) / s
    cdot = n @ fdot
    sdot = -c * cdot / s
    edot = (-cdot * f - c * fdot) / s - (n - c * f) * sdot / (s * s)
    return e, edot


def rhs(state, m, Id, If, rho, d):
    x, v, f, w = state[0:3], state[3:6], state[6:9], state[9:12]
    f = f / np.linalg.norm(f)
    fdot = np.cross(w, f)
    e, edot = e_and_rate(f, fdot)
    r = d * f - rho * e
    rdot = d * fdot - rho * edot
    Iinv = lambda u: u / Id + (1.0 / If - 1.0 / Id) * (f @ u) * f
    I = lambda u: Id * u + (If - Id) * (f @ u) * f
    gyro = np.cross(w, I(w))
    # F/m + g_vec + (Iinv(r x F - gyro)) x r + w x rdot = 0, linear in F: K F = b
    K = np.zeros((3, 3))
    for j in range(3):
        u = np.zeros(3); u[j] = 1.0
        K[:, j] = u / m + np.cross(Iinv(np.cross(r, u)), r)
    b = -(np.array([0.0, 0.0, -g]) - np.cross(Iinv(gyro), r) + np.cross(w, rdot))
    F = np.linalg.solve(K, b)
    a = F / m + np.array([0.0, 0.0, -g])
    wdot = Iinv(np.cross(r, F) - gyro)
    return np.concatenate([v, a, fdot, wdot]), F


def run(Omega_factor, beta, T=0.5, h=5e-5):
    m, a_r = 0.4, 0.04
    Id, If = m * a_r ** 2 / 4, m * a_r ** 2 / 2
    # f at angle beta to n (the disc's plane at beta to the plane), leaning along -x
    f = np.array([-np.sin(beta), 0.0, np.cos(beta)])
    Omega = Omega_factor * np.sqrt(4 * g / (a_r * np.sin(beta)))
    c = n @ f
    w = Omega * n - Omega * c * f  # centre at rest: w parallel to the contact radius
    y = np.concatenate([np.zeros(3), np.zeros(3), f, w])  # the centre's position does not enter the dynamics
    gap = lambda y: y[2] - a_r * np.sqrt(1.0 - (n @ y[6:9] / np.linalg.norm(y[6:9])) ** 2)  # z_cm + h(n.f), d = 0
    gap0, gap_drift = gap(y), 0.0
    beta_max = 0.0
    vmax = 0.0
    for k in range(int(T / h)):
        k1, _ = rhs(y, m, Id, If, a_r, 0.0)
        k2, _ = rhs(y + h / 2 * k1, m, Id, If, a_r, 0.0)
        k3, _ = rhs(y + h / 2 * k2, m, Id, If, a_r, 0.0)
        k4, _ = rhs(y + h * k3, m, Id, If, a_r, 0.0)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        fn = y[6:9] / np.linalg.norm(y[6:9])
        beta_max = max(beta_max, abs(np.arccos(fn @ n) - beta))
        vmax = max(vmax, np.linalg.norm(y[3:6]))
        gap_drift = max(gap_drift, abs(gap(y) - gap0))
    return beta_max, vmax, gap_drift


for factor in (1.0, 1.05):
    db, vm, dg = run(factor, 0.5)
    print("Omega = %.2f x sqrt(4 g / (a sin beta)): max |beta - beta0| = %.3g rad, max |v_cm| = %.3g m/s, "
          "gap z_cm + h(n.f) drift %.3g m" % (factor, db, vm, dg))
