#!/usr/bin/env bash
# The documentation command: installs doxygen and Debian's MathJax (libjs-mathjax)
# when missing, writes the reference and user manual to build/doc/index.html and
# fails on any Doxygen warning (WARN_AS_ERROR = FAIL_ON_WARNINGS in the Doxyfile).
# The pages work offline: MathJax is copied beside them (MATHJAX_RELPATH = mathjax).
#   bash scripts/build_docs.sh
#   DEM_BUILD_DIR=/tmp/b bash scripts/build_docs.sh     # writes /tmp/b/doc
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
MATHJAX_DIR="${DEM_MATHJAX_DIR:-/usr/share/javascript/mathjax}"

bash "$ROOT/scripts/install_packages.sh" doxygen libjs-mathjax

HTML="$BUILD_DIR/doc"
rm -rf "$HTML"
mkdir -p "$BUILD_DIR"
cd "$ROOT"   # the Doxyfile's paths are relative to the repository root
# Doxygen prints each warning and exits non-zero when there was one.
{ cat doc/Density_equalizing_maps/Doxyfile; echo "OUTPUT_DIRECTORY = $BUILD_DIR"; } | doxygen -

if [[ ! -f "$MATHJAX_DIR/MathJax.js" ]]; then
  echo "build_docs: no MathJax at $MATHJAX_DIR (install libjs-mathjax): formulas would not render" >&2
  exit 1
fi
# Only what the pages load (the TeX input, the HTML-CSS output and its fonts, the
# extensions and configurations); not the unpacked sources, tests and translations.
mkdir -p "$HTML/mathjax"
cp -rL "$MATHJAX_DIR/MathJax.js" "$MATHJAX_DIR/config" "$MATHJAX_DIR/extensions" \
       "$MATHJAX_DIR/jax" "$MATHJAX_DIR/fonts" "$HTML/mathjax/"
if grep -lE 'src="https?://[^"]*[Mm]ath[Jj]ax' "$HTML"/*.html; then
  echo "build_docs: the pages above load MathJax from the network" >&2
  exit 1
fi
echo "build_docs: $(ls "$HTML"/*.html | wc -l) pages in $HTML (index.html), 0 Doxygen warnings, MathJax local"
