"""Free sphere in simple shear, Stokes: omega_z = -gammadot/2 = -0.5 (Jeffery 1922)."""
import sys
from testlib import table, check, finish

last = table(sys.argv[1], "particles.csv")[-1]
check(abs(last["wz"] / -0.5 - 1) < 0.02, f"omega_z = {last['wz']:.6f} = -0.5 within 2 %")
# The scene is its own mirror image in z and its own image under a half turn about z, so
# the discrete equations give omega_x = omega_y = 0 and V = 0 up to round-off; the bounds
# check that symmetry (measured 2e-16 |omega_z| and 7e-11 U; Delta t = 100 makes the
# system ill-conditioned, hence the looser velocity bound).
spin = max(abs(last["wx"]), abs(last["wy"]))
check(spin < 1e-10 * abs(last["wz"]), f"no spin about x, y: {spin:.2e} < 1e-10 |omega_z|")
v = max(abs(last[c]) for c in ("vx", "vy", "vz"))
check(v < 1e-8 * 0.5, f"the sphere at the centre stays (|V| = {v:.2e} < 1e-8 U)")
finish()
