#!/usr/bin/env bash
# Installs every build and test dependency from Debian 12 packages.
# Idempotent: packages already present are skipped by apt.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libsystemc-dev          # SystemC 2.3.4 + TLM-2.0 (pkg-config: systemc)
  zlib1g-dev              # zlib: the FST wave writer of the verilated models and of the RTL cache's entries
  libopencv-dev           # image I/O, rectification, reference matchers, plots
  libboost-test-dev       # Boost.Test (unit test framework)
  libcli11-dev            # command-line parsing
  nlohmann-json3-dev      # JSON reports
  python3                 # helper scripts (scripts/model-speed.sh)
  verilator               # the RTL design verilated into SystemC models (rtl_model/, 5.006)
  yosys                   # generic-gate synthesis of the PE and the CP (area figures, 0.23)
  nextpnr-ice40           # place and route on an iCE40 (scripts/rtl-pnr.sh, the design's Fmax; 0.4)
  fpga-icestorm           # the iCE40 chip database nextpnr-ice40 reads (and icepack / icetime)
  valgrind                # memcheck test of a TLM run (scripts/valgrind.sh, CTest valgrind.tlm_run)
  gnuplot-nox             # sweep plots (pngcairo and svg terminals; docs/whatif.md)
  fonts-dejavu-core       # a font for gnuplot's cairo terminals
  munge                   # Slurm authentication (the private test cluster runs its own munged)
  slurmctld slurmd        # Slurm 22.05 controller and node daemons (CTest engine.slurm, docs/cluster.md)
  slurm-client            # sbatch, squeue, scancel, sacct: the Slurm executor
  gtkwave xvfb xauth      # every generated view loaded in GTKWave, headless (CTest waves.gtkwave_views)
  lcov                    # genhtml / lcov of the RTL code coverage (scripts/rtl-coverage.sh)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
