#!/usr/bin/env bash
# The Python package's tests: builds the wheel with the README's install command
# (`pip install ./python`) into a fresh virtual environment, then runs python/tests with pytest.
# The wheel is built by maturin into the workspace's target dir in the release profile, so it
# reuses what `cargo test --release --workspace` compiled (only pyo3 and the module itself build).
#
# HATCHERY_PYTHON_VENV: where the environment goes (default target/python-venv; it is made anew
# each run so that the install is tested as a new user would run it).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${HATCHERY_PYTHON_VENV:-target/python-venv}
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q --disable-pip-version-check --upgrade pip
echo "python-tests: pip install ./python (builds the wheel with maturin)"
"$venv/bin/python" -m pip install -q --disable-pip-version-check "./python[test,widget]"
"$venv/bin/python" -c "import hatchery; print('python-tests: imported hatchery; adapter:', hatchery.adapter())"
# The tests compare with the command line; build it if the Rust tests did not.
[ -x target/release/hatchery ] || cargo build --release --bin hatchery
HATCHERY_BIN=target/release/hatchery "$venv/bin/python" -m pytest -q -p no:cacheprovider \
    --rootdir python python/tests "$@"
