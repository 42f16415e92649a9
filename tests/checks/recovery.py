"""Recovery by halving the time step (tests/recovery_2d.prm).

The first step fails at dt = 0.5 (2 Newton iterations allowed) and is retried with halved
steps; afterwards dt doubles back to 0.5. The settling velocity at t = 4 must agree with
the run without the iteration limit (same prm with 'Max nonlinear iterations = 20':
vy(4) = -0.0121749 on this 8 x 16 mesh) to 2 %: the detour through small steps must not
change the answer beyond the time-discretisation error (on this coarse mesh, R/h = 1.6, the
settling velocity moves by about 1 % between dt = 0.25 and 0.5: doc/method.md)."""
import sys
from testlib import table, check, finish

out = sys.argv[1]
stats = table(out, "statistics.csv")
first = stats[0]
check(first["time_step_reductions"] >= 1,
      f"step 1 was retried with a smaller step ({int(first['time_step_reductions'])} halvings)")
check(abs(first["dt"] - 0.5 / 2 ** first["time_step_reductions"]) < 1e-12,
      f"step 1 used dt = 0.5 / 2^{int(first['time_step_reductions'])} = {first['dt']}")
body = stats[:-2]  # the last two steps share the remainder to land on t = 4
for a, b in zip(body, body[1:]):
    if a["dt"] < 0.5 - 1e-12 and b["time_step_reductions"] == 0:
        check(abs(b["dt"] - min(0.5, 2 * a["dt"])) < 1e-12,
              f"step {int(b['step'])}: dt grows back, {a['dt']} -> {b['dt']}")
check(abs(body[-1]["dt"] - 0.5) < 1e-12, "the steps before the last two run at the requested dt = 0.5")
check(abs(stats[-1]["dt"] - stats[-2]["dt"]) < 1e-12, "the last two steps share the remainder")
check(abs(stats[-1]["time"] - 4) < 1e-12, "the run reaches t = 4")
check(all(r["nonlinear_iterations"] <= 2 for r in stats), "no step used more than 2 iterations")
vy = [r["vy"] for r in table(out, "particles.csv")][-1]
reference = -0.0121749
check(abs(vy - reference) <= 2e-2 * abs(reference),
      f"vy(4) = {vy:.7f} vs {reference} without the iteration limit (2 %)")
finish()
