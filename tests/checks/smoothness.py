"""The smoothness figure S of a run stays below a stored bound (S is defined in
doc/method.md, "Smoothness measure"). Usage: smoothness.py OUTPUT_DIR BOUND MIN_SAMPLES"""
import sys
from testlib import table, check, finish

bound, samples = float(sys.argv[2]), int(sys.argv[3])
rows = table(sys.argv[1], "smoothness.csv")
check(len(rows) == 1 and rows[0]["samples"] >= samples, f"one particle, at least {samples} steps recorded")
check(rows[0]["smoothness"] < bound, f"S = {rows[0]['smoothness']:.5f} < {bound}")
check(rows[0]["smoothness"] > 0, "S is computed (non-zero)")
finish()
