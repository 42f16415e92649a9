# The 3D scenes of the scaling benchmarks (benchmarks/scaling.sh, strong_scaling.sh), as
# parameter text on stdout; sourced, with $top the repository.
#  - sediment n: the seed's sediment scene (box 1 x 2 x 1, sphere R = 0.2, rho_P = 1.5,
#    mu = 1), Subdivisions n x 2n x n, one BDF1 Stokes step of 0.1;
#  - array n: prm/validation/array3d.prm (a fixed sphere in a periodic cube, c = 0.064,
#    dt = 100: steady Stokes), Subdivisions n x n x n, no particle refinement;
#  - adaptive_levelset: the settings appended to a scene for the adaptive runs of
#    doc/smoothness.md (variant adaptls): level-set cut cells, 2 particle refinement levels.

sediment() { # n
  printf 'set Dimension = 3\nset Gravity = 0, -10, 0\n'
  printf 'subsection Geometry\n  set Lower corner = -0.5, -0.5, -0.5\n'
  printf '  set Upper corner = 0.5, 1.5, 0.5\n  set Subdivisions = %s, %s, %s\nend\n' "$1" $((2 * $1)) "$1"
  printf 'subsection Fluid\n  set Convection = false\nend\n'
  printf 'subsection Particles\n  set Particles = 0, 1, 0 : 0.2 : 1.5\nend\n'
  printf 'subsection Time\n  set End time = 0.1\n  set Time step = 0.1\nend\n'
}

array() { # n
  sed "s/^  set Subdivisions .*/  set Subdivisions = $1, $1, $1/;
       s/^  set Particle refinement levels .*/  set Particle refinement levels = 0/" \
    "$top/prm/validation/array3d.prm"
}

adaptive_levelset() {
  printf 'subsection Quadrature\n  set Cut cells = level set\nend\n'
  printf 'subsection Refinement\n  set Particle refinement levels = 2\nend\n'
}
