#!/usr/bin/env bash
# Runs the README's two commands (bash scripts/demo.sh, then bash
# scripts/test.sh) on a fresh Debian release, in a chroot that debootstrap
# makes, and prints what passed. A check for a person to run (as root), not
# part of CI: a full run takes about an hour on 2 cores.
#
#   sudo bash scripts/check_distro.sh trixie|bookworm [--root DIR] [--keep-root] [--demo-only]
#
# The root is made anew each run (a fresh machine, an empty ccache) in
# /var/tmp/hba-distro/<release>, or DIR; --keep-root reuses one left by an
# earlier run (its packages and ccache: quicker, not a fresh machine). The
# project is copied in as the work tree's tracked files (a clean clone, with
# uncommitted changes); ../shared, where present, is bound beside it read-only.
# --demo-only runs the first command alone (its time on a fresh machine).
# The mirror is $HBA_DEBIAN_MIRROR or http://deb.debian.org/debian.
set -euo pipefail

usage() {
  echo "usage: $0 trixie|bookworm [--root DIR] [--keep-root] [--demo-only]" >&2
  exit 2
}
[ "$#" -ge 1 ] || usage
release="$1"
shift
case "$release" in trixie | bookworm) ;; *) usage ;; esac
root="/var/tmp/hba-distro/$release"
keep_root=0
commands=(demo tests)
while [ "$#" -gt 0 ]; do
  case "$1" in
    --root) root="$2"; shift 2 ;;
    --keep-root) keep_root=1; shift ;;
    --demo-only) commands=(demo); shift ;;
    *) usage ;;
  esac
done
if [ "$(id -u)" -ne 0 ]; then
  echo "check_distro: needs root (debootstrap, chroot, mounts): sudo bash $0 $release" >&2
  exit 1
fi

project="$(cd "$(dirname "$0")/.." && pwd)"
shared="$(dirname "$project")/shared"
mirror="${HBA_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
logs="$root/work/logs"

if ! command -v debootstrap >/dev/null; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap
fi

if [ "$keep_root" -eq 0 ] || [ ! -x "$root/bin/bash" ]; then
  echo "check_distro: making a fresh Debian $release root in $root"
  rm -rf --one-file-system "$root"
  mkdir -p "$(dirname "$root")"
  debootstrap --variant=minbase "$release" "$root" "$mirror" >"$root.debootstrap.log" 2>&1 || {
    tail -n 20 "$root.debootstrap.log" >&2
    exit 1
  }
  # The sources of an installed Debian: the release, its updates, security.
  security="$(dirname "$mirror")/debian-security"
  cat >"$root/etc/apt/sources.list" <<SOURCES
deb $mirror $release main
deb $mirror $release-updates main
deb $security $release-security main
SOURCES
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"

# The project as a clean clone would have it, with the work tree's changes.
rm -rf --one-file-system "$root/work/main" "$logs"
mkdir -p "$root/work/main" "$root/work/shared" "$logs"
(cd "$project" && git ls-files -z --cached --others --exclude-standard |
  tar --null --ignore-failed-read -T - -cf -) | tar -xf - -C "$root/work/main"

# In a mount namespace of its own: every mount goes when the run ends,
# however it ends.
inside=$(
  cat <<'INSIDE'
set -uo pipefail
root="$1" shared="$2" commands="$3"
mount -t proc proc "$root/proc"
mount -t sysfs sys "$root/sys"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
mount -t tmpfs shm "$root/dev/shm"
if [ -d "$shared" ]; then
  mount --bind "$shared" "$root/work/shared"
  mount -o remount,bind,ro "$root/work/shared"
fi
run() {  # run NAME COMMAND: the command in the chroot, its output in logs/NAME.log
  local name="$1" command="$2" start=$SECONDS status
  echo "check_distro: $name: $command"
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    HBA_JOBS="${HBA_JOBS:-}" bash -c "cd /work/main && $command" >"$root/work/logs/$name.log" 2>&1
  status=$?
  echo "$status $((SECONDS - start))" >"$root/work/logs/$name.status"
}
run demo "bash scripts/demo.sh"
[ "$commands" = demo ] || run tests "bash scripts/test.sh"
INSIDE
)
unshare --mount --propagation private bash -c "$inside" inside "$root" "$shared" "${commands[*]}"

# What passed.
seconds() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }
echo
echo "== Debian $release: $(cat "$root/etc/debian_version"), $(chroot "$root" g++ --version 2>/dev/null | head -n 1)"
failed=0
for name in "${commands[@]}"; do
  read -r status took <"$logs/$name.status"
  # The compilers' warnings (file:line:col: warning:), not apt's or Python's.
  warnings=$(grep -cE '^[^ ]+:[0-9]+:([0-9]+:)? warning:|^cc1plus: warning:' "$logs/$name.log" || true)
  verdict=passed
  [ "$status" -eq 0 ] || { verdict="FAILED (exit $status)"; failed=1; }
  [ "$warnings" -eq 0 ] || { verdict="$verdict, $warnings compiler warnings"; failed=1; }
  echo "$name: $verdict in $(seconds "$took"); log $logs/$name.log"
done
echo "-- demo:"
grep -E 'ATE trans m|^(before|after): *MME|^Took' "$logs/demo.log" || tail -n 15 "$logs/demo.log"
[ "${#commands[@]}" -eq 2 ] || exit "$failed"
echo "-- tests:"
grep -E 'tests passed|tests failed|Total Test time' "$logs/tests.log" || tail -n 30 "$logs/tests.log"
sed -n '/The following tests did not run/,/^$/p;/The following tests FAILED/,/^$/p' "$logs/tests.log"
exit "$failed"
