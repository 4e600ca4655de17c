# The table of bench/side_by_side.sh: one row per figure of bench/speed_targets.sh, one column
# per side (old, new), each cell listing the rounds' values in order. Input: the script's log,
# every run headed by a line "#### SIDE ROUND TIME".
/^#### / { side = $2; next }
function add(figure, value) {
  if (!(figure in seen)) { seen[figure] = 1; order[++n] = figure }
  cell[figure, side] = cell[figure, side] (cell[figure, side] == "" ? "" : ", ") value
}
/^delaunay\/1M\/threads:2: wall/ { add("Delaunay 1M, 2 threads, wall (s; target 5)", $3) }
/^dey_zhao\/1M\/iterations/ {
  for (i = 1; i <= NF; ++i) if ($i ~ /^s_total=/) { sub("s_total=", "", $i); add("Dey-Zhao 1M total (s; target 8)", sprintf("%.2f", $i)) }
}
/^dey_zhao\/1M:/ { for (i = 1; i <= NF; ++i) if ($i == "fnv1a") add("Dey-Zhao 1M output hash", $(i + 1)) }
/^poisson\/1M\/threads:2: wall/ { add("Poisson 1M, uniform candidates, wall (s; target 5)", $3) }
/^poisson_darts\/1M\/threads:2: wall/ { add("Poisson 1M, darts, wall (s; target 5)", $3) }
/^poisson(_darts)?\/1M\/threads:2: wall/ { for (i = 1; i <= NF; ++i) if ($i == "hash") add("Poisson 1M hashes (uniform, darts)", $(i + 1)) }
/^reconstruction / { add("quickstart reconstruction, min / median (s; target 0.6)", $2 " / " $3) }
/^BM_QmatSimplify\/[0-9]+\/0\// { add("Q-MAT, one thread, " model() " (paper " paper() " s)", $2 " " $3) }
/^BM_CoverageAxisExact\// { add("Coverage Axis exact, " model() " (paper " paper() " s)", $2 " " $3) }
function model(   i) {
  for (i = NF; i > 0; --i) if ($i ~ /\.(off|obj|ply)$/) return $i
  return "?"
}
function paper(   i, f) {
  for (i = 1; i <= NF; ++i) if ($i ~ /^paper_s=/) { f = $i; sub("paper_s=", "", f); return f }
  return "?"
}
END {
  print "| figure | old | new |"
  print "|---|---|---|"
  for (i = 1; i <= n; ++i) print "| " order[i] " | " cell[order[i], "old"] " | " cell[order[i], "new"] " |"
}
