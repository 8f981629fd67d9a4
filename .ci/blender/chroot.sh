#!/bin/sh
# A Debian trixie chroot with Blender 4.3.2, for `make test-blender` (run as root; Debian/Ubuntu host).
#   chroot.sh path           build the chroot if absent (cached), print its directory
#   chroot.sh run CMD...     run CMD inside it (sh -c), with /proc, /dev and this checkout (at
#                            /fibrilfit) mounted in a private mount namespace: the mounts vanish
#                            with the command, so an interrupted run leaves nothing mounted
# The cache is keyed on the suite and the package list (FIBRILFIT_CHROOT_CACHE, default
# /var/cache/fibrilfit/trixie-<hash>), outside the clone, so CI on the same machine reuses it. It is
# built in a temporary directory and renamed when complete: an interrupted build is never used, and
# a lock keeps two builds (CI and a developer) from racing. Anything the build cannot get (no
# debootstrap, no Debian mirror reachable) fails with one line on stderr and exit 1.
set -eu

SUITE=trixie
PACKAGES="blender python3-numpy xvfb xauth xdotool imagemagick libgl1-mesa-dri libglx-mesa0 chromium fonts-dejavu-core"
# The Debian mirror: DEBIAN_MIRROR, else the first .../debian archive the host's apt sources name
# (deb822 .sources or a one-line sources.list)
host_mirror() {
    { cat /etc/apt/sources.list.d/*.sources 2>/dev/null | sed -n 's|^URIs:[[:space:]]*\([^[:space:]]*/debian\)/*$|\1|p'
      cat /etc/apt/sources.list 2>/dev/null | sed -n 's|^deb[[:space:]]\{1,\}\(\[[^]]*\][[:space:]]\{1,\}\)\{0,1\}\([^[:space:]]*/debian\)/*[[:space:]].*|\2|p'
    } | head -n 1
}
MIRROR=${DEBIAN_MIRROR:-$(host_mirror)}
CACHE=${FIBRILFIT_CHROOT_CACHE:-/var/cache/fibrilfit}
KEY=$(printf '%s %s\n' "$SUITE" "$PACKAGES" | sha256sum | cut -c1-12)
DIR=$CACHE/$SUITE-$KEY
CHECKOUT=$(cd "$(dirname "$0")/../.." && pwd)
LOG=$CACHE/$SUITE-$KEY.log

die() { echo "test-blender: $*" >&2; exit 1; }

build() {
    [ "$(id -u)" = 0 ] || die "building the trixie chroot needs root (debootstrap, chroot)"
    mkdir -p "$CACHE"
    exec 9>"$CACHE/.lock"
    flock 9
    [ -f "$DIR/.fibrilfit-ready" ] && return
    if ! command -v debootstrap >/dev/null; then
        echo "test-blender: installing debootstrap on the host" >&2
        { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap; } \
            >>"$LOG" 2>&1 || die "cannot install debootstrap on the host (see $LOG)"
    fi
    [ -n "$MIRROR" ] || die "no Debian mirror: the host's apt sources name no .../debian archive; set DEBIAN_MIRROR"
    tmp=$DIR.partial
    rm -rf "$tmp"
    echo "test-blender: building the $SUITE chroot in $DIR (a few minutes; log $LOG)" >&2
    debootstrap --variant=minbase "$SUITE" "$tmp" "$MIRROR" >>"$LOG" 2>&1 \
        || die "debootstrap $SUITE from $MIRROR failed: no Debian packages reachable? (see $LOG)"
    cp /etc/resolv.conf "$tmp/etc/resolv.conf"
    ln -sf ../proc/self/mounts "$tmp/etc/mtab"  # Blender reads the mounted file systems
    unshare --mount --propagation private sh -c '
        mount -t proc proc "$1/proc" && mount --rbind /dev "$1/dev" &&
        chroot "$1" sh -c "apt-get update -q &&
            DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $2 &&
            apt-get clean"' sh "$tmp" "$PACKAGES" >>"$LOG" 2>&1 \
        || die "apt-get install in the $SUITE chroot failed: no Debian packages reachable? (see $LOG)"
    chroot "$tmp" blender --version >>"$LOG" 2>&1 || die "blender does not start in the chroot (see $LOG)"
    touch "$tmp/.fibrilfit-ready"
    mv "$tmp" "$DIR"
}

case "${1:-}" in
    path)
        [ -f "$DIR/.fibrilfit-ready" ] || build
        echo "$DIR" ;;
    run)
        shift
        [ -f "$DIR/.fibrilfit-ready" ] || build
        [ "$(id -u)" = 0 ] || die "running in the chroot needs root (unshare, mount, chroot)"
        mkdir -p "$DIR/fibrilfit"
        [ -e "$DIR/etc/mtab" ] || ln -sf ../proc/self/mounts "$DIR/etc/mtab"
        exec unshare --mount --propagation private sh -c '
            mount -t proc proc "$1/proc" && mount --rbind /dev "$1/dev" &&
            mount --bind "$2" "$1/fibrilfit" && exec chroot "$1" sh -c "cd /fibrilfit && $3"' \
            sh "$DIR" "$CHECKOUT" "$*" ;;
    *)
        die "usage: chroot.sh path | run CMD..." ;;
esac
