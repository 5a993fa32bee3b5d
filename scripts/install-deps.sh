#!/usr/bin/env bash
# Installs the Debian packages moreau builds and tests with. Idempotent: only packages that are
# missing are installed, so running it on a ready machine costs a dpkg query and nothing else.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev        # dense/sparse linear algebra
  libsuitesparse-dev   # CHOLMOD/UMFPACK (FEM engine)
  petsc-dev            # the PETSc plugin: Krylov solvers, hypre's BoomerAMG, MUMPS, with Open MPI
  openmpi-bin          # mpirun: distributed FEM runs and their tests
  libmetis-dev         # METIS: partitions a FEM mesh among the MPI ranks of a distributed run
  libopenblas0-serial  # BLAS behind CHOLMOD's supernodal Cholesky: 3.8x faster factorizations than
                       # the reference BLAS on a 20^3 hex block; the serial build keeps results
                       # independent of the thread count (moreau's threads are its own, OpenMP)
  nlohmann-json3-dev   # scene files
  libcli11-dev         # command line
  libfmt-dev           # formatting
  libmuparser-dev      # time functions in boundary conditions
  libtinyobjloader-dev # OBJ meshes
  tetgen               # tetrahedralizing OBJ surfaces for soft bodies
  gmsh                 # meshing .geo files for FEM solids and fluids (the cylinder benchmark)
  libqhull-dev         # convex hulls of rigid bodies
  libccd-dev           # convex-convex contacts (Minkowski portal refinement)
  libboost1.81-dev     # Boost.PFR: checkpoints walk the state's structs field by field
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev libomp-14-dev  # make test-sanitize and make fuzz: ASan, UBSan, libFuzzer (clang 14)
  python3-numpy        # the Python module's arrays; bench/mpm_column_reference.py, the MPM reference of the XPBI sand column
  python3-dev pybind11-dev  # the Python module (python/)
  python3-pytest       # its tests
  python3-matplotlib   # its example (python/examples/drop_and_plot.py)
  blender              # tests/external: Blender imports and renders the OBJ and PLY frames
  libcpp-httplib-dev   # moreau view: serves an output directory to the browser
  chromium             # moreau render and the viewer's browser test (headless, software WebGL)
  ffmpeg               # moreau render --video
  paraview python3-paraview  # tests/external: ParaView's pvpython opens every .pvd the engine writes
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The viewer page is bundled with npm (viewer/package-lock.json). Node.js and npm usually come with
# the machine; Debian's packages stand in where they do not.
if ! command -v npm >/dev/null 2>&1; then
  missing+=(nodejs npm)
fi

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
