#!/bin/sh
# The mutation pass (docs/testing.md): each mutant of tests/mutation/mutants.txt is applied to a
# COPY of the source tree, the test target it names is rebuilt, its tests are run, and the tests
# that fail (that catch the mutant) are listed; then the file is restored. Not part of ctest.
#
#   tests/mutation/run_mutants.sh [COPY [BUILD [MUTANT_ID...]]]
#
# COPY (default /tmp/feint-mutants-src) is made from this tree when it does not exist (never the
# tree itself: the script refuses to mutate it); BUILD (default COPY-build) is a Release build of
# it with the tests on. A mutant that no test catches is printed as SURVIVED. Exit status: the
# number of survivors.
set -eu
here=$(cd "$(dirname "$0")/../.." && pwd)
copy=${1:-/tmp/feint-mutants-src}
build=${2:-$copy-build}
[ $# -gt 0 ] && shift
[ $# -gt 0 ] && shift
case "$(cd "$(dirname "$copy")" && pwd)/$(basename "$copy")" in
  "$here") echo "run_mutants.sh: COPY must not be the source tree itself" >&2; exit 2 ;;
esac
if [ ! -d "$copy" ]; then
  mkdir -p "$copy"
  (cd "$here" && tar --exclude=.git --exclude='./build*' -cf - .) | (cd "$copy" && tar -xf -)
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$copy" -B "$build" -DCMAKE_BUILD_TYPE=Release -DFEINT_BUILD_TESTS=ON >/dev/null
fi
jobs=${JOBS:-2}
survivors=0
python3 - "$here/tests/mutation/mutants.txt" "$@" > "$build/mutants.list" <<'PY'
import sys
want = set(sys.argv[2:])
blocks, cur = [], None
for line in open(sys.argv[1], encoding="utf-8"):
    line = line.rstrip("\n")
    if line.startswith("id "):
        f = [x.strip() for x in line[3:].split("|")]
        cur = {"id": f[0], "file": f[1], "target": f[2], "filter": f[3]}
        blocks.append(cur)
    elif line.startswith("- "):
        cur["old"] = line[2:]
    elif line.startswith("+ "):
        cur["new"] = line[2:]
for b in blocks:
    if not want or b["id"] in want:
        print("\t".join([b["id"], b["file"], b["target"], b["filter"], b["old"], b["new"]]))
PY
failed_tests() {  # the tests a gtest log names as failed, or "(exit N)" when it died before
  names=$(sed -n 's/^\[  FAILED  \] \([A-Za-z0-9_/]*\.[A-Za-z0-9_/]*\).*/\1/p' "$1" | sort -u)
  if [ -z "$names" ] && [ "$2" -ne 0 ]; then names="(exit $2)"; fi
  echo "$names"
}
# The unmutated build first: its failures (there should be none) are not counted as catches.
cut -f3,4 "$build/mutants.list" | sort -u | while IFS="$(printf '\t')" read -r target filter; do
  # The collect tests that run a server or kill one exec the feint program: build it too.
  if [ "$target" = feint_tests_collect ]; then also=feint; else also=$target; fi
  cmake --build "$build" --target "$target" "$also" -j"$jobs" >"$build/baseline.build.log" 2>&1
  rc=0; "$build/tests/$target" --gtest_filter="$filter" >"$build/baseline.log" 2>&1 || rc=$?
  failed_tests "$build/baseline.log" "$rc" > "$build/baseline.$target.failed"
  echo "baseline $target '$filter': $(tr '\n' ' ' < "$build/baseline.$target.failed")(failures)"
done
while IFS="$(printf '\t')" read -r id file target filter old new; do
  src="$copy/$file"
  cp "$src" "$src.orig"
  if ! python3 - "$src" "$old" "$new" <<'PY'
import sys
path, old, new = sys.argv[1], sys.argv[2].replace("\\n", "\n"), sys.argv[3].replace("\\n", "\n")
text = open(path, encoding="utf-8").read()
if text.count(old) != 1:
    sys.exit(f"{path}: the original text occurs {text.count(old)} times, not once: {old!r}")
open(path, "w", encoding="utf-8").write(text.replace(old, new))
PY
  then
    echo "$id: NOT APPLIED (the source changed; update tests/mutation/mutants.txt)"
    mv "$src.orig" "$src"
    continue
  fi
  if ! cmake --build "$build" --target "$target" -j"$jobs" >"$build/$id.build.log" 2>&1; then
    echo "$id: does not build (see $build/$id.build.log)"
  else
    rc=0; "$build/tests/$target" --gtest_filter="$filter" >"$build/$id.test.log" 2>&1 || rc=$?
    caught=$(failed_tests "$build/$id.test.log" "$rc" | grep -vxF -f "$build/baseline.$target.failed" | tr '\n' ' ')
    if [ -n "$caught" ]; then
      echo "$id: caught by $caught"
    else
      echo "$id: SURVIVED ($target --gtest_filter='$filter')"
      survivors=$((survivors + 1))
    fi
  fi
  mv "$src.orig" "$src"
  touch "$src"
done < "$build/mutants.list"
exit "$survivors"
