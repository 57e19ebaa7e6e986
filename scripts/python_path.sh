#!/usr/bin/env bash
# Makes `/usr/bin/python3 -c "import dynmesh"` find the module in MODULE_DIR without PYTHONPATH:
# writes dynmesh.pth naming MODULE_DIR into the user site directory of /usr/bin/python3
# (PYTHONUSERBASE moves that directory). Run by scripts/setup.sh for build/release/python; the
# last run wins. usage: scripts/python_path.sh MODULE_DIR
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: $0 MODULE_DIR" >&2; exit 2; }
module_dir="$(cd "$1" && pwd)"
site_dir="$(/usr/bin/python3 -c 'import site; print(site.getusersitepackages() if site.ENABLE_USER_SITE else "")')"
if [ -z "$site_dir" ]; then
    echo "python_path: the user site directory of /usr/bin/python3 is disabled; use PYTHONPATH=$module_dir"
    exit 0
fi
mkdir -p "$site_dir"
printf '%s\n' "$module_dir" > "$site_dir/dynmesh.pth.tmp"
mv "$site_dir/dynmesh.pth.tmp" "$site_dir/dynmesh.pth"
echo "python_path: /usr/bin/python3 imports dynmesh from $module_dir (via $site_dir/dynmesh.pth)"
