#!/usr/bin/env bash
# The installed library as its users meet it, from the installed files only (issue 12):
#   1. make install into a fresh temporary prefix: exactly the documented files, the soname;
#   2. the header alone compiles as C89, C99, C11, C++98, C++11 and C++17 (-pedantic -Werror);
#   3. a C99 client (c_examples/element_skeleton.c) built with pkg-config, linked shared and
#      static, and a C++ client (tests/install/client.cpp) built with CMake's find_package,
#      linked shared and static -- each copied into a scratch directory with no include path
#      into the source tree -- run, and run again under valgrind;
#   4. DESTDIR staging; make uninstall removes exactly what install put there;
#   5. an up-to-date build installs without cargo (`make`, then `sudo make install`); bad input:
#      no cargo, a prefix that cannot be written, a failure half-way: a message, a non-zero exit
#      and nothing installed.
# Needs cc, c++, cmake, pkg-config, valgrind, readelf (.ci/run installs them).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
for tool in cc c++ cmake pkg-config valgrind readelf; do
    command -v "$tool" >/dev/null || { echo "tests/install: $tool is missing" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
passed=0
failed=0
ok() { echo "  ok   $*"; passed=$((passed + 1)); }
fail() { echo "  FAIL $*"; failed=$((failed + 1)); }
check() { local what=$1; shift; if "$@"; then ok "$what"; else fail "$what"; fi; }
# A valgrind run: no error, no leak.
vg() { valgrind -q --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite "$@" > /dev/null; }

echo "== make install PREFIX=$prefix"
make --no-print-directory install PREFIX="$prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log"; exit 1; }
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
abi=$(sed -n 's/^#define ROCKING_ABI_VERSION \([0-9]*\).*/\1/p' include/rocking.h)
expected="include/rocking.h
lib/cmake/rocking/rockingConfig.cmake
lib/cmake/rocking/rockingConfigVersion.cmake
lib/librocking.a
lib/librocking.so
lib/librocking.so.$abi
lib/librocking.so.$version
lib/pkgconfig/rocking.pc"
expected=$(echo "$expected" | LC_ALL=C sort)
got=$(cd "$prefix" && find . \( -type f -o -type l \) | sed 's|^\./||' | LC_ALL=C sort)
check "installed files are exactly the documented ones" test "$got" = "$expected" || echo "$got"
check "soname librocking.so.$abi" bash -c "readelf -d '$prefix/lib/librocking.so.$version' | grep -q 'SONAME.*\[librocking.so.$abi\]'"
check "librocking.so -> librocking.so.$abi -> librocking.so.$version" \
    test "$(readlink "$prefix/lib/librocking.so")" = "librocking.so.$abi" -a "$(readlink "$prefix/lib/librocking.so.$abi")" = "librocking.so.$version"
check "installed header is the checked-in one" cmp -s include/rocking.h "$prefix/include/rocking.h"
check "installing again over it succeeds" bash -c "make --no-print-directory install PREFIX='$prefix' > '$work/reinstall.log' 2>&1 \
    && [ \"\$(cd '$prefix' && find . \( -type f -o -type l \) | sed 's|^\./||' | LC_ALL=C sort)\" = '$expected' ]"
echo "   shared library $(stat -c %s "$prefix/lib/librocking.so.$version") bytes, static $(stat -c %s "$prefix/lib/librocking.a") bytes"

echo "== the header alone"
printf '#include <rocking.h>\nint main(void) { return (int)rocking_abi_version() - ROCKING_ABI_VERSION; }\n' > "$work/h.c"
cp "$work/h.c" "$work/h.cpp"
for std in c89 c99 c11; do
    check "header compiles as $std" cc -std=$std -Wall -Wextra -pedantic -Werror -I"$prefix/include" -c "$work/h.c" -o "$work/h.o"
done
for std in c++98 c++11 c++17; do
    check "header compiles as $std" c++ -std=$std -Wall -Wextra -pedantic -Werror -I"$prefix/include" -c "$work/h.cpp" -o "$work/h.o"
done

# The clients, in scratch directories: nothing of the source tree on their include paths.
mkdir -p "$work/c" "$work/cxx"
cp c_examples/element_skeleton.c c_examples/rocking_samples.h "$work/c/"
cp tests/install/CMakeLists.txt tests/install/client.cpp c_examples/rocking_samples.h "$work/cxx/"
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
libdir=$(pkg-config --variable=libdir rocking)

echo "== C99 client with pkg-config"
check "pkg-config --modversion rocking = $version" test "$(pkg-config --modversion rocking)" = "$version"
check "pkg-config --static --libs has Libs.private" bash -c "pkg-config --static --libs rocking | grep -q -- '-lpthread'"
cd "$work/c"
check "builds, shared" cc -std=c99 -Wall -Wextra -Werror -pedantic element_skeleton.c -o skeleton-shared \
    $(pkg-config --cflags --libs rocking) -Wl,-rpath,"$libdir" -lm
check "builds, static" cc -std=c99 -Wall -Wextra -Werror -pedantic element_skeleton.c -o skeleton-static \
    $(pkg-config --cflags rocking) -Wl,-Bstatic -lrocking -Wl,-Bdynamic -Wl,--as-needed $(pkg-config --static --libs rocking) -lm
check "shared build needs librocking.so.$abi" bash -c "readelf -d skeleton-shared | grep -q 'NEEDED.*\[librocking.so.$abi\]'"
check "static build needs no librocking" bash -c "! readelf -d skeleton-static | grep -q 'NEEDED.*librocking'"
for exe in skeleton-shared skeleton-static; do
    check "$exe reproduces the thesis 4.2 events" bash -c "./$exe > $exe.out && grep -q '^done: 3 events' $exe.out && grep -q '^EVENT kind=impact t=0.1958' $exe.out"
    check "$exe clean under valgrind" vg ./$exe
done
cd "$root"

echo "== C++ client with CMake"
for kind in shared static; do
    static=$([ $kind = static ] && echo ON || echo OFF)
    check "cmake configure + build, $kind" bash -c "cmake -S '$work/cxx' -B '$work/cxx/build-$kind' -DCMAKE_PREFIX_PATH='$prefix' \
        -Drocking_USE_STATIC_LIBS=$static > '$work/cmake-$kind.log' 2>&1 && cmake --build '$work/cxx/build-$kind' >> '$work/cmake-$kind.log' 2>&1" \
        || cat "$work/cmake-$kind.log"
    exe=$work/cxx/build-$kind/client
    if [ $kind = shared ]; then
        check "CMake shared build needs librocking.so.$abi" bash -c "readelf -d '$exe' | grep -q 'NEEDED.*\[librocking.so.$abi\]'"
    else
        check "CMake static build needs no librocking" bash -c "! readelf -d '$exe' | grep -q 'NEEDED.*librocking'"
    fi
    check "C++ client, $kind: Eq. 11" bash -c "'$exe' | grep -q ': ok$'"
    check "C++ client, $kind, clean under valgrind" vg "$exe"
done
# A merged-/usr system (/lib -> usr/lib): CMake may find the package through the link, from the
# prefix "/", as <prefix>/lib/cmake/rocking; the targets must still point at /usr. Simulated
# under $work/merged with the link merged/lib -> usr/lib and CMAKE_PREFIX_PATH=merged.
make --no-print-directory install PREFIX="$work/merged/usr" > "$work/merged.log" 2>&1
ln -s usr/lib "$work/merged/lib"
check "CMake package found through a /lib -> /usr/lib link" bash -c "cmake -S '$work/cxx' -B '$work/cxx/build-merged' \
    -DCMAKE_PREFIX_PATH='$work/merged' > '$work/cmake-merged.log' 2>&1 && grep -q 'merged/lib/cmake/rocking' '$work/cxx/build-merged/CMakeCache.txt' \
    && cmake --build '$work/cxx/build-merged' >> '$work/cmake-merged.log' 2>&1 && '$work/cxx/build-merged/client' | grep -q ': ok$'"
mkdir -p "$work/v"
printf 'cmake_minimum_required(VERSION 3.13)\nproject(p LANGUAGES C)\nfind_package(rocking 0.2 REQUIRED)\n' > "$work/v/CMakeLists.txt"
check "find_package(rocking 0.2) refuses $version" bash -c "! cmake -S '$work/v' -B '$work/v/build' -DCMAKE_PREFIX_PATH='$prefix' > '$work/v.log' 2>&1"

echo "== DESTDIR, uninstall"
make --no-print-directory install DESTDIR="$work/stage" PREFIX=/opt/rocking > "$work/destdir.log" 2>&1
check "DESTDIR: files under DESTDIR/PREFIX" test -f "$work/stage/opt/rocking/lib/librocking.so.$version" -a ! -e /opt/rocking/lib/librocking.a
check "DESTDIR: rocking.pc names the final prefix" grep -q '^prefix=/opt/rocking$' "$work/stage/opt/rocking/lib/pkgconfig/rocking.pc"
touch "$prefix/lib/someone-elses.so"
make --no-print-directory uninstall PREFIX="$prefix" > "$work/uninstall.log" 2>&1
left=$(cd "$prefix" && find . \( -type f -o -type l \) | sed 's|^\./||')
check "uninstall removes exactly what was installed" test "$left" = "lib/someone-elses.so" -a ! -e "$prefix/lib/cmake/rocking"

# A version bump within one ABI: installing the new version over the old removes the old real
# file (no link names it any more), and uninstall with the old sources removes the new one.
bump=$work/bump
make --no-print-directory install PREFIX="$bump" > "$work/bump0.log" 2>&1
make --no-print-directory install PREFIX="$bump" VERSION=99.0.0 > "$work/bump1.log" 2>&1
check "a newer version installed over an older one replaces its real file" bash -c \
    "[ \"\$(readlink '$bump/lib/librocking.so.$abi')\" = librocking.so.99.0.0 ] && [ -f '$bump/lib/librocking.so.99.0.0' ] \
     && [ ! -e '$bump/lib/librocking.so.$version' ]"
make --no-print-directory uninstall PREFIX="$bump" > "$work/bump2.log" 2>&1
check "uninstall after a version bump removes the installed version's file" \
    test -z "$(cd "$bump" && find . \( -type f -o -type l \))"
# A prefix with characters that sed's replacement would take as commands.
amp="$work/R&D|x"
make --no-print-directory install PREFIX="$amp" > "$work/amp.log" 2>&1 || true
check "a prefix with & and |: rocking.pc and the CMake package name it as given" bash -c \
    "grep -qxF 'prefix=$amp' '$amp/lib/pkgconfig/rocking.pc' && grep -qF '$amp' '$amp/lib/cmake/rocking/rockingConfig.cmake'"

echo "== bad input"
bad=$work/bad
# `make` then `sudo make install`: root has no cargo on its PATH (sudo's secure_path), and an
# up-to-date build is installed without running cargo (nor leaving root-owned files in target/).
check "built: make install without cargo installs the build" bash -c \
    "make --no-print-directory install CARGO=/nonexistent/cargo PREFIX='$bad/p0' > '$work/b0.log' 2>&1 \
     && cmp -s include/rocking.h '$bad/p0/include/rocking.h'"
# -W: as if Cargo.toml had just changed, so that the build is out of date.
check "out of date, no cargo: message, non-zero exit, nothing installed" bash -c \
    "! make --no-print-directory -W Cargo.toml install CARGO=/nonexistent/cargo PREFIX='$bad/p1' > '$work/b1.log' 2>&1 && grep -q 'cargo not found' '$work/b1.log' && [ ! -e '$bad/p1' ]"
mkdir -p "$bad" && echo file > "$bad/a-file"
check "prefix under a file: message, non-zero exit" bash -c \
    "! make --no-print-directory install PREFIX='$bad/a-file/p' > '$work/b2.log' 2>&1 && grep -q 'rocking install: cannot install into' '$work/b2.log'"
check "read-only prefix: message, non-zero exit" bash -c \
    "! make --no-print-directory install PREFIX=/proc/rocking > '$work/b3.log' 2>&1 && grep -q 'rocking install: cannot' '$work/b3.log'"
mkdir -p "$bad/p4" && echo file > "$bad/p4/include"
check "include is a file: message, non-zero exit, nothing installed" bash -c \
    "! make --no-print-directory install PREFIX='$bad/p4' > '$work/b4.log' 2>&1 && grep -q 'is not a directory' '$work/b4.log' \
     && [ -z \"\$(cd '$bad/p4' && find . -mindepth 1 ! -name include)\" ]"
# A copy that fails after the library files were copied (where the header's temporary copy
# goes, a directory stands): everything copied and every directory created is removed again.
mkdir -p "$bad/p5/include/.rocking.h.rocking-new/x"
check "failure half-way through the copies: rolled back" bash -c \
    "! make --no-print-directory install PREFIX='$bad/p5' > '$work/b5.log' 2>&1 && grep -q 'nothing was installed' '$work/b5.log' \
     && [ -z \"\$(cd '$bad/p5' && find . -mindepth 1 ! -path './include*')\" ]"

echo "install: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
