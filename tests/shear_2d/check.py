"""Free disk in simple shear, Stokes: omega_z = -gammadot/2 = -0.5 (a torque-free cylinder
turns with the fluid's rotation rate; doc/references/README.md, Stokes limit)."""
import sys
from testlib import table, check, finish

last = table(sys.argv[1], "particles.csv")[-1]
check(abs(last["wz"] / -0.5 - 1) < 0.02, f"omega_z = {last['wz']:.6f} = -0.5 within 2 %")
# The scene is its own image under a half turn, so V = 0 up to round-off: the bound
# checks that symmetry of the discrete equations (measured 2e-10 U; Delta t = 100 makes
# the system ill-conditioned).
v = max(abs(last[c]) for c in ("vx", "vy"))
check(v < 1e-8 * 0.5, f"the disk at the centre stays (|V| = {v:.2e} < 1e-8 U)")
finish()
