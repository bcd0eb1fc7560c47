#!/usr/bin/env bash
# Rebuilds the published page's JPEG 2000 decoder, web/openjpeg/j2k_decode.js and
# j2k_decode.wasm.gz (vendored in the repository: building relume and CI never need emscripten),
# from Debian packages only:
#   - OpenJPEG: Debian bookworm's source package openjpeg2 (2.5.0-2+deb12u3 when written, the
#     release relume's own libopenjp2-7 comes from), with Debian's patches (dpkg-source -x applies
#     them), fetched into a temporary folder through a private apt state (the system's source
#     lists and package lists are left alone). apt checks the files against the archive's signed
#     index; dpkg-source's warning that it cannot check the .dsc's own signature (without
#     debian-keyring) is expected;
#   - emscripten: Debian's package (3.1.6~dfsg-5 when written; installed when missing).
# The library is built for size (-Os: 12% smaller than -O3 and as fast on the ball's planes),
# without threads, codec tools or third-party libraries, and linked with the wrapper
# web/openjpeg/j2k_decode.c into an ES module (MODULARIZE + EXPORT_ES6, for the page and its
# module Web Workers; web/weight_planes.js hands it the .wasm); the module's first lines say
# which versions it was built from. The .wasm is stored gzipped (gzip -9n: 208 kB -> 67 kB on the
# wire from any server; the page inflates it with the browser's DecompressionStream). With the
# same packages a rebuild writes the same bytes.
# Usage: scripts/build_openjpeg_wasm.sh   (about 3 minutes on 2 cores; needs deb.debian.org, and
# root or sudo only to install missing packages)
set -euo pipefail
cd "$(dirname "$0")/.."
web="$PWD/web/openjpeg"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
command -v emcc >/dev/null ||
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends emscripten
command -v dpkg-source >/dev/null ||
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends dpkg-dev
# Debian's emcc finds its JavaScript dependencies (acorn) only through NODE_PATH.
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/sources.d"
cat > "$work/sources.d/debian.sources" <<'SOURCES'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main

Types: deb-src
URIs: http://deb.debian.org/debian-security
Suites: bookworm-security
Components: main
SOURCES
apt_private=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$work/sources.d"
             -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache")
apt-get "${apt_private[@]}" -qq update
# The release of the libopenjp2-7 that relume links, when installed; else the newest.
version="$(dpkg-query -W -f='${Version}' libopenjp2-7 2>/dev/null || true)"
(cd "$work" && apt-get "${apt_private[@]}" -qq source --download-only "openjpeg2${version:+=$version}")
(cd "$work" && dpkg-source -x openjpeg2_*.dsc openjpeg)

emcmake cmake -S "$work/openjpeg" -B "$work/build" -DCMAKE_BUILD_TYPE=MinSizeRel \
  -DBUILD_SHARED_LIBS=OFF -DBUILD_CODEC=OFF -DBUILD_THIRDPARTY=OFF -DOPJ_USE_THREAD=OFF \
  -DBUILD_PKGCONFIG_FILES=OFF > "$work/configure.log"
emmake cmake --build "$work/build" -j"$(nproc)" --target openjp2 > "$work/build.log"

openjpeg="$(sed -n 's/^Version: //p' "$work"/openjpeg2_*.dsc)"
emscripten="$(dpkg-query -W -f='${Version}' emscripten)"
cat > "$work/header.js" <<HEADER
// j2k_decode.js: OpenJPEG $openjpeg (Debian's source package, its patches applied) and
// web/openjpeg/j2k_decode.c built for WebAssembly (j2k_decode.wasm) by Debian's emscripten
// $emscripten: scripts/build_openjpeg_wasm.sh. Generated: do not edit; rerun the script.
HEADER
emcc -Os -I"$work/openjpeg/src/lib/openjp2" -I"$work/build/src/lib/openjp2" \
  "$web/j2k_decode.c" "$work/build/bin/libopenjp2.a" -o "$web/j2k_decode.js" \
  --extern-pre-js "$work/header.js" \
  -s MODULARIZE=1 -s EXPORT_ES6=1 -s ENVIRONMENT=web,worker -s ALLOW_MEMORY_GROWTH=1 \
  -s FILESYSTEM=0 \
  -s EXPORTED_FUNCTIONS=_j2k_decode,_j2k_free_planes,_j2k_errors,_malloc,_free \
  -s EXPORTED_RUNTIME_METHODS=HEAPU8,HEAP16,HEAP32,UTF8ToString
gzip -9nf "$web/j2k_decode.wasm"
chmod 644 "$web/j2k_decode.wasm.gz"
ls -l "$web"
