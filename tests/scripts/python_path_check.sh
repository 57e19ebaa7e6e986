#!/usr/bin/env bash
# scripts/python_path.sh (what scripts/setup.sh runs) makes /usr/bin/python3 import the module
# of MODULE_DIR without PYTHONPATH: run against a private user base (PYTHONUSERBASE), then
# imported from a directory that is not the module's.
# usage: python_path_check.sh SCRIPT MODULE_DIR
set -euo pipefail
script="$1" module_dir="$2"
base="$(mktemp -d)"
trap 'rm -rf "$base"' EXIT
PYTHONUSERBASE="$base" bash "$script" "$module_dir"
cd "$base"
PYTHONUSERBASE="$base" env -u PYTHONPATH /usr/bin/python3 -c '
import os, sys
import dynmesh
found = os.path.realpath(os.path.dirname(dynmesh.__file__))
print("dynmesh", dynmesh.__version__, "from", found)
sys.exit(found != os.path.realpath(sys.argv[1]))' "$module_dir"
