"""An ellipse turning freely in simple shear (tests/jeffery_ellipse_2d.prm).

Jeffery's orbit in the plane (Jeffery, Proc. R. Soc. A 102 (1922) 161; for the ellipse
e.g. Zettner & Yoda, J. Fluid Mech. 442 (2001) 241): an ellipse of semi-axes a, b whose
a axis makes the angle theta with the flow, in the shear u = G y e_x at zero Reynolds
number, turns at

    dtheta/dt = -G (a^2 sin^2 theta + b^2 cos^2 theta) / (a^2 + b^2),

with period T = 2 pi (a^2 + b^2) / (G a b): slowest along the flow (-G b^2/(a^2 + b^2)),
fastest across it (-G a^2/(a^2 + b^2)). Checked once the shear has developed (t >= 1):
the angular velocity against the formula at the ellipse's angle (5 %: it wobbles by 1-2 %
as the refined band moves with the ellipse), the fastest rate, and the time it takes to
turn from its angle at t = 1 to the last one against the time the formula gives (3 %).
The walls (2a/H = 0.2) and the small Reynolds number (G a^2 rho/mu = 0.04) slow it: in a
box twice as large and the same cells near the ellipse the turning time is 0.6 % longer
than Jeffery's instead of 1.8 %."""
import math
import sys
from testlib import table, check, finish, parameters

out = sys.argv[1]
prm = parameters(out)
shape = prm["Particles/Particles"].split(":")[1].split(None, 1)  # 'ellipse a, b[, angle]'
a, b = (float(v) for v in shape[1].split(",")[:2])
lower = [float(v) for v in prm["Geometry/Lower corner"].split(",")]
upper = [float(v) for v in prm["Geometry/Upper corner"].split(",")]
walls = {k.strip(): float(v.split(",")[0])
         for k, v in (entry.split(":") for entry in prm["Boundary conditions/Wall velocities"].split(";"))}
G = (walls["y+"] - walls["y-"]) / (upper[1] - lower[1])

rows = [r for r in table(out, "particles.csv")]
theta, t = [], []
for r in rows:
    angle = r["rotz"]
    if theta:  # unwrap: the rotation angle lies in (-pi, pi]
        while angle - theta[-1] > math.pi:
            angle -= 2 * math.pi
        while angle - theta[-1] < -math.pi:
            angle += 2 * math.pi
    theta.append(angle)
    t.append(r["time"])


def rate(th):
    return -G * (a * a * math.sin(th) ** 2 + b * b * math.cos(th) ** 2) / (a * a + b * b)


def phase(th):
    """Time from theta = 0 to th by the formula (th <= 0, turning clockwise)."""
    k = G * a * b / (a * a + b * b)
    # tan(theta) = -(b/a) tan(k t): t = atan(-(a/b) tan theta)/k on each half turn.
    turns = math.floor((-th + math.pi / 2) / math.pi)
    inner = th + turns * math.pi
    return (math.atan(-(a / b) * math.tan(inner)) + turns * math.pi) / k


developed = [i for i, time in enumerate(t) if time >= 1.0]
worst = max(abs(rows[i]["wz"] - rate(theta[i])) / abs(rate(theta[i])) for i in developed)
check(worst < 0.05, f"angular velocity within 5 % of Jeffery's at the ellipse's angle "
                    f"(worst {100 * worst:.2f} %, t >= 1)")
fastest = max(-rows[i]["wz"] for i in developed)
across = G * a * a / (a * a + b * b)
check(abs(fastest / across - 1) < 0.03,
      f"fastest turn {fastest:.4f} against Jeffery's G a^2/(a^2 + b^2) = {across:.4f} "
      f"({100 * (fastest / across - 1):+.2f} %, 3 % allowed)")
first, last = developed[0], developed[-1]
turned = theta[first] - theta[last]
check(turned > math.pi / 2, f"the ellipse turns more than a quarter turn ({turned:.3f} rad)")
expected = phase(theta[last]) - phase(theta[first])
took = t[last] - t[first]
check(abs(took / expected - 1) < 0.03,
      f"time to turn from {theta[first]:.3f} to {theta[last]:.3f} rad: {took:.3f} against "
      f"Jeffery's {expected:.3f} ({100 * (took / expected - 1):+.2f} %, 3 % allowed)")
finish()
