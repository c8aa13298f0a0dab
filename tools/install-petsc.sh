#!/bin/sh
# Install what the `petsc` feature needs on Debian or Ubuntu: PETSc 3.18 (real scalars, with
# Open MPI, MUMPS and hypre) and pkg-config, which the build uses to find it. The package lists
# are refreshed first: on a machine whose lists are stale, installing PETSc's dependencies
# fails with "held broken packages". Runs apt-get through sudo unless run as root.
set -eu
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
$sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    libpetsc-real3.18-dev pkg-config > /dev/null
echo "PETSc installed: build with  cargo build --release --features petsc"
