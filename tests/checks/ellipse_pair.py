"""Two ellipses meeting in the fluid (tests/ellipse_pair_2d.prm).

A heavy ellipse A (rho 1.8, turned 45 degrees) settles onto a light one B (rho 0.2, flat)
that rises below it; the repulsion acts at the true gap of the two shapes (doc/method.md
§13). What is checked:

- no overlap: statistics.csv's min_gap (the true gap) stays positive, and the contact
  force acts exactly while the gap is below the range h (the finest cell);
- the force pushes the centres apart, F_A . (X_A - X_B) > 0;
- momentum: the contact forces on A and B are equal and opposite (Newton's third law);
- angular momentum: the force acts at the contact points p_A, p_B, which lie gap * n
  apart along it, so the contact torques satisfy
  T_A + T_B + (X_A - X_B) x F_A = (p_A - p_B) x F_A = 0. The contact torque of a particle
  is what its torque balance ((F5), doc/method.md §0) leaves besides the hydrodynamic
  torque T of particles.csv (§9): T_c = rho_P J dw/dt - T, J = |P| (a^2 + b^2) / 4 (§13),
  dw/dt by the step's BDF formula (§2) from the w column;
- the contact turns the ellipses: A meets B's top with its lower left side, left of both
  centres, so while the force grows to its largest value the push turns A clockwise and
  B anticlockwise, their long axes toward each other, with a lever |T_c| / |F| between
  b/5 and a (the arm ends on the surface), and A's angular velocity changes faster
  clockwise at the largest force than in the last step before the contact;
- the pair separates: the sideways push sends A to the left of B, A (heavier than the
  fluid) slides down past B (lighter) and the contact ends before the run does, the gap
  then growing.
"""
import math
import sys
from testlib import table, check, finish, parameters

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
stats = table(out, "statistics.csv")
a, b = 0.2, 0.1
J = math.pi * a * b * (a * a + b * b) / 4  # J / rho of the ellipse
levels = int(prm["Refinement/Particle refinement levels"])
h = 0.125 / 2 ** levels  # base cells of 0.125
rho = {0: 1.8, 1: 0.2}
A = [r for r in rows if r["id"] == 0]
B = [r for r in rows if r["id"] == 1]
scheme = prm["Time/Scheme"]


def angular_acceleration(history, n):
    """dw/dt at row n (n >= 1) by the BDF formula of step n: BDF1 for the first step (and
    every step with Scheme = BDF1), else BDF2 with k = dt_n / dt_(n-1)."""
    dt = history[n]["time"] - history[n - 1]["time"]
    if n == 1 or scheme == "BDF1":
        return (history[n]["wz"] - history[n - 1]["wz"]) / dt
    k = dt / (history[n - 1]["time"] - history[n - 2]["time"])
    return ((1 + 2 * k) / ((1 + k) * dt) * history[n]["wz"] - (1 + k) / dt * history[n - 1]["wz"]
            + k * k / ((1 + k) * dt) * history[n - 2]["wz"])


def contact_torque(history, n, density):
    return density * J * angular_acceleration(history, n) - history[n]["tz"]


def force(n):
    return math.hypot(A[n]["contact_fx"], A[n]["contact_fy"])


check(len(A) == len(B) == len(stats) + 1, f"{len(stats)} steps of two ellipses")
check(all(s["time_step_reductions"] == 0 for s in stats), "no step was retried")
check(min(s["min_gap"] for s in stats) > 0,
      f"no overlap: smallest gap {min(s['min_gap'] for s in stats):.5f} > 0")
touching = [n for n in range(1, len(A)) if force(n) != 0]
check(len(touching) >= 5, f"a contact of {len(touching)} steps")
if not touching:
    finish()
check(all((stats[n - 1]["min_gap"] < h) == (n in touching) for n in range(1, len(A))),
      f"a contact force exactly while the gap is below the range h = {h}")
scale = max(force(n) for n in touching)
check(all(abs(A[n]["contact_f" + c] + B[n]["contact_f" + c]) <= 1e-12 * scale
          for n in touching for c in "xy"),
      "the contact forces on A and B are equal and opposite")
check(all(A[n]["contact_fx"] * (A[n]["x"] - B[n]["x"]) +
          A[n]["contact_fy"] * (A[n]["y"] - B[n]["y"]) > 0 for n in touching),
      "the contact force pushes the centres apart")

worst = 0.0
for n in touching:
    TA, TB = contact_torque(A, n, rho[0]), contact_torque(B, n, rho[1])
    dx, dy = A[n]["x"] - B[n]["x"], A[n]["y"] - B[n]["y"]
    worst = max(worst, abs(TA + TB + dx * A[n]["contact_fy"] - dy * A[n]["contact_fx"]) / (scale * a))
check(worst < 1e-6,
      f"angular momentum: T_c,A + T_c,B + (X_A - X_B) x F_A = 0 to {worst:.1e} of |F| a (1e-6)")

first = touching[0]
strongest = max(touching, key=force)
impact = [n for n in touching if n <= strongest]
lever_A = [-contact_torque(A, n, rho[0]) / force(n) for n in impact]
lever_B = [contact_torque(B, n, rho[1]) / force(n) for n in impact]
check(all(0.2 * b < lever <= a for lever in lever_A + lever_B),
      f"up to the largest force (t = {A[strongest]['time']:g}) the contact turns A clockwise "
      f"and B anticlockwise, levers {min(lever_A + lever_B):.4f} to {max(lever_A + lever_B):.4f} "
      f"in (b/5, a]")
before = A[first - 1]["wz"] - A[first - 2]["wz"]
at = A[strongest]["wz"] - A[strongest - 1]["wz"]
check(at < min(before, 0),
      f"A's angular velocity changes by {at:.4f} in the step of the largest force, "
      f"{before:.4f} in the last step before the contact")

last = touching[-1]
check(A[last]["x"] < B[last]["x"] and A[last]["vx"] < B[last]["vx"],
      f"at the end of the contact A is left of B and moves left of it "
      f"(vx {A[last]['vx']:.4f} and {B[last]['vx']:.4f})")
check(last < len(A) - 2 and stats[-1]["min_gap"] > stats[last]["min_gap"] >= h and
      A[-1]["vy"] < 0 < B[-1]["vy"],
      f"the pair separates: the contact ends at t = {A[last + 1]['time']:g}, "
      f"the gap grows to {stats[-1]['min_gap']:.4f} with A sinking past B")
finish()
