#!/usr/bin/env bash
# scripts/packages.sh debian_archive_source: the archive of the release, read from apt source files
# of both formats (one-line .list, deb822 .sources), never a -security or -updates suite, a deb-src
# line or a comment; its signed-by, else Debian's keyring; exit 1 when no source carries main.
set -u
source "$(dirname "$0")/../../scripts/packages.sh"
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
failed=0
expect() {  # WANT FILE...
  local want=$1 got
  shift
  got=$(debian_archive_source bookworm "$@") || got="exit $?"
  [ "$got" = "$want" ] || { echo "FAIL: $* -> '$got', expected '$want'"; failed=1; }
}
printf '# deb http://commented.example/debian bookworm main\ndeb http://sec.example/debian-security bookworm-security main\ndeb-src http://src.example/debian bookworm main\ndeb [arch=amd64 signed-by=/k.gpg] http://m.example/debian bookworm contrib main\n' >"$d/a.list"
printf 'Types: deb-src deb\n# a comment\nURIs: http://n.example/debian\nSuites: bookworm-updates bookworm\nComponents: contrib main\n\nTypes: deb\nURIs: http://o.example/debian\nSuites: bookworm\nComponents: main\nSigned-By: /o.gpg\n' >"$d/b.sources"
printf 'Types: deb\nURIs: http://u.example/debian\nSuites: bookworm-updates\nComponents: main\n\nTypes: deb\nURIs: http://v.example/debian\nSuites: bookworm\nComponents: main\nSigned-By: /v.gpg\n' >"$d/c.sources"
printf 'deb http://p.example/debian bookworm contrib\n' >"$d/d.list"
expect 'http://m.example/debian /k.gpg' "$d/a.list"
expect 'http://n.example/debian /usr/share/keyrings/debian-archive-keyring.gpg' "$d/b.sources"
expect 'http://v.example/debian /v.gpg' "$d/c.sources"
expect 'exit 1' "$d/d.list"
expect 'http://v.example/debian /v.gpg' "$d/d.list" "$d/c.sources"
expect 'exit 1' "$d/missing.list"
# The repository itself names no package host (the sources come from the machine).
if grep -rIl --exclude-dir=build --exclude-dir=build-asan --exclude-dir=.git -E 'deb[.]debian[.]org|security[.]debian[.]org' \
    "$(dirname "$0")/../../scripts"; then
  echo "FAIL: a script names a Debian host"; failed=1
fi
[ $failed -eq 0 ] && echo "ok"
exit $failed
