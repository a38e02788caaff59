#!/usr/bin/env bash
# The include-rule check (.ci/check-includes) on a copy of the tree: it passes as the
# tree stands, and fails, naming the file, line, included file and rule, once a law
# (physics/drag.hpp) includes the scene and the gas (disk/gas_column.hpp) the I/O layer.
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp -r "$root/src" "$root/physics" "$root/disk" "$root/tests" "$tmp/"
mkdir "$tmp/.ci"
cp "$root/.ci/check-includes" "$tmp/.ci/"
/usr/bin/python3 "$tmp/.ci/check-includes" "$tmp" >/dev/null ||
  { echo "failed: the copy of the tree does not pass as it stands"; exit 1; }

echo '#include "src/scene/config.hpp"' >>"$tmp/physics/drag.hpp"
echo '#include "src/io/h5.hpp"' >>"$tmp/disk/gas_column.hpp"
law_line=$(wc -l <"$tmp/physics/drag.hpp")
disk_line=$(wc -l <"$tmp/disk/gas_column.hpp")
rc=0
out=$(/usr/bin/python3 "$tmp/.ci/check-includes" "$tmp") || rc=$?
echo "$out"
[ "$rc" -eq 1 ] || { echo "failed: exit code $rc, expected 1"; exit 1; }
for expected in \
  "physics/drag.hpp:$law_line: includes src/scene/config.hpp (layer scene): layer laws (physics/) may include only laws (physics/), core (src/core/), disk (disk/)" \
  "disk/gas_column.hpp:$disk_line: includes src/io/h5.hpp (layer io): layer disk (disk/) may include only disk (disk/), core (src/core/), solver (src/solver/)" \
  "check-includes: 2 include(s) against the layer table"; do
  grep -qF "$expected" <<<"$out" || { echo "failed: no line '$expected'"; exit 1; }
done
echo "planted violations found"
