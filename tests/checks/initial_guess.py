"""Newton's initial guess (doc/method.md §5; tests/initial_guess_2d.prm).

OUTPUT_DIR is the run with 'Initial guess = extrapolated'; OUTPUT_DIR-variant (written by
the scene's test-variant) the same scene started from the last step's state. In a flow that
develops smoothly, the extrapolation u^n + w (u^n - u^{n-1}) is closer to u^{n+1} than
u^n by a factor of order dt. Checks:
- every step of order 2 started from the state with the smaller residual: its initial
  residual is at most the last-step run's (the two runs' u^n differ by the nonlinear
  tolerance only);
- the extrapolated state won in most of those steps, and
- the run needed at least a tenth fewer Newton iterations in all than the one from the
  last step (at dt = 0.02 about a fifth fewer)."""
import sys
from testlib import table, check, finish

out = sys.argv[1]
extrapolated = table(out, "statistics.csv")
last_step = table(out + "-variant", "statistics.csv")
check(len(extrapolated) == len(last_step) >= 10, f"both runs took the same {len(extrapolated)} steps")
check(all(r["extrapolated_start"] == 0 for r in last_step),
      "'Initial guess = last step' never starts from the extrapolated state")
check(extrapolated[0]["extrapolated_start"] == 0, "the first step (BDF1) starts from the last step")
later = list(zip(extrapolated, last_step))[1:]
for e, l in later:
    check(e["initial_residual"] <= l["initial_residual"] * (1 + 1e-6) + 1e-12,
          f"step {int(e['step'])}: started from the smaller residual "
          f"({e['initial_residual']:.3e}, from the last step {l['initial_residual']:.3e})")
wins = sum(int(e["extrapolated_start"]) for e, _ in later)
check(wins >= len(later) / 2, f"the extrapolated state won in {wins} of {len(later)} steps")
n_e = sum(int(r["nonlinear_iterations"]) for r in extrapolated)
n_l = sum(int(r["nonlinear_iterations"]) for r in last_step)
check(n_e <= 0.9 * n_l, f"{n_e} Newton iterations from the extrapolated state, {n_l} from the last step")
finish()
