#!/usr/bin/env bash
# The Python package's tests: a virtual environment made here, the package
# built into it by maturin (optimized: the sweep tests run 60 simulations),
# then pytest. .ci/run calls this after the cargo tests, whose `rover`
# executable the tests compare with.
#
#   python/ci.sh
set -euo pipefail
cd "$(dirname "$0")"
root="$(cd .. && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
export CARGO_TARGET_DIR="$target"
venv="${ROVER_PY_VENV:-$target/python-venv}"

if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
# shellcheck disable=SC1091
source "$venv/bin/activate"
python -m pip install --quiet --upgrade pip
# mcap and mcap-protobuf-support: the MCAP project's reader and protobuf
# decoder, which read a run's run.mcap back (tests/test_mcap.py); FMPy,
# the importer that validates and simulates an exported FMU
# (tests/test_fmu.py).
python -m pip install --quiet "maturin>=1.9,<2" pytest numpy pandas pyarrow ray gymnasium \
    "mcap==1.6.0" "mcap-protobuf-support==0.6.0" "fmpy==0.3.32"

maturin develop --release --locked

# The command line the Python runs are compared with: the one the cargo
# tests built, else a fresh build.
if [ -z "${ROVER_CLI:-}" ]; then
    if [ ! -x "$target/debug/rover" ]; then
        cargo build -p rover --locked
    fi
    export ROVER_CLI="$target/debug/rover"
fi
# The prebuilt plant library `rover export` packs into FMUs, beside the
# executable (the cargo tests build it too).
if [ ! -f "$(dirname "$ROVER_CLI")/librover_plant.so" ]; then
    cargo build -p rover-plant --locked --profile "$(basename "$(dirname "$ROVER_CLI")" | sed 's/^debug$/dev/')"
fi

# Ray's token authentication writes under $HOME; a local test cluster
# needs none.
export RAY_AUTH_MODE=disabled
python -m pytest -q tests "$@"
