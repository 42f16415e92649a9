#!/usr/bin/env bash
# The scene of the 2D many-particle benchmarks (sourced by particle_count_2d.sh and
# cut_cell_weights_2d.sh): N disks (radius 0.04, density 1.1) placed at random, at least
# 0.02 apart, in a closed 2 x 2 box of fluid (density 1, μ = 0.1, g = 981), contacts by
# the repulsion, 4 steps of 0.005.
#
# settling_disks_prm N SUBDIVISIONS [TOP]
# prints the parameter file on SUBDIVISIONS² base cells; TOP (y) keeps the centres below it
# (default: the whole box). Sections that a benchmark adds follow it.
settling_disks_prm() {
  local n=$1 subdivisions=$2 top=${3:-}
  local sub_box=""
  [ -n "$top" ] && sub_box="    set Lower corner = 0, 0
    set Upper corner = 2, $top
"
  cat <<PRM
set Dimension = 2
set Gravity = 0, -981
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 2, 2
  set Subdivisions = $subdivisions, $subdivisions
end
subsection Fluid
  set Density = 1
  set Viscosity = 0.1
end
subsection Particles
  subsection Random particles
    set Count = $n
    set Radius = 0.04
    set Density = 1.1
    set Minimum gap = 0.02
    set Seed = 1
${sub_box}  end
end
subsection Collisions
  set Model = repulsion
end
subsection Time
  set End time = 0.02
  set Time step = 0.005
end
PRM
}
