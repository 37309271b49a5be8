#!/usr/bin/env bash
# Fresh-machine check: runs the README's two quick-start commands, exactly as written, in
# brand-new Debian 12 roots — once in each order, each from a clean clone of the current
# commit with ../shared beside it — and prints each command's exit status and wall time.
# A machine that already has a package hides a missing install step; a new root does not.
#
#   sudo bash tools/ci/fresh_machine_check.sh [LOG_DIR]
#
# Needs root (chroot, mounts) and the network to Debian's package registry; refuses clearly
# (exit 2) without them. The minimal root (mmdebstrap --variant=apt, plus ca-certificates
# and git, as a new user's machine) is cached as a tarball in $TESSERA_FRESH_CACHE
# (default /var/cache/tessera/fresh-machine) and reused; downloaded .deb files are cached
# there too, which saves time without hiding anything: each root still has to install every
# package itself. The compiler cache is shared the same way (ccache's folder on this machine,
# or $TESSERA_FRESH_CCACHE, mounted as each root's ~/.cache/ccache): the roots install ccache
# with the full package set, and a hit only spares compiling a source that was compiled
# identically before. Only committed work is checked (the clone is of HEAD).
# Exit status: 0 when all four commands passed, 1 when any failed, 2 when it cannot run.
set -euo pipefail

repo="$(cd "$(dirname "$0")/../.." && pwd)"
cache="${TESSERA_FRESH_CACHE:-/var/cache/tessera/fresh-machine}"
tarball="$cache/bookworm-apt.tar"
max_age_days=7  # a cached root older than this is rebuilt, so its packages stay current

refuse() { echo "fresh_machine_check: cannot run: $*" >&2; exit 2; }

[ "$(id -u)" -eq 0 ] || refuse "needs root (chroot and mounts); run it with sudo"
git -C "$repo" rev-parse --verify -q HEAD >/dev/null || refuse "$repo is not a git checkout with a commit"
if ! command -v mmdebstrap >/dev/null; then
  echo "== installing mmdebstrap"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mmdebstrap >/dev/null 2>&1 ||
    { apt-get update -qq >/dev/null 2>&1 &&
      DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mmdebstrap >/dev/null 2>&1; } ||
    refuse "mmdebstrap is not installed and could not be installed"
fi
# The new roots use this machine's Debian sources; an update that cannot fetch them means
# no registry, so nothing below could work.
# Every enabled sources file (deb822 .sources or one-line .list; mmdebstrap writes its
# roots' as sources.list.d/0000debian.sources), each given to mmdebstrap as a mirror.
sources=()
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
  [ -s "$f" ] && grep -qE '^[[:space:]]*(deb[[:space:]]|URIs:)' "$f" && sources+=("$f")
done
[ ${#sources[@]} -gt 0 ] || refuse "no apt sources on this machine (/etc/apt/sources.list, /etc/apt/sources.list.d/)"
if ! update_errors="$(timeout 120 apt-get update -qq --error-on=any 2>&1)"; then
  refuse "no network to the Debian package registry: apt-get update failed: $(echo "$update_errors" | grep -m1 -E '^(E|W|Err):' || echo "timed out")"
fi

# The README's quick start, exactly as written: the commands of the first ```sh block under
# "## Quick start" of the committed README (a trailing "# comment" is the shell's, so it is dropped here).
mapfile -t commands < <(awk '/^## Quick start/ { section = 1; next }
  section && /^## / { exit }
  section && /^```sh/ { block = 1; next }
  block && /^```/ { exit }
  block && NF && $1 !~ /^#/ { sub(/[ \t]+#.*$/, ""); print }' <(git -C "$repo" show HEAD:README.md))
[ ${#commands[@]} -eq 2 ] || refuse "README.md's quick start should have exactly two commands, found ${#commands[@]}"
quickstart="${commands[0]}"
tests="${commands[1]}"
echo "== the README's quick start: 1) $quickstart  2) $tests"

commit="$(git -C "$repo" rev-parse HEAD)"
log_dir="$(mkdir -p "${1:-$repo/build/fresh_machine}" && cd "${1:-$repo/build/fresh_machine}" && pwd)"
shared="$repo/../shared"
work="$(mktemp -d /var/tmp/tessera-fresh.XXXXXX)"
mounted=()  # mount points, unmounted in reverse order on every exit path
command_pid=""  # the quick-start command running in a root, in its own process group

cleanup() {
  local i
  # A command still running (we were stopped): end its whole process group before unmounting.
  if [ -n "$command_pid" ]; then
    kill -TERM -- "-$command_pid" 2>/dev/null || true
    sleep 2
    kill -KILL -- "-$command_pid" 2>/dev/null || true
    wait "$command_pid" 2>/dev/null || true
  fi
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -R "${mounted[i]}" 2>/dev/null || umount -R -l "${mounted[i]}" 2>/dev/null || true
  done
  mounted=()
  # Remove the root only when nothing is mounted below it any more.
  if ! grep -q " $work/" /proc/self/mounts; then rm -rf "$work"; else
    echo "fresh_machine_check: left $work (still mounted)" >&2
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

mkdir -p "$cache/archives"
# This machine's compiler cache when it has ccache (CI's own builds of the commit warm it), else
# one kept beside the .deb files.
if [ -n "${TESSERA_FRESH_CCACHE:-}" ]; then ccache_dir="$TESSERA_FRESH_CCACHE"
elif command -v ccache >/dev/null; then ccache_dir="$(ccache -k cache_dir)"
else ccache_dir="$cache/ccache"; fi
ccache_max="$(command -v ccache >/dev/null && ccache -k max_size || echo 5G)"
mkdir -p "$ccache_dir"
echo "== compiler cache shared into the roots: $ccache_dir (max $ccache_max)"
if [ -f "$tarball" ] && [ -n "$(find "$tarball" -mtime -"$max_age_days")" ]; then
  echo "== reusing the cached Debian 12 root $tarball"
else
  echo "== building a minimal Debian 12 root with mmdebstrap ($(date +%T))"
  rm -rf "$tarball" "$tarball.part"  # a stale or half-made one (mv would move into a directory)
  # --format=tar: the ".part" name would otherwise make mmdebstrap write a directory.
  mmdebstrap --quiet --format=tar --variant=apt --include=ca-certificates,git bookworm "$tarball.part" "${sources[@]}"
  mv "$tarball.part" "$tarball"
fi

# Unpacks a new root, mounts what a machine has, and clones the commit into /work/tessera
# with ../shared beside it.
new_root() {
  local root="$1"
  mkdir -p "$root"
  tar -xf "$tarball" -C "$root"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  mount -t proc proc "$root/proc"; mounted+=("$root/proc")
  mount --rbind /sys "$root/sys"; mount --make-rslave "$root/sys"; mounted+=("$root/sys")
  mount --rbind /dev "$root/dev"; mount --make-rslave "$root/dev"; mounted+=("$root/dev")
  mount --bind "$cache/archives" "$root/var/cache/apt/archives"; mounted+=("$root/var/cache/apt/archives")
  mkdir -p "$root/root/.cache/ccache"
  mount --bind "$ccache_dir" "$root/root/.cache/ccache"; mounted+=("$root/root/.cache/ccache")
  mkdir -p "$root/work"
  git clone -q --no-hardlinks "$repo" "$root/work/tessera"
  git -C "$root/work/tessera" checkout -q --detach "$commit"
  if [ -d "$shared" ]; then mkdir -p "$root/work/shared" && cp -a "$shared/." "$root/work/shared/"; fi
}

unmount_root() {
  local root="$1" i keep=()
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    case "${mounted[i]}" in
      "$root"/*) umount -R "${mounted[i]}" || umount -R -l "${mounted[i]}" ;;
      *) keep=("${mounted[i]}" "${keep[@]}") ;;
    esac
  done
  mounted=("${keep[@]}")
  rm -rf "$root"
}

results=()
failed=0

# Runs one quick-start command in the root as a new root user would: a clean environment,
# from the clone's top folder. Records its exit status and wall time.
run_command() {
  local root="$1" order="$2" cmd="$3" log="$log_dir/$2-$(basename "${3##* }" .sh).log"
  local start end status stats="$root/root/ccache-stats.log"
  rm -f "$stats"
  echo "== [$order] $cmd ($(date +%T)), log: $log"
  start=$(date +%s.%N)
  # In the background, in a process group of its own, and waited for: bash runs the INT/TERM
  # trap during `wait` at once (it would only after a foreground child ended), and the
  # cleanup can then end the command's every process before it unmounts.
  set +e
  setsid chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    CCACHE_MAXSIZE="$ccache_max" CCACHE_STATSLOG=/root/ccache-stats.log \
    /bin/bash -c "cd /work/tessera && $cmd" >"$log" 2>&1 </dev/null &
  command_pid=$!
  wait "$command_pid"
  status=$?
  command_pid=""
  set -e
  end=$(date +%s.%N)
  local wall; wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.0f", b - a }')
  # The render command must leave the picture it promises.
  if [ "$status" -eq 0 ] && [ "$cmd" = "$quickstart" ] && [ ! -s "$root/work/tessera/spheres.png" ]; then
    echo "   $cmd exited 0 but wrote no spheres.png"; status=1
  fi
  # What the compiler cache spared: compilations through ccache that were hits (none when the
  # command ran before ccache was installed).
  local hits=0 compiles=0
  if [ -s "$stats" ]; then
    hits=$(grep -cE '^(direct|preprocessed)_cache_hit$' "$stats" || true)
    compiles=$(grep -cE '^((direct|preprocessed)_cache_hit|cache_miss)$' "$stats" || true)
  fi
  results+=("$(printf '%-22s %-26s exit %-3s %5s s   ccache hits %s/%s' "[$order]" "$cmd" "$status" "$wall" "$hits" "$compiles")")
  echo "   exit $status after ${wall} s"
  if [ "$status" -ne 0 ]; then
    failed=1
    echo "   last lines of $log:"; tail -n 25 "$log" | sed 's/^/   | /'
  fi
  return 0
}

# Building and testing write nothing into the clone (generated files go to the build folder):
# its git status, ignored files included, shows only build/ and the quick start's spheres.png.
check_source_tree() {
  local root="$1" order="$2" left
  left="$(chroot "$root" git -C /work/tessera status --porcelain --ignored=matching --untracked-files=all |
    grep -vE '^!! (build/|spheres\.png$)' || true)"
  if [ -n "$left" ]; then
    failed=1
    results+=("$(printf '%-22s %s' "[$order]" "the source tree changed: $(echo "$left" | head -5 | tr '\n' ' ')")")
    echo "   the build changed the source tree:"; echo "$left" | sed 's/^/   | /'
  else
    results+=("$(printf '%-22s %s' "[$order]" "git status of the source tree: clean but build/ and spheres.png")")
  fi
}

# The two orders, each in its own new root: command 1 first (a new user), and command 2
# first (a developer who goes straight to the tests).
for order in render-first tests-first; do
  root="$work/$order"
  echo "== new Debian 12 root for order $order ($(date +%T))"
  new_root "$root"
  if [ "$order" = render-first ]; then first="$quickstart"; second="$tests"; else first="$tests"; second="$quickstart"; fi
  run_command "$root" "$order" "$first"
  run_command "$root" "$order" "$second"
  check_source_tree "$root" "$order"
  unmount_root "$root"
done

echo "== fresh-machine check of $commit ($(date +%T))"
printf '%s\n' "${results[@]}"
if [ "$failed" -ne 0 ]; then echo "fresh-machine check: FAILED (logs in $log_dir)"; exit 1; fi
echo "fresh-machine check: both quick-start commands pass on a fresh Debian 12, in both orders"
