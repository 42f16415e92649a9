"""Free sphere in simple shear, Stokes: omega_z = -gammadot/2 = -0.5 (Jeffery 1922)."""
import sys
from testlib import table, check, finish

last = table(sys.argv[1], "particles.csv")[-1]
check(abs(last["wz"] / -0.5 - 1) < 0.02, f"omega_z = {last['wz']:.6f} = -0.5 within 2 %")
check(abs(last["wx"]) < 1e-6 and abs(last["wy"]) < 1e-6,
      f"no spin about x, y: {last['wx']:.2e}, {last['wy']:.2e}")
v = max(abs(last[c]) for c in ("vx", "vy", "vz"))
check(v < 5e-4, f"the sphere at the centre stays (|V| = {v:.2e} < 1e-3 U): it has no reason to move")
finish()
