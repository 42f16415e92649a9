"""The numbers a scene's header comment states, read back from a run of that scene (a test
prm that includes it): each claim TIME:COLUMN:VALUE:TOLERANCE asks that particle 0's
COLUMN in particles.csv at TIME is within TOLERANCE of VALUE, the digits the comment gives.
Usage: scene_claims.py OUTPUT_DIR CLAIM [CLAIM ...]"""
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "particles.csv")
for claim in sys.argv[2:]:
    time, column, value, tolerance = claim.split(":")
    at = [r for r in rows if r["id"] == 0 and abs(r["time"] - float(time)) < 1e-9]
    if check(len(at) == 1, f"particle 0 has a row at t = {time}"):
        got = at[0][column]
        check(abs(got - float(value)) <= float(tolerance),
              f"{column}(t = {time}) = {got:.6g}, the comment says {value} (within {tolerance})")
finish()
