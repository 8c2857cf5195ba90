#!/bin/bash
# Builds the Debian package around the rotord of this build and checks it
# (tests/packaging/CMakeLists.txt says why prebuilt). `make deb` runs the
# same script (scripts/build-deb.sh) but compiles rotord from source.
# DEB_HOST_ARCH (arm64, armhf: tests/cross): the package of a cross build's
# rotord, whose binary runs here under qemu-user.
set -u
fail() { echo "FAIL: $*"; exit 1; }
for tool in dpkg-buildpackage dh dh_installsysusers lintian systemd-analyze man git; do
  command -v "$tool" >/dev/null || fail "$tool is missing (scripts/install-deps.sh)"
done
cd "$ROTORD_SOURCE_DIR" || fail "no source dir"
out="$PACKAGING_DIR"
start=$(date +%s)
ROTORD_PREBUILT="$ROTORD" DEB_BUILD_DIR="$out" DEB_HOST_ARCH="${DEB_HOST_ARCH:-}" ./scripts/build-deb.sh >"$out.log" 2>&1 ||
  { tail -40 "$out.log"; fail "dpkg-buildpackage failed (log: $out.log)"; }
arch=${DEB_HOST_ARCH:-$(dpkg --print-architecture)}
deb=$(ls "$out"/rotord_*_"$arch".deb 2>/dev/null | head -1)
[ -f "$deb" ] || fail "no rotord_*.deb in $out"
echo "built $deb"
# Nothing of debhelper's in the source tree.
for f in debian/.debhelper debian/rotord debian/files debian/debhelper-build-stamp obj-*; do
  [ -e "$f" ] && fail "$f left in the source tree"
done
x=$(mktemp -d)
trap 'rm -rf "$x"' EXIT
# The copy holds what `make deb` needs to compile from source, as
# dh_auto_configure runs it (here ROTORD_PREBUILT skips that step): the
# map's data, ignored by git, was once missing from it and stopped the build.
cmake -S "$out/rotord" -B "$x/configure" -G Ninja -DROTORD_BUILD_TESTS=OFF >"$x/configure.log" 2>&1 ||
  { tail -8 "$x/configure.log"; fail "the tree build-deb.sh copied does not configure"; }

# 1. Contents.
contents=$(dpkg-deb -c "$deb") || fail "dpkg-deb -c"
echo "$contents"
has() { grep -qE "^$1 +root/root +[0-9]+ [0-9-]+ [0-9:]+ \./$2\$" <<<"$contents" || fail "no $2 ($1)"; }
has '-rwxr-xr-x' 'usr/bin/rotord'
has '-rw-r--r--' '(usr/)?lib/systemd/system/rotord.service'
has '-rw-r--r--' 'etc/rotord/rotord.conf'
has '-rw-r--r--' 'usr/lib/sysusers.d/rotord.conf'
has '-rw-r--r--' '(usr/)?lib/udev/rules.d/55-rotord.rules'
has '-rw-r--r--' 'usr/share/man/man8/rotord.8.gz'
has '-rw-r--r--' 'usr/share/doc/rotord/README.md.gz'
has '-rw-r--r--' 'usr/share/doc/rotord/copyright'

dpkg-deb -x "$deb" "$x/root" && dpkg-deb -e "$deb" "$x/control" || fail "cannot unpack"
unit=$(ls "$x"/root/{usr/,}lib/systemd/system/rotord.service 2>/dev/null | head -1)
cmp -s "$unit" debian/rotord.service || fail "the packaged unit is not debian/rotord.service"
grep -qx /etc/rotord/rotord.conf "$x/control/conffiles" || fail "rotord.conf is not a conffile"
grep -q '^ROTORD_OPTS="--hw gpiod"$' "$x/root/etc/rotord/rotord.conf" || fail "ROTORD_OPTS"
grep -q '^u rotord ' "$x/root/usr/lib/sysusers.d/rotord.conf" || fail "no rotord user in sysusers"
# The rotord user, then its hardware groups where they exist; not started.
grep -q 'systemd-sysusers .*rotord.conf' "$x/control/postinst" || fail "postinst creates no user"
grep -q 'for group in gpio i2c dialout' "$x/control/postinst" || fail "postinst adds no groups"
# The devices' group applied before the install returns (tests/pi_vm):
# the rules reloaded once the group exists, the events waited for.
grep -q 'udevadm control --reload' "$x/control/postinst" || fail "postinst does not reload udev's rules"
grep -q 'udevadm trigger --settle ' "$x/control/postinst" || fail "postinst does not settle udev"
grep -q "deb-systemd-invoke start" "$x/control/postinst" && fail "the service starts on install"
sh -n "$x/control/postinst" || fail "postinst syntax"
dpkg-deb -f "$deb" Depends | grep -q 'libgpiod' || fail "Depends has no libgpiod"
# The sysusers line, applied to an empty root: a rotord user and group.
mkdir -p "$x/sysroot/etc"
systemd-sysusers --root="$x/sysroot" "$x/root/usr/lib/sysusers.d/rotord.conf" >/dev/null 2>&1 ||
  fail "systemd-sysusers refuses rotord.conf"
grep -q '^rotord:x:[0-9]*:[0-9]*:.*:/var/lib/rotord:/usr/sbin/nologin$' "$x/sysroot/etc/passwd" ||
  fail "no rotord user from sysusers"
# postinst on a machine with gpio and dialout but no i2c group, the system's
# commands replaced by stubs that log (nothing on this machine changes):
# rotord joins exactly the groups that exist.
mkdir -p "$x/stubs"
for cmd in systemd-sysusers deb-systemd-helper deb-systemd-invoke udevadm; do
  printf '#!/bin/sh\nexit 0\n' >"$x/stubs/$cmd"
done
printf '#!/bin/sh\n[ "$1" = passwd ] && [ "$2" = rotord ] && exit 0\n[ "$1" = group ] && { [ "$2" = gpio ] || [ "$2" = dialout ]; }\n' >"$x/stubs/getent"
printf '#!/bin/sh\necho rotord\n' >"$x/stubs/id"
printf '#!/bin/sh\necho "usermod $*" >>"%s/usermod.log"\n' "$x" >"$x/stubs/usermod"
chmod +x "$x"/stubs/*
PATH="$x/stubs:$PATH" sh "$x/control/postinst" configure || fail "postinst configure failed"
[ "$(cat "$x/usermod.log")" = "usermod -a -G gpio rotord
usermod -a -G dialout rotord" ] || fail "postinst groups: $(cat "$x/usermod.log" 2>/dev/null)"
# The preinst makes the user and group before the udev rule is unpacked
# (udevd drops a GROUP= it reads before the group exists), once only.
sh -n "$x/control/preinst" || fail "preinst syntax"
mkdir -p "$x/stubs-pre"
printf '#!/bin/sh\necho "useradd $*" >>"%s/useradd.log"\n' "$x" >"$x/stubs-pre/useradd"
printf '#!/bin/sh\nexit 2\n' >"$x/stubs-pre/getent"
chmod +x "$x"/stubs-pre/*
PATH="$x/stubs-pre:$PATH" sh "$x/control/preinst" install || fail "preinst install failed"
grep -q -- '--system --user-group --home-dir /var/lib/rotord .* rotord$' "$x/useradd.log" ||
  fail "preinst makes no rotord user: $(cat "$x/useradd.log" 2>/dev/null)"
PATH="$x/stubs:$x/stubs-pre:$PATH" sh "$x/control/preinst" upgrade 1.0 || fail "preinst upgrade failed"
[ "$(wc -l <"$x/useradd.log")" = 1 ] || fail "preinst made the user a second time"

# 2. The unit: what the issue asks for, and systemd accepts it.
for line in Type=notify WatchdogSec= Restart=on-failure User=rotord StateDirectory=rotord \
  ConfigurationDirectory=rotord EnvironmentFile=-/etc/rotord/rotord.conf \
  'ExecStart=/usr/bin/rotord $ROTORD_OPTS' 'ExecStopPost=/usr/bin/rotord --outputs-off $ROTORD_OPTS' \
  ProtectSystem=strict ProtectHome=yes NoNewPrivileges=yes PrivateTmp=yes DevicePolicy=closed \
  'DeviceAllow=char-gpiochip rw' 'DeviceAllow=char-i2c rw' 'DeviceAllow=char-ttyUSB rw'; do
  grep -qF -- "$line" "$unit" || fail "the unit has no $line"
done
# verify: the binary at the unit's path is the packaged one, and the man
# page (Documentation=man:rotord(8)) is checked below, not installed here.
sed "s|/usr/bin/rotord|$x/root/usr/bin/rotord|" "$unit" >"$x/rotord.service"
systemd-analyze verify --man=no "$x/rotord.service" 2>&1 | tee "$x/verify.log"
[ "${PIPESTATUS[0]}" -eq 0 ] && [ ! -s "$x/verify.log" ] || fail "systemd-analyze verify"
# The sandboxing stays at least as tight as it is (exposure 2.2 of 10 when written).
systemd-analyze security --offline=yes --threshold=30 "$x/rotord.service" >"$x/security.log" 2>&1 ||
  { tail -3 "$x/security.log"; fail "systemd-analyze security: exposure above 3.0"; }
tail -1 "$x/security.log"

# 3. lintian: no error or warning (info tags allowed; overrides say why).
# Here two info tags, hardening-no-bindnow and hardening-no-fortify-functions,
# come from the prebuilt binary (this build's flags, not dpkg-buildflags');
# `make deb` compiles with dpkg-buildflags' hardening and has neither.
lintian --fail-on error,warning --pedantic -I "$deb" 2>&1 | grep -v 'running with root privileges' |
  tee "$x/lintian.log"
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "lintian"

# 4. The packaged binary runs (an arm one under qemu-user); the man page
# renders without warnings.
run=()
case $arch in
  arm64) run=(qemu-aarch64-static) ;;
  armhf) run=(qemu-arm-static) ;;
esac
"${run[@]}" "$x/root/usr/bin/rotord" --print-config --hw sim --config "$x/none.json" >/dev/null ||
  fail "the packaged rotord does not run"
warnings=$(LC_ALL=C.UTF-8 man --warnings -l "$x/root/usr/share/man/man8/rotord.8.gz" 2>&1 >/dev/null)
[ -z "$warnings" ] || fail "man page: $warnings"
echo "PASS ($arch, $(($(date +%s) - start)) s)"
