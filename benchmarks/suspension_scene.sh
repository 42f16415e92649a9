#!/usr/bin/env bash
# The scene of the suspension benchmarks (sourced by suspension_3d.sh and
# suspension_time_3d.sh): N equal spheres (radius 0.5, density 2) placed at random with a
# gap of at least d/4 in a triply periodic cube of fluid (density 1, μ = 10⁴, g = 1),
# Stokes flow, level-set cut cells, uniform mesh. A uniform body force
# f = −(ρ_f + φ Δρ) g balances the weight of fluid and spheres: a periodic box has no
# bottom, and without it the whole box would accelerate.
#
# suspension_prm N BOX CELLS SEED SOLVER DT END SCHEME DIRECTORY [SECTIONS [GAP]]
# prints the parameter file; SECTIONS (text) is added before the Quadrature subsection;
# GAP is the minimum gap of the placement (default 0.25 = d/4).
suspension_prm() {
  local n=$1 box=$2 cells=$3 seed=$4 solver=$5 dt=$6 end=$7 scheme=$8 directory=$9
  local sections="${10:-}" gap="${11:-0.25}"
  local force
  force=$(/usr/bin/python3 -c "import math; print(repr(1 + $n * 4 / 3 * math.pi * 0.125 / $box ** 3))")
  cat <<PRM
set Dimension = 3
set Gravity   = 0, 0, -1
subsection Geometry
  set Lower corner        = 0, 0, 0
  set Upper corner        = $box, $box, $box
  set Subdivisions        = $cells, $cells, $cells
  set Periodic directions = x, y, z
end
subsection Fluid
  set Density    = 1
  set Viscosity  = 10000
  set Convection = false
  set Body force = 0, 0, $force
end
subsection Particles
  subsection Random particles
    set Count       = $n
    set Radius      = 0.5
    set Density     = 2
    set Minimum gap = $gap
    set Seed        = $seed
  end
end
${sections}subsection Quadrature
  set Cut cells = level set
end
subsection Solver
  set Linear solver = $solver
end
subsection Time
  set Time step = $dt
  set End time  = $end
  set Scheme    = $scheme
end
subsection Output
  set Directory    = $directory
  set VTU interval = 0
end
PRM
}
