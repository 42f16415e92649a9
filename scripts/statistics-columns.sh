#!/usr/bin/env bash
# Print the named columns of one row of a statistics.csv (or any CSV with a header),
# comma-separated: statistics-columns.sh FILE ROW NAME... with ROW a data row number
# (1 = the first step) or 'last'. Columns are found by name, so scripts do not depend on
# the order of the columns.
set -euo pipefail
file=$1 row=$2
shift 2
awk -F, -v row="$row" -v names="$*" '
  NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  row == "last" || NR - 1 == row { line = $0 }
  END {
    n = split(names, want, " "); split(line, f, ",")
    for (k = 1; k <= n; k++) {
      if (!(want[k] in col)) { print "no column " want[k] > "/dev/stderr"; exit 1 }
      printf "%s%s", (k > 1 ? "," : ""), f[col[want[k]]]
    }
    print ""
  }' "$file"
