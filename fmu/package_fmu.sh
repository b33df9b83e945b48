#!/usr/bin/env bash
# package_fmu.sh STAGE MD_TOOL OUT.fmu -- write STAGE/modelDescription.xml with
# MD_TOOL, then zip it with STAGE/binaries/linux64/rt_bushing.so into OUT.fmu
# (FMI 2.0 section 2.3 layout). Reproducible: fixed file order and timestamps,
# no extra attributes (zip -X), no directory entries (-D). Written to a
# temporary name and renamed, so a failed run leaves no partial FMU.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 STAGE MD_TOOL OUT.fmu" >&2
  exit 2
fi
stage=$1 md=$2 out=$3
files=(modelDescription.xml binaries/linux64/rt_bushing.so)
"$md" "$stage/modelDescription.xml"
# Zip copies with fixed timestamps, so the build outputs keep theirs (and
# are not relinked on the next build).
outdir=$(cd "$(dirname "$out")" && pwd)
pack="$outdir/.$(basename "$out").pack.$$"
tmp="$outdir/.$(basename "$out").tmp.$$"
rm -rf "$pack" "$tmp"
trap 'rm -rf "$pack" "$tmp"' EXIT
for f in "${files[@]}"; do
  [ -f "$stage/$f" ] || { echo "package_fmu: missing $stage/$f" >&2; exit 1; }
  mkdir -p "$pack/$(dirname "$f")"
  cp "$stage/$f" "$pack/$f"
  TZ=UTC touch -d '1980-01-02 00:00:00' "$pack/$f"
done
(cd "$pack" && TZ=UTC zip -X -D -q -9 "$tmp" "${files[@]}")
mv -f "$tmp" "$out"
