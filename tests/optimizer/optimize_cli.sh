#!/usr/bin/env bash
# `cinepath optimize` through the real binary: bad input exits 2 naming the file and the key, writing
# nothing; --strict exits 3 and writes nothing; the output is a plan every stage reads, marked as
# optimized; the same bytes on every run and at any thread count.
#   tests/optimizer/optimize_cli.sh CINEPATH SOURCE_DIR
set -euo pipefail
CINEPATH=$1
SRC=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$CINEPATH" plan "$SRC/examples/orbit_shots.json" -o "$T/plan.json"

# A plan optimized without a scene: same schema, marked, feasible, readable by export and info.
"$CINEPATH" optimize "$T/plan.json" --quality draft --report "$T/report.json" -o "$T/opt.json"
python3 - "$T/opt.json" "$T/report.json" << 'PY'
import json, sys
plan, report = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert plan["schema"] == "cinepath.plan/1", plan["schema"]
assert plan["optimized"]["by"] == "cinepath optimize" and plan["optimized"]["quality"] == "draft"
assert plan["optimized"]["scene"] is None
for key in ("terms", "total", "limits", "shots", "solver", "skipped"):
    assert key in report, key
assert "clearance: no scene mesh" in report["skipped"], report["skipped"]
assert report["total"]["after"] <= report["total"]["before"] + 1e-9
PY
"$CINEPATH" export "$T/opt.json" --format qgc-plan -o "$T/mission" > /dev/null
"$CINEPATH" info "$(ls "$T"/mission/*.plan | head -1)" > /dev/null

# The same bytes on every run, and on one core.
"$CINEPATH" optimize "$T/plan.json" --quality draft -o "$T/opt2.json"
taskset -c 0 "$CINEPATH" optimize "$T/plan.json" --quality draft -o "$T/opt3.json"
cmp "$T/opt.json" "$T/opt2.json" || fail "two runs differ"
cmp "$T/opt.json" "$T/opt3.json" || fail "one core differs"
"$CINEPATH" optimize "$T/plan.json" --quality draft -o - | cmp - "$T/opt.json" || fail "stdout differs"

# Bad input: exit 2, the file and the key named, nothing written.
expect_refusal() {  # expect_refusal CODE PATTERN ARGS...
  local code=$1 pattern=$2
  shift 2
  rm -f "$T/out.json"
  set +e
  "$CINEPATH" optimize "$@" -o "$T/out.json" 2> "$T/err"
  local rc=$?
  set -e
  [[ $rc == "$code" ]] || fail "exit $rc, expected $code for $*: $(cat "$T/err")"
  grep -q -- "$pattern" "$T/err" || fail "message lacks '$pattern': $(cat "$T/err")"
  [[ ! -e $T/out.json ]] || fail "output written for $*"
}
sed 's#"cinepath.plan/1"#"cinepath.plan/9"#' "$T/plan.json" > "$T/other_schema.json"
expect_refusal 2 "other_schema.json: schema" "$T/other_schema.json"
python3 - "$T/plan.json" "$T/nan.json" << 'PY'
import json, sys
text = open(sys.argv[1]).read()
plan = json.loads(text)
plan["samples"][5]["focal_length_mm"] = float("nan")
open(sys.argv[2], "w").write(json.dumps(plan))  # Python writes the bare token NaN
PY
expect_refusal 2 "nan.json" "$T/nan.json"
printf '{"origin": {"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0}, "mesh": "absent.glb"}' > "$T/scene.json"
expect_refusal 2 "scene.json: mesh" "$T/plan.json" --scene "$T/scene.json"
expect_refusal 2 "quality" "$T/plan.json" --quality best

# --strict: a plan that still breaks a limit after optimizing exits 3 and writes nothing.
python3 - "$T/plan.json" "$T/strict.json" << 'PY'
import json, sys
plan = json.load(open(sys.argv[1]))
plan["drone"]["min_altitude_m"] = 0.0
plan["drone"]["max_altitude_m"] = 1.0  # the orbit flies at 10 m: no 5 m deviation can fix that
json.dump(plan, open(sys.argv[2], "w"))
PY
expect_refusal 3 "after optimizing" "$T/strict.json" --strict --quality draft
echo "optimize_cli: ok"
