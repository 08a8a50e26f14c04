#!/usr/bin/env bash
# End-to-end checks of the `crestline` command: exit codes, messages, and
# that failures leave no output file behind. Usage: test_cli.sh CRESTLINE
set -uo pipefail
crestline=${1:?usage: test_cli.sh path/to/crestline}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# A 30×30 height field z = 0.1 cos(4πx) on [0,2]²: two ridges and valleys.
awk 'BEGIN {
  n = 30; pi = atan2(0, -1);
  for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) {
    x = 2 * i / n; y = 2 * j / n; printf "v %.6f %.6f %.6f\n", x, y, 0.1 * cos(4 * pi * x) }
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
    a = j * (n + 1) + i + 1; printf "f %d %d %d\nf %d %d %d\n", a, a + 1, a + n + 2, a, a + n + 2, a + n + 1 }
}' > "$work/wave.obj"
vertices=$(grep -c '^v ' "$work/wave.obj")

# expect CODE NAME -- ARGS: runs crestline, checks the exit code.
expect() {
  local code=$1 name=$2
  shift 3
  "$crestline" "$@" > "$work/stdout" 2> "$work/stderr"
  local got=$?
  [ "$got" -eq "$code" ] || fail "$name: exit code $got, expected $code ($(head -c 300 "$work/stderr"))"
}
# one_line_naming NAME TEXT: stderr is one line that mentions TEXT.
one_line_naming() {
  [ "$(wc -l < "$work/stderr")" -eq 1 ] || fail "$1: stderr is not one line: $(cat "$work/stderr")"
  grep -qF -- "$2" "$work/stderr" || fail "$1: stderr does not name $2: $(cat "$work/stderr")"
}
absent() { [ ! -e "$2" ] && [ ! -e "$2.tmp" ] || fail "$1: $2 was left behind"; }

# Success in each format.
for ext in obj json svg glb; do
  expect 0 "write .$ext" -- "$work/wave.obj" -o "$work/lines.$ext" --quiet
  [ -s "$work/lines.$ext" ] || fail "write .$ext: no output"
  [ ! -e "$work/lines.$ext.tmp" ] || fail "write .$ext: temporary file left"
  [ ! -s "$work/stderr" ] || fail "write .$ext: --quiet printed $(cat "$work/stderr")"
done
grep -q '^o ridges$' "$work/lines.obj" || fail "OBJ has no 'o ridges'"
grep -q '^o valleys$' "$work/lines.obj" || fail "OBJ has no 'o valleys'"
grep -q '^l [0-9]* [0-9]*' "$work/lines.obj" || fail "OBJ has no polyline"
grep -q '"ridges":\[' "$work/lines.json" || fail "JSON has no ridges"
grep -q '<g id="valleys"' "$work/lines.svg" || fail "SVG has no valleys group"

# Whatever we wrote as JSON parses as JSON (when node is there to check).
if command -v node > /dev/null; then
  node -e 'const j = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    if (!Array.isArray(j.ridges) || !Array.isArray(j.valleys) || typeof j.stats !== "object") process.exit(1);' \
    "$work/lines.json" || fail "lines.json does not parse as the documented JSON"
fi

# --with-mesh: the welded surface first, then the lines numbered after it.
expect 0 "--with-mesh .obj" -- "$work/wave.obj" -o "$work/mesh.obj" --with-mesh --quiet
grep -q '^o surface$' "$work/mesh.obj" || fail "--with-mesh: no 'o surface'"
[ "$(grep -c '^f ' "$work/mesh.obj")" -eq "$(grep -c '^f ' "$work/wave.obj")" ] || fail "--with-mesh: wrong face count"
[ "$(grep -c '^v ' "$work/mesh.obj")" -eq $((vertices + $(grep -c '^v ' "$work/lines.obj"))) ] ||
  fail "--with-mesh: vertices are not the surface's plus the lines'"
awk -v n="$vertices" '/^l / { for (i = 2; i <= NF; i++) if ($i <= n) bad = 1 } END { exit bad }' "$work/mesh.obj" ||
  fail "--with-mesh: a polyline index points into the surface"
[ "$(head -c 4 "$work/lines.glb")" = glTF ] || fail ".glb: no glTF header"
expect 0 "--with-mesh .glb" -- "$work/wave.obj" -o "$work/mesh.glb" --with-mesh --quiet
[ "$(head -c 4 "$work/mesh.glb")" = glTF ] || fail "--with-mesh .glb: no glTF header"
[ ! -e "$work/mesh.glb.tmp" ] || fail "--with-mesh .glb: temporary file left"
# The surface in the GLB reads back (its lines are skipped with a note) and gives lines again.
expect 0 "--with-mesh .glb reads back" -- "$work/mesh.glb" -o "$work/again.obj" --stats
grep -q "\"triangles\":$(grep -c '^f ' "$work/wave.obj")," "$work/stdout" ||
  fail "--with-mesh .glb: read back with another triangle count: $(cat "$work/stdout")"
grep -qi 'line' "$work/stderr" || fail "--with-mesh .glb: reading back did not note the skipped lines"
expect 1 "lines-only .glb has no surface" -- "$work/lines.glb" -o "$work/none.obj" --quiet
absent "lines-only .glb has no surface" "$work/none.obj"
expect 2 "--with-mesh with .svg" -- "$work/wave.obj" -o "$work/mesh.svg" --with-mesh
one_line_naming "--with-mesh with .svg" "--with-mesh"
absent "--with-mesh with .svg" "$work/mesh.svg"

# --stats: one JSON object on stdout.
expect 0 "--stats" -- "$work/wave.obj" -o "$work/stats.obj" --stats --quiet
[ "$(wc -l < "$work/stdout")" -eq 1 ] || fail "--stats: stdout is not one line"
for key in vertices triangles singular_max singular_min ridges valleys creases ridge_length valley_length crease_length crease_angle seconds; do
  grep -q "\"$key\":" "$work/stdout" || fail "--stats: no $key"
done
grep -q "\"vertices\":$vertices," "$work/stdout" || fail "--stats: vertices is not $vertices"
grep -q '"seconds":{"read":[0-9.e-]*,"repair":[0-9.e-]*,"topology":[0-9.e-]*,"presmooth":' "$work/stdout" || fail "--stats: seconds not read, repair, topology, then by stage"
grep -q '"filter":[0-9.e-]*,"creases":[0-9.e-]*,"write":[0-9.e-]*}}' "$work/stdout" || fail "--stats: no write seconds after the stages"
if command -v node > /dev/null; then
  node -e 'JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"))' "$work/stdout" ||
    fail "--stats output does not parse as JSON"
fi

# Every parameter, including a weights file with one number per vertex.
awk -v n="$vertices" 'BEGIN { for (i = 0; i < n; i++) print (i % 2 ? 0.5 : 1) }' > "$work/weights.txt"
expect 0 "all options" -- "$work/wave.obj" -o "$work/all.svg" --presmooth-steps 1 --presmooth-time-step 0.5 \
  --smoothing-steps 2 --smoothing-time-step 0.5 --boundary-rings 1 --fairing-bound 0.2 \
  --fairing-iterations 10 --threshold 0.1 --view top --svg-width 400 --stroke-width 2 --silhouette --svg-surface-tolerance 0.3 \
  --weights "$work/weights.txt" --repair-report
grep -q 'welded_vertices: 0' "$work/stderr" || fail "--repair-report: no counts: $(cat "$work/stderr")"
grep -q '<g id="silhouette"' "$work/all.svg" || fail "--silhouette: no silhouette group"

# Failures: exit code, one line naming the file, no output.
expect 1 "missing input" -- "$work/nope.obj" -o "$work/out.obj"
one_line_naming "missing input" "$work/nope.obj"
absent "missing input" "$work/out.obj"

printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' > "$work/broken.obj"
expect 1 "broken input" -- "$work/broken.obj" -o "$work/out.svg"
one_line_naming "broken input" "$work/broken.obj"
absent "broken input" "$work/out.svg"

head -c 2000 /dev/urandom > "$work/noise.obj"
"$crestline" "$work/noise.obj" -o "$work/out.json" > /dev/null 2>&1
[ $? -ne 0 ] || [ -s "$work/out.json" ] || fail "random bytes: exit 0 but no output"
rm -f "$work/out.json"

# Weights per vertex of the input file also work when repair welds vertices:
# the same height field as a soup, three vertices per triangle.
awk '/^v /{ v[++n] = $0 } /^f /{ print v[$2]; print v[$3]; print v[$4]; k += 3; f = f sprintf("f %d %d %d\n", k - 2, k - 1, k) }
     END { printf "%s", f }' "$work/wave.obj" > "$work/soup.obj"
soup_vertices=$(grep -c '^v ' "$work/soup.obj")
awk -v n="$soup_vertices" 'BEGIN { for (i = 0; i < n; i++) print 0.5 }' > "$work/soup-weights.txt"
expect 0 "weights per input vertex" -- "$work/soup.obj" -o "$work/soup.obj.json" --weights "$work/soup-weights.txt"
grep -q 'Welded' "$work/stderr" || fail "soup: repair did not report welding: $(cat "$work/stderr")"

printf '1\n2\n' > "$work/short.txt"
expect 1 "wrong weight count" -- "$work/wave.obj" -o "$work/out.obj" --weights "$work/short.txt" --quiet
one_line_naming "wrong weight count" "$work/short.txt"
absent "wrong weight count" "$work/out.obj"

expect 1 "missing output folder" -- "$work/wave.obj" -o "$work/no/such/dir/out.obj"
one_line_naming "missing output folder" "$work/no/such/dir/out.obj"

# An existing output is replaced only on success.
echo keep > "$work/keep.obj"
expect 1 "failure keeps old output" -- "$work/broken.obj" -o "$work/keep.obj"
[ "$(cat "$work/keep.obj")" = keep ] || fail "a failed run changed an existing output"

# Usage errors: exit code 2.
cp "$work/wave.obj" "$work/same.obj"
expect 2 "output is the input" -- "$work/same.obj" -o "$work/same.obj"
cmp -s "$work/wave.obj" "$work/same.obj" || fail "the input mesh was overwritten"
expect 2 "unsupported extension" -- "$work/wave.obj" -o "$work/out.png"
one_line_naming "unsupported extension" ".obj, .json, .svg or .glb"
absent "unsupported extension" "$work/out.png"
expect 2 "unknown option" -- "$work/wave.obj" -o "$work/out.obj" --no-such-option
expect 2 "missing -o" -- "$work/wave.obj"
expect 2 "bad view" -- "$work/wave.obj" -o "$work/out.svg" --view sideways
expect 2 "negative steps" -- "$work/wave.obj" -o "$work/out.obj" --smoothing-steps -1
one_line_naming "negative steps" "--smoothing-steps must be a whole number from 0 to 50"

# Every count and time step has a range (the parameter table): outside it, or
# not a number (nan too), is a usage error naming the option, before the mesh
# is read.
long_number=$(printf '9%.0s' $(seq 309))
while read -r flag value; do
  expect 2 "$flag $value" -- "$work/wave.obj" -o "$work/out.obj" "$flag" "$value"
  one_line_naming "$flag $value" "crestline: ${flag%%=*} must be "
  absent "$flag $value" "$work/out.obj"
done << EOF
--smoothing-steps 1000000000
--presmooth-steps 1000000000
--fairing-iterations 1000000000
--smoothing-steps 2.5
--smoothing-steps 0x10
--smoothing-steps auto
--presmooth-time-step -1
--presmooth-time-step nan
--presmooth-time-step 11
--smoothing-time-step inf
--threshold nan
--threshold -1
--threshold 1e
--fairing-bound $long_number
--boundary-rings 21
--short-line-length -0.5
--svg-width 15
--stroke-width 0
--view sideways
EOF
expect 2 "309-digit value" -- "$work/wave.obj" -o "$work/out.obj" --fairing-bound "$long_number"
[ "$(wc -c < "$work/stderr")" -lt 160 ] || fail "309-digit value: the message repeats it: $(cat "$work/stderr")"
expect 2 "missing value" -- "$work/wave.obj" -o "$work/out.obj" --smoothing-steps
one_line_naming "missing value" "--smoothing-steps needs a value"
expect 2 "a flag with a wrong value" -- "$work/wave.obj" -o "$work/out.svg" --silhouette=maybe
one_line_naming "a flag with a wrong value" "--silhouette must be true or false"
expect 2 "a command flag with a wrong value" -- "$work/wave.obj" -o "$work/out.obj" --stats=maybe
one_line_naming "a command flag with a wrong value" "--stats takes no value"
absent "a command flag with a wrong value" "$work/out.obj"
expect 2 "a second input" -- "$work/wave.obj" "$work/wave.obj" -o "$work/out.obj"
one_line_naming "a second input" "unexpected argument"
expect 2 "-o without a value" -- "$work/wave.obj" -o
one_line_naming "-o without a value" "--output needs a value"
# "--" ends the options: a file whose name starts with a dash is an input.
cp "$work/wave.obj" "$work/-dash.obj"
command_path=$(cd "$(dirname "$crestline")" && pwd)/$(basename "$crestline")
(cd "$work" && "$command_path" -q -o dash-out.obj -- -dash.obj) || fail "an input after -- was not read"
[ -s "$work/dash-out.obj" ] || fail "an input after --: no output"
# The bounds themselves are accepted, and "auto" where a parameter has it.
expect 0 "range ends" -- "$work/wave.obj" -o "$work/ends.obj" --quiet --smoothing-steps 0 --presmooth-steps 0 \
  --fairing-iterations 1000 --boundary-rings 0 --threshold auto --presmooth-time-step 10
expect 0 "--threshold inf keeps no line" -- "$work/wave.obj" -o "$work/none.obj" --quiet --threshold inf --stats
grep -q '"ridges":0,"valleys":0' "$work/stdout" || fail "--threshold inf kept lines: $(cat "$work/stdout")"

# The automatic threshold and the same threshold set by hand keep the same lines.
expect 0 "automatic threshold" -- "$work/wave.obj" -o "$work/auto.obj" --quiet --stats
used=$(sed -n 's/.*"threshold":\([^,}]*\).*/\1/p' "$work/stdout")
expect 0 "manual threshold" -- "$work/wave.obj" -o "$work/manual.obj" --quiet --threshold "$used"
cmp -s "$work/auto.obj" "$work/manual.obj" || fail "threshold $used by hand keeps other lines than the automatic one"

# --help documents every option with its default.
expect 0 "--help" -- --help
for option in presmooth-steps presmooth-time-step smoothing-steps smoothing-time-step boundary-rings \
  fairing-bound fairing-iterations threshold view svg-width stroke-width silhouette svg-surface-tolerance \
  weights with-mesh stats quiet repair-report; do
  grep -q -- "--$option" "$work/stdout" || fail "--help does not document --$option"
done
help=$(tr -s ' \n' ' ' < "$work/stdout")
grep -qF -- '--smoothing-steps N Implicit extremality smoothing steps (paper 5.1); 0: off (0 to 50; default 3)' <<< "$help" ||
  fail "--help: no range or default for --smoothing-steps"
grep -qF -- '(auto or 0 to inf; default auto)' <<< "$help" || fail "--help: no range or default for --threshold"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
