#!/usr/bin/env bash
# Installs every build, test and workflow dependency of finverse from Debian 12 packages.
# Idempotent: apt-get skips what is already there. Nothing is downloaded outside apt.
#
#   tools/scripts/install-deps.sh            build + workflow + tests
#   tools/scripts/install-deps.sh --peers    also the benchmark peers (OpenFOAM, CalculiX, hypre)
#
# Why each package beyond the expected set (Eigen, OpenCV, CGAL, VTK, HDF5, Snakemake, pagmo2,
# CLI11, GoogleTest, h5py, matplotlib):
#   nlohmann-json3-dev   JSON for the provenance `config` attribute and summary.json; a complete,
#                        tested parser/serialiser is better than a hand-written one.
#   libsuitesparse-dev   CHOLMOD sparse Cholesky for the FEM (DESIGN.md 5.2), faster than Eigen's.
#   libyaml-cpp-dev      the case files of `fin-cfd run CASE.yaml` (YAML like config/); a complete YAML 1.2
#                        parser with line numbers for errors beats a hand-written subset.
#   python3-jsonschema   Snakemake's config validation against config/config.schema.yaml.
#   python3-numpy        array handling in the plotting and summary helpers.
#   python3-scipy        Qhull's Delaunay triangulation for the flap phantom's floor
#                        (hessenthaler_junction_stl.py): robust where a hand-written one is not.
#   ninja-build          faster incremental builds than make (optional; CMake falls back to make).
#   clang, libclang-rt-14-dev  the sanitized test build (test-all.sh; the runtime is only a
#                        recommendation of clang): clang compiles that build in about
#                        0.65 of GCC's time, which keeps CI under its 40 minutes (build_time.md).
#   slurm-wlm            SLURM's daemons and commands for ctest workflow_slurm: the workflow through
#                        profiles/slurm on a one-node cluster the test starts itself (issue 48).
#   libopenmpi-dev, openmpi-bin  MPI for fin-fit run's evaluations across ranks (issue 48): the
#                        engine a cluster already has, not a scheduler of ours; mpirun for its test.
set -euo pipefail

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

pkgs=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libeigen3-dev libopencv-dev libcgal-dev libvtk9-dev libhdf5-dev
  libpagmo-dev libcli11-dev libgtest-dev libgmock-dev nlohmann-json3-dev libsuitesparse-dev libyaml-cpp-dev
  clang libclang-rt-14-dev libomp-dev libopenmpi-dev openmpi-bin
  snakemake slurm-wlm python3-jsonschema python3-yaml python3-numpy python3-scipy python3-h5py python3-matplotlib
)
peers=(openfoam calculix-ccx libhypre-dev)

want=("${pkgs[@]}")
if [ "${1:-}" = "--peers" ]; then want+=("${peers[@]}"); fi

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#want[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
