#!/bin/sh
# Runs check_formats.py with the first Python 3 that has its readers: the
# Debian interpreter (/usr/bin/python3, where python3-nibabel, python3-vtk9 and
# python3-meshio install) before whatever python3 is first on PATH.
#   check_formats.sh check_formats.py DIR DEM
script=$1; dir=$2; dem=$3
for py in /usr/bin/python3 python3; do
  if command -v "$py" >/dev/null 2>&1 && "$py" -c "import numpy, nibabel, vtk, meshio" >/dev/null 2>&1; then
    exec "$py" "$script" "$dir" --dem "$dem"
  fi
done
echo "check_formats: skipped: no python3 with numpy, nibabel, vtk and meshio (Debian: python3-nibabel python3-vtk9 python3-meshio)"
exit 77
