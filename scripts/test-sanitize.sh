#!/usr/bin/env bash
# Runs the tests of a sanitizer build except those in tests/sanitize-skip.txt (one test name per
# line, '#' comments; a name ending in '*' skips every test whose name starts with the rest), two
# at a time. The tests to run are passed to ctest by number: a regex of some eighty names is more
# than ctest's regular expressions hold, and it silently skipped the wrong tests.
#   scripts/test-sanitize.sh BUILD_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$1"
skip=$(grep -v '^#' "$root/tests/sanitize-skip.txt" | grep -v '^$' || true)
# "  Test  #12: Name  # GetParam() = ..." -> "12 Name"
numbers=$(ctest -N | sed -n 's/^ *Test *#\([0-9]*\): \([^ ]*\).*$/\1 \2/p' |
          awk -v skip="$skip" 'BEGIN { n = split(skip, s, "\n")
                                       for (i = 1; i <= n; ++i)
                                         if (s[i] ~ /\*$/) prefix[substr(s[i], 1, length(s[i]) - 1)] = 1
                                         else skipped[s[i]] = 1 }
                               { for (p in prefix) if (index($2, p) == 1) next }
                               !($2 in skipped) { printf "%s%s", (count++ ? "," : ""), $1 }')
echo "test-sanitize: running $(echo "$numbers" | tr ',' '\n' | grep -c .) of $(ctest -N | grep -c ' Test *#') tests"
ctest -j2 --output-on-failure --timeout 1800 -I "0,0,0,$numbers"
