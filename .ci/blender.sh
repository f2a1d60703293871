#!/usr/bin/env bash
# Installs Debian's Blender for the Blender round trip (tests/blender.rs), if missing.
# The test skips with a note when Blender is absent, so a machine without apt still runs
# the rest of the suite.
set -euo pipefail
# The add-on (contrib/blender/seasynth_addon) needs Blender's numpy: Debian's python3-numpy.
if command -v blender >/dev/null 2>&1 && dpkg -s python3-numpy >/dev/null 2>&1; then
  exit 0
fi
if command -v apt-get >/dev/null 2>&1; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends blender python3-numpy
else
  echo "note: no apt-get: Blender is not installed and tests/blender.rs will skip" >&2
fi
