#!/usr/bin/env bash
# Fetches Mesa 25 lavapipe (mesa-vulkan-drivers with its libdrm2 and libdrm-amdgpu1) from Debian
# bookworm-backports and unpacks it into a folder, as a second Vulkan driver for tests and
# benchmarks. It is never a renderer path and is never installed system-wide: apt-get only
# downloads, through a private sources list and private apt state, and dpkg -x only unpacks.
#
# Usage:
#   scripts/mesa25-lavapipe.sh build/mesa25 && . build/mesa25/env.sh && ctest ...
# The folder defaults to build/mesa25. Safe to run again: once the folder holds the driver,
# it only prints the env lines. env.sh sets VK_DRIVER_FILES (this lavapipe only) and
# LD_LIBRARY_PATH (its libdrm first). LP_NATIVE_VECTOR_WIDTH=128 gives subgroup size 4
# (the default on AVX2 machines is 8).
set -Eeuo pipefail

me=mesa25-lavapipe
die() { echo "$me: error: $*" >&2; exit 1; }
trap 'die "command failed (line $LINENO): $BASH_COMMAND"' ERR

suite=bookworm-backports
packages=(mesa-vulkan-drivers libdrm2 libdrm-amdgpu1)

out=${1:-build/mesa25}
case $out in *[\'\"\\\|\&]* | *$'\n'*) die "folder name must not contain quotes, backslashes, '|', '&' or newlines: $out" ;; esac
mkdir -p "$out" || die "cannot create $out"
out=$(cd "$out" && pwd -P)

arch=$(uname -m)
icd_dir=$out/usr/share/vulkan/icd.d
icd=$icd_dir/lvp_icd.$arch.json
env_sh=$out/env.sh

write_env() {
  local lib=$1
  cat >"$env_sh" <<EOF
# Mesa 25 lavapipe from $suite, unpacked by scripts/mesa25-lavapipe.sh (not installed).
# Source it: . $env_sh
export VK_DRIVER_FILES='$icd'
case ":\${LD_LIBRARY_PATH:-}:" in
  *':$lib:'*) ;;
  *) export LD_LIBRARY_PATH='$lib'\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH} ;;
esac
EOF
}

print_env() {
  echo "$me: Mesa 25 lavapipe ready in $out"
  grep -E '^export|^  \*\) export' "$env_sh" | sed -E 's/^  \*\) //; s/ ;;$//'
  echo "$me: use it with: . $env_sh"
}

lib_of_icd() { # the library directory the ICD json points at
  sed -nE 's/.*"library_path"[[:space:]]*:[[:space:]]*"([^"]*)\/libvulkan_lvp\.so".*/\1/p' "$icd"
}

# Already unpacked: nothing to fetch.
if [ -f "$icd" ] && grep -qF "\"$out/" "$icd"; then
  lib=$(lib_of_icd)
  [ -f "$lib/libvulkan_lvp.so" ] || die "$icd points at a missing $lib/libvulkan_lvp.so; remove $out and run again"
  [ -f "$env_sh" ] || write_env "$lib"
  print_env
  exit 0
fi

command -v apt-get >/dev/null || die "apt-get not found (this script needs Debian 12 bookworm)"
command -v dpkg >/dev/null || die "dpkg not found (this script needs Debian 12 bookworm)"
# shellcheck source=/dev/null
codename=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
[ "$codename" = bookworm ] || die "this script targets Debian 12 bookworm (found '${codename:-unknown}')"

# The system's own Debian mirror: the first enabled 'deb' entry for bookworm, bookworm-updates or
# bookworm-backports, from one-line sources lists or deb822 .sources files. Prints "URI SIGNED-BY".
find_mirror() {
  local f
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -r "$f" ] || continue
    awk '
      { sub(/#.*/, "") }
      $1 != "deb" { next }
      {
        i = 2; signed = ""
        if ($2 ~ /^\[/) {
          while (i <= NF) {
            o = $i; gsub(/[\[\]]/, "", o)
            if (o ~ /^signed-by=/) { sub(/^signed-by=/, "", o); signed = o }
            if ($i ~ /\]$/) { i++; break }
            i++
          }
        }
        uri = $i; s = $(i + 1)
        if (s ~ /^bookworm(-updates|-backports)?\/?$/ && uri !~ /^cdrom:/) { print uri, signed; exit }
      }' "$f"
  done
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -r "$f" ] || continue
    awk '
      BEGIN { RS = ""; FS = "\n" }
      {
        types = ""; uris = ""; suites = ""; signed = ""; enabled = "yes"; key = ""
        for (n = 1; n <= NF; n++) {
          line = $n
          if (line ~ /^#/) continue
          if (line ~ /^[ \t]/) { if (key == "uris") uris = uris " " line; continue }
          key = tolower(line); sub(/:.*/, "", key)
          val = line; sub(/^[^:]*:[ \t]*/, "", val)
          if (key == "types") types = val
          else if (key == "uris") uris = val
          else if (key == "suites") suites = val
          else if (key == "signed-by") signed = val
          else if (key == "enabled") enabled = tolower(val)
        }
        if (enabled == "no" || (" " types " ") !~ / deb /) next
        if (signed !~ /^\//) signed = ""
        ns = split(suites, sv, /[ \t]+/); ok = 0
        for (k = 1; k <= ns; k++) if (sv[k] ~ /^bookworm(-updates|-backports)?\/?$/) ok = 1
        if (!ok) next
        nu = split(uris, uv, /[ \t]+/)
        for (k = 1; k <= nu; k++) if (uv[k] != "" && uv[k] !~ /^cdrom:/) { print uv[k], signed; exit }
      }' "$f"
  done
}

mirror_line=$(find_mirror)
mirror_line=${mirror_line%%$'\n'*}
[ -n "$mirror_line" ] || die "no Debian bookworm mirror found in /etc/apt/sources.list or /etc/apt/sources.list.d/*.{list,sources}"
read -r mirror signed_by <<<"$mirror_line"

# Private apt state: sources list, lists and cache live in a scratch folder inside $out.
work=$(mktemp -d "$out/.fetch.XXXXXX") || die "cannot create a scratch folder in $out"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/etc" "$work/lists/partial" "$work/cache/archives/partial" "$work/debs" "$work/root"
opts=${signed_by:+[signed-by=$signed_by] }
echo "deb $opts$mirror $suite main" >"$work/etc/sources.list"
apt_opts=(
  -o "Dir::Etc::SourceList=$work/etc/sources.list"
  -o Dir::Etc::SourceParts=/dev/null
  -o "Dir::State::Lists=$work/lists"
  -o "Dir::Cache=$work/cache"
  -o Dir::Cache::pkgcache= -o Dir::Cache::srcpkgcache=
)
# As root, apt would hand downloads to the _apt user, who cannot write to the scratch folder.
if [ "$(id -u)" -eq 0 ]; then apt_opts+=(-o APT::Sandbox::User=root); fi

echo "$me: fetching ${packages[*]} from $mirror $suite" >&2
log=$work/apt.log
apt_error() { # the first apt error or warning in the log, else its last line
  local line
  line=$(grep -m 1 -E '^[EW]: ' "$log" || true)
  echo "${line:-$(tail -n 1 "$log")}"
}
apt-get "${apt_opts[@]}" -q --error-on=any update >"$log" 2>&1 ||
  die "apt-get update of $mirror $suite failed: $(apt_error)"
(cd "$work/debs" && apt-get "${apt_opts[@]}" -q download "${packages[@]/%//$suite}") >"$log" 2>&1 ||
  die "apt-get download of ${packages[*]} from $suite failed: $(apt_error)"

for deb in "$work"/debs/*.deb; do
  [ -f "$deb" ] || die "apt-get download produced no .deb files"
  dpkg -x "$deb" "$work/root" || die "dpkg -x failed on $(basename "$deb")"
done

so=$(find "$work/root/usr/lib" -name libvulkan_lvp.so -print -quit)
[ -n "$so" ] || die "libvulkan_lvp.so not found in mesa-vulkan-drivers"
src_icd=
for j in "$work/root/usr/share/vulkan/icd.d/lvp_icd.$arch.json" "$work/root/usr/share/vulkan/icd.d/lvp_icd.json"; do
  if [ -f "$j" ]; then src_icd=$j; break; fi
done
[ -n "$src_icd" ] || die "lvp_icd json not found in mesa-vulkan-drivers"

# Move the unpacked tree into $out, then point the ICD json at the unpacked library (the json
# holds a bare file name or an absolute /usr/lib path). The json is written last: it marks a
# complete unpack.
cp -a "$work/root/." "$out/"
lib=$out/${so#"$work/root/"}
lib=${lib%/libvulkan_lvp.so}
src_icd=$out/${src_icd#"$work/root/"}
grep -q '"library_path"' "$src_icd" || die "no library_path in $src_icd"
missing=$(LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ldd "$lib/libvulkan_lvp.so" | grep 'not found' || true)
[ -z "$missing" ] || die "libvulkan_lvp.so needs libraries missing here: $(echo "$missing" | awk '{print $1}' | tr '\n' ' ')"
write_env "$lib"
sed -E "s|(\"library_path\"[[:space:]]*:[[:space:]]*\")[^\"]*(\")|\1$lib/libvulkan_lvp.so\2|" "$src_icd" >"$work/icd.json"
mv "$work/icd.json" "$icd"
print_env
