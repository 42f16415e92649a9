"""A prolate spheroid turning freely in simple shear, against Jeffery's orbit (3D).

Jeffery (Proc. R. Soc. A 102 (1922) 161): at zero Reynolds number the symmetry axis p of a
spheroid of aspect ratio r in the shear u = G y e_x follows

    dp/dt = W p + B (E p - (p.E p) p),   B = (r^2 - 1)/(r^2 + 1),

E and W the symmetric and skew parts of grad u. The orbit constant
C = sqrt(r^2 p_y^2 + p_x^2)/(r |p_z|) stays fixed (the spheroid "kayaks" about the vorticity
axis z), and the period is T = 2 pi (r + 1/r)/G.

Reads particles.csv of the run (columns time, rotx, roty, rotz: the rotation from the body
frame, whose x axis is the symmetry axis a, to the world), integrates Jeffery's equation
from the simulated axis at t = T_START (the shear has developed), and prints one CSV row:
the time the azimuth of p in the flow-gradient plane takes to turn against Jeffery's, the
largest angle between the simulated and Jeffery's axis, and the drift of C. Draws PNG
with the azimuth and the polar angle of both.

Usage: python3 jeffery_orbit_3d.py OUTPUT_DIR a b G T_START PNG
"""
import csv
import math
import sys

import numpy as np

out, a, b, G, t_start, png = sys.argv[1], *map(float, sys.argv[2:6]), sys.argv[6]
r = a / b
B = (r * r - 1) / (r * r + 1)
grad = np.zeros((3, 3))
grad[0, 1] = G  # du_x/dy
E, W = 0.5 * (grad + grad.T), 0.5 * (grad - grad.T)


def axis(rot):
    """The body x axis in the world: Rodrigues' formula for the rotation vector rot."""
    angle = np.linalg.norm(rot)
    if angle == 0:
        return np.array([1.0, 0, 0])
    k = rot / angle
    e = np.array([1.0, 0, 0])
    return e * math.cos(angle) + np.cross(k, e) * math.sin(angle) + k * (k @ e) * (1 - math.cos(angle))


def jeffery(p):
    Ep = E @ p
    return W @ p + B * (Ep - (p @ Ep) * p)


def orbit_constant(p):
    return math.sqrt(r * r * p[1] ** 2 + p[0] ** 2) / (r * abs(p[2]))


def azimuth(ps):
    """The angle of p's projection on the flow-gradient plane from the flow direction,
    unwrapped (turning clockwise, as the shear turns it: decreasing)."""
    phi = np.unwrap(np.arctan2(ps[:, 1], ps[:, 0]))
    return phi


with open(f"{out}/particles.csv") as f:
    rows = [r for r in csv.DictReader(f)]
t = np.array([float(x["time"]) for x in rows])
p_sim = np.array([axis(np.array([float(x[c]) for c in ("rotx", "roty", "rotz")])) for x in rows])
keep = t >= t_start - 1e-12
t, p_sim = t[keep], p_sim[keep]

# Jeffery's axis from the simulated one at t_start, by RK4 with 100 substeps per output step.
p_j = [p_sim[0]]
for k in range(1, len(t)):
    p, n = p_j[-1].copy(), 100
    h = (t[k] - t[k - 1]) / n
    for _ in range(n):
        k1 = jeffery(p)
        k2 = jeffery(p + 0.5 * h * k1)
        k3 = jeffery(p + 0.5 * h * k2)
        k4 = jeffery(p + h * k3)
        p = p + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        p /= np.linalg.norm(p)
    p_j.append(p)
p_j = np.array(p_j)

phi_sim, phi_j = azimuth(p_sim), azimuth(p_j)
# The time Jeffery's axis takes to reach the simulated one's last azimuth.
target = phi_sim[-1]
if phi_j[-1] > target:  # Jeffery's has not got there yet: go on integrating
    p, time, h = p_j[-1].copy(), t[-1], 1e-3
    phi_prev = phi_j[-1]
    while phi_prev > target and time < t[-1] + 100:
        p = p + h * jeffery(p)
        p /= np.linalg.norm(p)
        time += h
        phi_prev = phi_prev + ((math.atan2(p[1], p[0]) - phi_prev + math.pi) % (2 * math.pi) - math.pi)
    took_jeffery = time - t[0]
else:
    k = int(np.argmax(phi_j <= target))
    s = (phi_j[k - 1] - target) / (phi_j[k - 1] - phi_j[k])
    took_jeffery = t[k - 1] + s * (t[k] - t[k - 1]) - t[0]
took = t[-1] - t[0]
deviation = max(math.degrees(math.acos(min(1.0, abs(x @ y)))) for x, y in zip(p_sim, p_j))
C = np.array([orbit_constant(p) for p in p_sim])
drift = np.max(np.abs(C / C[0] - 1))
print("turned_rad,time_to_turn_error,max_axis_deviation_deg,orbit_constant_start,orbit_constant_drift")
print(f"{phi_sim[0] - phi_sim[-1]:.4f},{took / took_jeffery - 1:.5f},{deviation:.3f},{C[0]:.5f},{drift:.5f}")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, ax = plt.subplots(1, 2, figsize=(10, 4))
ax[0].plot(t, phi_sim, "o", ms=3, label="fdparticle")
ax[0].plot(t, phi_j, "-", label="Jeffery (1922)")
ax[0].set_xlabel("t G")
ax[0].set_ylabel("azimuth of the axis in the x-y plane [rad]")
ax[1].plot(t, np.degrees(np.arccos(np.abs(p_sim[:, 2]))), "o", ms=3, label="fdparticle")
ax[1].plot(t, np.degrees(np.arccos(np.abs(p_j[:, 2]))), "-", label="Jeffery (1922)")
ax[1].set_xlabel("t G")
ax[1].set_ylabel("angle of the axis from the vorticity axis z [deg]")
for x in ax:
    x.legend()
    x.grid(alpha=0.3)
fig.suptitle(f"spheroid a/b = {r:g} in simple shear: Jeffery's orbit from t = {t_start:g}")
fig.tight_layout()
fig.savefig(png, dpi=90)
