#!/bin/sh
# Installs (or uninstalls) the built C library: called by the root Makefile (`make install`,
# `make uninstall`), which passes everything through the environment:
#   PREFIX DESTDIR LIBDIR INCLUDEDIR  where (LIBDIR and INCLUDEDIR relative to PREFIX)
#   VERSION ABI                      package version (Cargo.toml), ABI version (rocking.h)
#   BUILD                            cargo's output directory (target/dist)
#   NATIVE_LIBS                      what the static library needs (-lgcc_s -lm ...)
#   STRIP                            strip program, for the static library's debug sections
#
# Installs all or nothing: everything is staged under $BUILD/stage first, each destination is
# probed for writing, the files are copied next to their final names and renamed into place
# only once every copy has succeeded. On any failure what this run created is removed.
set -eu

die() { echo "rocking install: $*" >&2; exit 1; }

for v in PREFIX LIBDIR INCLUDEDIR VERSION ABI BUILD; do
    eval "test -n \"\${$v:-}\"" || die "$v is not set (run it through make install)"
done
DESTDIR=${DESTDIR:-}
case "$PREFIX" in /*) ;; *) die "PREFIX must be an absolute path, got '$PREFIX'" ;; esac
case "$LIBDIR$INCLUDEDIR" in /*|*..*) die "LIBDIR and INCLUDEDIR are relative to PREFIX, got '$LIBDIR', '$INCLUDEDIR'" ;; esac
DEST=$DESTDIR$PREFIX

# What is installed, relative to the prefix: shared library (real file, soname link, link for
# the linker), static library, header, pkg-config file, CMake package.
REAL=librocking.so.$VERSION
SONAME=librocking.so.$ABI
CMAKEDIR=$LIBDIR/cmake/rocking
FILES="$LIBDIR/$REAL $LIBDIR/$SONAME $LIBDIR/librocking.so $LIBDIR/librocking.a $INCLUDEDIR/rocking.h $LIBDIR/pkgconfig/rocking.pc $CMAKEDIR/rockingConfig.cmake $CMAKEDIR/rockingConfigVersion.cmake"

# The real file an installed soname link points to, if it is one of ours (librocking.so.X in the
# same directory): the file of the version installed before, whatever this build's version is.
linked_real() {
    t=$(readlink "$DEST/$LIBDIR/$SONAME" 2>/dev/null) || return 0
    case "$t" in librocking.so.*/*|*/*) ;; librocking.so.*) echo "$t" ;; esac
}

uninstall() {
    removed=0
    # After a version bump the installed real file is not this version's: the soname link says
    # which it is.
    old=$(linked_real)
    if [ -n "$old" ] && [ "$old" != "$REAL" ] && [ -f "$DEST/$LIBDIR/$old" ]; then
        rm -f "$DEST/$LIBDIR/$old" || die "cannot remove $DEST/$LIBDIR/$old"
        echo "removed $DEST/$LIBDIR/$old"
        removed=$((removed + 1))
    fi
    for f in $FILES; do
        if [ -e "$DEST/$f" ] || [ -L "$DEST/$f" ]; then
            rm -f "$DEST/$f" || die "cannot remove $DEST/$f"
            echo "removed $DEST/$f"
            removed=$((removed + 1))
        fi
    done
    # The package's own directory; the shared ones (lib, include, pkgconfig, cmake) stay.
    rmdir "$DEST/$CMAKEDIR" 2>/dev/null || true
    [ "$removed" -gt 0 ] || echo "rocking: nothing to uninstall under $DEST"
}

stage() {
    S=$BUILD/stage
    rm -rf "$S"
    mkdir -p "$S/$LIBDIR/pkgconfig" "$S/$CMAKEDIR" "$S/$INCLUDEDIR"
    for f in "$BUILD/librocking.so" "$BUILD/librocking.a" include/rocking.h; do
        [ -f "$f" ] || die "$f is missing: build first (make)"
    done
    cp "$BUILD/librocking.so" "$S/$LIBDIR/$REAL"
    ln -s "$REAL" "$S/$LIBDIR/$SONAME"
    ln -s "$SONAME" "$S/$LIBDIR/librocking.so"
    cp "$BUILD/librocking.a" "$S/$LIBDIR/librocking.a"
    if command -v "${STRIP:-strip}" >/dev/null 2>&1; then
        "${STRIP:-strip}" --strip-debug "$S/$LIBDIR/librocking.a"
    fi
    cp include/rocking.h "$S/$INCLUDEDIR/rocking.h"
    chmod 644 "$S/$LIBDIR/librocking.a" "$S/$INCLUDEDIR/rocking.h"
    chmod 755 "$S/$LIBDIR/$REAL"
    up=$(echo "$CMAKEDIR" | sed 's|[^/][^/]*|..|g')
    cmake_libs=$(echo "$NATIVE_LIBS" | sed 's/-l//g; s/^ *//; s/ *$//; s/  */;/g')
    major=${VERSION%%.*}; rest=${VERSION#*.}; minor=${rest%%.*}
    pointer=$(( $(getconf LONG_BIT) / 8 ))
    # Values for sed's replacement: `\`, `&` and the delimiter `|` taken literally (a prefix
    # such as /opt/R&D).
    lit() { printf '%s' "$1" | sed 's/[\\&|]/\\&/g'; }
    PREFIX_S=$(lit "$PREFIX"); LIBDIR_S=$(lit "$LIBDIR"); INCLUDEDIR_S=$(lit "$INCLUDEDIR")
    for t in rocking.pc:$LIBDIR/pkgconfig rockingConfig.cmake:$CMAKEDIR rockingConfigVersion.cmake:$CMAKEDIR; do
        name=${t%%:*}; dir=${t#*:}
        sed -e "s|@PREFIX@|$PREFIX_S|g" -e "s|@LIBDIR@|$LIBDIR_S|g" -e "s|@INCLUDEDIR@|$INCLUDEDIR_S|g" \
            -e "s|@VERSION@|$VERSION|g" -e "s|@VERSION_MAJOR@|$major|g" -e "s|@VERSION_MINOR@|$minor|g" \
            -e "s|@ABI@|$ABI|g" -e "s|@NATIVE_LIBS@|$NATIVE_LIBS|g" -e "s|@NATIVE_LIBS_CMAKE@|$cmake_libs|g" \
            -e "s|@CMAKE_TO_PREFIX@|$up|g" -e "s|@SIZEOF_VOID_P@|$pointer|g" \
            "dist/$name.in" > "$S/$dir/$name"
        chmod 644 "$S/$dir/$name"
        ! grep -n '@[A-Z_]*@' "$S/$dir/$name" || die "unsubstituted template variable in $name"
    done
}

# The nearest existing ancestor of a path.
existing() {
    p=$1
    while [ ! -e "$p" ] && [ ! -L "$p" ]; do p=$(dirname "$p"); done
    echo "$p"
}

install() {
    stage
    # Preflight: every destination directory exists as a directory or can be created, every
    # destination file is not a directory, and the nearest existing ancestor accepts a file.
    for f in $FILES; do
        d=$(dirname "$DEST/$f")
        a=$(existing "$d")
        [ -d "$a" ] || die "cannot install into $d: $a is not a directory"
        [ ! -d "$DEST/$f" ] || [ -L "$DEST/$f" ] || die "cannot install $DEST/$f: it is a directory"
        probe=$(mktemp "$a/.rocking-probe.XXXXXX" 2>/dev/null) || die "cannot write into $a (to install $DEST/$f): permission denied or read-only"
        rm -f "$probe"
    done
    created=""
    copied=""
    rollback() {
        for c in $copied; do rm -f "$c" || true; done
        for d in $created; do rmdir "$d" 2>/dev/null || true; done
        die "$1; nothing was installed"
    }
    for f in $FILES; do
        d=$(dirname "$DEST/$f")
        if [ ! -d "$d" ]; then
            # Record each directory this run creates, deepest last, to remove them on failure.
            missing=""
            p=$d
            while [ ! -d "$p" ]; do missing="$p $missing"; p=$(dirname "$p"); done
            mkdir -p "$d" 2>/dev/null || rollback "cannot create $d"
            for m in $missing; do created="$m $created"; done
        fi
        tmp="$d/.$(basename "$f").rocking-new"
        cp -P -T "$BUILD/stage/$f" "$tmp" 2>/dev/null || rollback "cannot write $tmp"
        copied="$copied $tmp"
    done
    old=$(linked_real)
    for f in $FILES; do
        d=$(dirname "$DEST/$f")
        mv -f -T "$d/.$(basename "$f").rocking-new" "$DEST/$f" || die "cannot rename into $DEST/$f"
        echo "installed $DEST/$f"
    done
    # The same ABI's earlier version, which no link names any more (another ABI's soname link
    # and file stay: binaries linked against it still load them).
    if [ -n "$old" ] && [ "$old" != "$REAL" ] && [ -f "$DEST/$LIBDIR/$old" ]; then
        rm -f "$DEST/$LIBDIR/$old" && echo "removed the earlier $DEST/$LIBDIR/$old"
    fi
}

case "${1:-}" in
    install) install ;;
    uninstall) uninstall ;;
    *) die "usage: install.sh install|uninstall (through make install / make uninstall)" ;;
esac
