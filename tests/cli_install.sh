#!/usr/bin/env bash
# make install / make uninstall: a DESTDIR-staged install (the files in place, no DESTDIR in them),
# and an install into a temporary PREFIX that is then used: pkg-config, a program compiled and
# linked against the installed library, the installed bin/jointrom drawing its plot with the
# installed scripts (no JOINTROM_SHARE), and JOINTROM_SHARE still taking precedence.
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
unset JOINTROM_SHARE
mk() { make --no-print-directory "$@" > "$tmp/make.log" 2>&1 || { tail -5 "$tmp/make.log"; return 1; }; }

# staged: DESTDIR=stage PREFIX=/opt/jointrom
st=$tmp/stage; sp=$st/opt/jointrom
check "mk install DESTDIR='$st' PREFIX=/opt/jointrom" "make install DESTDIR PREFIX succeeds"
missing=
for f in bin/jointrom lib/libjointrom.a lib/pkgconfig/jointrom.pc include/jointrom.h \
         $(cd include && ls jointrom/*.h jointrom/private/*.h 2>/dev/null | sed 's|^|include/|') \
         $(cd share && ls *.gp | sed 's|^|share/jointrom/|'); do
  [ -f "$sp/$f" ] || missing="$missing $f"
done
check "[ -z '$missing' ]" "staged install holds bin, lib, pkgconfig, headers and plot scripts${missing:+ (missing:$missing)}"
check "[ -x '$sp/bin/jointrom' ] && [ ! -x '$sp/lib/libjointrom.a' ]" "staged modes: binary executable, library not"
check "grep -qx 'prefix=/opt/jointrom' '$sp/lib/pkgconfig/jointrom.pc' && ! grep -rqF '$st' '$st'" "staged files name PREFIX, never DESTDIR"
check "mk uninstall DESTDIR='$st' PREFIX=/opt/jointrom && [ -z \"\$(find '$st' -type f)\" ]" "make uninstall removes every installed file"

# used: PREFIX=tmp/prefix
p=$tmp/prefix
check "mk install PREFIX='$p'" "make install PREFIX succeeds"
export PKG_CONFIG_PATH=$p/lib/pkgconfig
fl=$(pkg-config --cflags --libs jointrom 2>&1)
check "echo \"\$fl\" | grep -qF -- '-I$p/include' && echo \"\$fl\" | grep -qF -- '-L$p/lib -ljointrom' && echo \"\$fl\" | grep -q -- '-lslepc'" "pkg-config --cflags --libs jointrom: installed include and lib dirs, SLEPc"
check "[ \"\$(pkg-config --variable=sharedir jointrom)\" = '$p/share/jointrom' ]" "pkg-config --variable=sharedir jointrom"
cat > "$tmp/use.c" << 'EOF'
#include <jointrom.h>
#include <jointrom/private/contactimpl.h>
#include <slepcsys.h>
int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  PetscCall(JRInitializePackage());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "jointrom %d.%d package initialized\n", JR_VERSION_MAJOR, JR_VERSION_MINOR));
  PetscCall(SlepcFinalize());
  return 0;
}
EOF
cc=$(pkg-config --variable=ccompiler jointrom)
check "$cc -o '$tmp/use' '$tmp/use.c' \$(pkg-config --cflags --libs jointrom) > '$tmp/cc.log' 2>&1 || { head -5 '$tmp/cc.log'; false; }" "a program compiles and links against the installed library ($cc, pkg-config)"
check "'$tmp/use' | grep -q 'package initialized'" "the program runs SlepcInitialize and JRInitializePackage"

# the installed binary, run from elsewhere, finds the installed plot scripts: they get a line that
# leaves a mark, so a fallback to the source tree's share/ would show
if command -v gnuplot > /dev/null; then
  echo "set print '$tmp/mark'; print 'installed'" >> "$p/share/jointrom/plot_loop.gp"
  (cd "$tmp" && "$p/bin/jointrom" -options_file "$OLDPWD/runs/element_nv.opts" -element_loop "$tmp/x" > "$tmp/run.log" 2>&1)
  check "[ \"\$(head -c 4 '$tmp/x.png' | tail -c 3)\" = PNG ] && [ -s '$tmp/x.csv' ]" "installed bin/jointrom writes the loop CSV and PNG (JOINTROM_SHARE unset)"
  check "[ \"\$(cat '$tmp/mark' 2>/dev/null)\" = installed ]" "installed bin/jointrom plots with PREFIX/share/jointrom's scripts"
  mkdir "$tmp/empty"
  o=$(cd "$tmp" && JOINTROM_SHARE=$tmp/empty "$p/bin/jointrom" -options_file "$OLDPWD/runs/element_nv.opts" -element_loop "$tmp/y" 2>&1)
  check "echo \"\$o\" | grep -qF 'gnuplot failed on $tmp/empty/plot_loop.gp' && [ ! -e '$tmp/y.png' ]" "JOINTROM_SHARE takes precedence over the installed scripts"
fi
