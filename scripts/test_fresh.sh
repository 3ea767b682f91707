#!/usr/bin/env bash
# make test-fresh: the whole suite on a fresh Debian 12, in a throwaway root.
#
# A machine that has been used for development has packages installed by hand, which hide
# a missing install step from `make test`. This script proves the two commands the README
# promises on a Debian 12 that has nothing but `make`: it bootstraps a minimal bookworm
# root (debootstrap --variant=minbase), clones the committed HEAD of this repository into
# it, runs `make test` there, and deletes the root afterwards, whatever the result.
#
# `scripts/test_fresh.sh demo` (make demo-fresh) times the first `make demo` there instead:
# from the moment `make demo` starts (apt included) until `rostopic list` shows the demo's
# topics, then it stops the demo by the id of the process it started. The demo's master runs
# on a port of its own, as the root shares this machine's loopback.
#
# The bootstrapped base is cached as a tarball (FRESH_CACHE, under /var/cache/) so a second
# run skips the download. Needs root (chroot, mounts).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
cache_dir=${FRESH_CACHE:-/var/cache/plc_cell}
base_tar="$cache_dir/bookworm-minbase.tar"
root=${FRESH_ROOT:-}
target=${1:-${FRESH_TARGET:-test}}

if [ "$(id -u)" != 0 ]; then
  echo "test-fresh: needs root (debootstrap, chroot and mounts); run it as root or with sudo" >&2
  exit 2
fi
if [ -n "$(git -C "$repo" status --porcelain --untracked-files=no)" ]; then
  echo "test-fresh: note: uncommitted changes are not tested; the root gets the committed HEAD $(git -C "$repo" rev-parse --short HEAD)"
fi

# The mirror this machine's apt uses: a fresh machine sees the same archive.
mirror=${FRESH_MIRROR:-$(grep -hoE '^(URIs: |deb )[^ ]+' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null \
  | sed -E 's/^(URIs: |deb )//' | grep -v security | head -n 1 || true)}
mirror=${mirror:-http://deb.debian.org/debian}

if ! command -v debootstrap >/dev/null; then
  echo "== installing debootstrap on this machine"
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap </dev/null
fi

[ -n "$root" ] || root=$(mktemp -d /var/tmp/plc_cell-fresh.XXXXXX)
mounted=()
cleanup() {
  local rc=$?
  # Processes still running inside the root (a make interrupted by a signal) go first.
  for p in /proc/[0-9]*; do
    [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && kill -9 "${p#/proc/}" 2>/dev/null
  done
  for ((i=${#mounted[@]}-1; i>=0; i--)); do umount -l "${mounted[$i]}" 2>/dev/null || true; done
  # Never follow a mount left behind: delete only what is on the root's own file system.
  if ! grep -q " $root/" /proc/mounts; then rm -rf --one-file-system "$root"; else
    echo "test-fresh: $root still has mounts; not deleted" >&2; fi
  exit $rc
}
trap cleanup EXIT INT TERM

# The topics that say the demo is up: the cell's I/O and one of its signals.
DEMO_TOPICS=(/plc_node/io /plc_node/io_words /plc_node/signals/conveyor_run)
DEMO_LIMIT=${DEMO_LIMIT:-3600}  # s: give up (and fail) after this long

time_demo() {
  local port pid up="" listed
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  # setsid: the demo is the leader of a process group of its own, stopped through its id.
  setsid chroot "$root" /usr/bin/env -i "${env_in_root[@]}" ROS_MASTER_URI="http://localhost:$port" \
    /bin/bash -c "cd /srv/plc_cell && exec make demo" </dev/null > "$root/srv/make.log" 2>&1 &
  pid=$!
  echo "== make demo started (pid $pid, master port $port); load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  # Phases from make's own output: apt done when catkin starts, build done when the demo starts.
  # CPU seconds: what make's finished children (apt, catkin) used, which the load does not inflate.
  local built="" building="" cpu=""
  while kill -0 "$pid" 2>/dev/null && [ $(( $(date +%s) - t1 )) -lt "$DEMO_LIMIT" ]; do
    sleep 2
    [ -n "$building" ] || ! grep -q 'catkin_make' "$root/srv/make.log" || building=$(( $(date +%s) - t1 ))
    if [ -z "$built" ] && grep -q '^== starting the demo cell' "$root/srv/make.log"; then
      built=$(( $(date +%s) - t1 ))
      cpu=$(awk -v hz="$(getconf CLK_TCK)" '{print int(($16 + $17) / hz)}' "/proc/$pid/stat")
    fi
    [ -n "$built" ] || continue  # no rostopic (a Python start-up each) while the build runs
    listed=$(chroot "$root" /usr/bin/env -i "${env_in_root[@]}" ROS_MASTER_URI="http://localhost:$port" \
      ROS_HOSTNAME=localhost /bin/bash -c \
      "source /srv/plc_cell/.build/ws/devel/setup.bash && timeout 10 rostopic list" 2>/dev/null) || continue
    up=yes
    for t in "${DEMO_TOPICS[@]}"; do grep -qx "$t" <<<"$listed" || up=""; done
    [ -z "$up" ] || break
  done
  local took=$(( $(date +%s) - t1 ))
  kill -INT -- "-$pid" 2>/dev/null || true
  for _ in $(seq 20); do kill -0 "$pid" 2>/dev/null || break; sleep 1; done
  kill -KILL -- "-$pid" 2>/dev/null || true
  grep -E '^== (installing|starting)|catkin_make|Error|error:' "$root/srv/make.log" | cut -c1-200 || true
  echo "== load average now: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
  echo "== apt until ${building:-?} s, build until ${built:-?} s; apt and build used ${cpu:-?} CPU seconds"
  if [ -n "$up" ]; then
    echo "== demo topics up ${took} s after make demo started (whole run $(( $(date +%s) - t0 )) s)"
    return 0
  fi
  tail -n 30 "$root/srv/make.log"
  echo "== demo topics not up after ${took} s"
  return 1
}

t0=$(date +%s)
if [ -f "$base_tar" ]; then
  echo "== unpacking the cached bookworm minbase ($base_tar)"
  tar -C "$root" -xpf "$base_tar"
else
  echo "== debootstrap --variant=minbase bookworm from $mirror (cached afterwards in $base_tar)"
  # make: a user needs it to type the README's two commands; nothing else is added.
  debootstrap --variant=minbase --include=make bookworm "$root" "$mirror" > "$root.debootstrap.log" 2>&1 \
    || { tail -n 30 "$root.debootstrap.log" >&2; rm -f "$root.debootstrap.log"; exit 1; }
  rm -f "$root.debootstrap.log"
  mkdir -p "$cache_dir"
  tar -C "$root" -cpf "$base_tar.tmp" . && mv "$base_tar.tmp" "$base_tar"
fi
echo "== base root ready in $(( $(date +%s) - t0 )) s"

# Same suites as this machine (updates and security), so packages match a fresh install.
cat > "$root/etc/apt/sources.list" <<SRC
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb ${mirror%/debian}/debian-security bookworm-security main
SRC
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
host=$(hostname)
printf '127.0.0.1\tlocalhost\n::1\tlocalhost ip6-localhost ip6-loopback\n127.0.1.1\t%s\n' "$host" > "$root/etc/hosts"

for m in proc sys dev dev/pts; do mkdir -p "$root/$m"; done
mount -t proc proc "$root/proc"; mounted+=("$root/proc")
mount -t sysfs sys "$root/sys"; mounted+=("$root/sys")
mount --bind /dev "$root/dev"; mounted+=("$root/dev")
mount --bind /dev/pts "$root/dev/pts"; mounted+=("$root/dev/pts")

echo "== cloning $(git -C "$repo" rev-parse --short HEAD) into the root"
mkdir -p "$root/srv"
git clone -q --no-hardlinks "$repo" "$root/srv/plc_cell"

env_in_root=(HOME=/root LANG=C.UTF-8 TERM=dumb CI="${CI:-}"
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin)
echo "== make $target in the fresh root"
t1=$(date +%s)
if [ "$target" = demo ]; then
  time_demo
  exit $?
fi
set +e
chroot "$root" /usr/bin/env -i "${env_in_root[@]}" \
  /bin/bash -c "cd /srv/plc_cell && make $target" </dev/null 2>&1 | tee "$root/srv/make.log"
rc=${PIPESTATUS[0]}
set -e
echo "== make $target in the fresh root: exit $rc after $(( $(date +%s) - t1 )) s (whole run $(( $(date +%s) - t0 )) s)"
# The phases make marked (scripts/phase.sh), as the table of docs/testing.md.
echo "== phases (load average now $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores):"
echo "| phase | wall, s | CPU, s |"
echo "|---|---|---|"
echo "| root and clone | $(( t1 - t0 )) | |"
sed -n -E 's/^== phase (.*): ([0-9]+) s, ([0-9]+) CPU s$/| \1 | \2 | \3 |/p' "$root/srv/make.log"
echo "| whole run | $(( $(date +%s) - t0 )) | |"
# The suite's own closing line, last, for whoever reads the run's last lines.
grep -E '^[0-9]+ passed, [0-9]+ failed' "$root/srv/make.log" | tail -n 1 || true
exit $rc
