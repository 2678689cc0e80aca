#!/usr/bin/env bash
# Side by side with pooltool 0.6 (issue 17): seeded shots, pooltool's results with Han 2005
# cushions, ours, and a comparison printed as markdown, in two modes (each side's own
# ball-ball model; frictionless ball-ball on both). Not run in CI. See README.md.
#
#   tools/pooltool-compare/run.sh        (from anywhere; PYTHON=python3.12 to pick one)
#
# Idempotent: the venv is reused while requirements.txt is unchanged; the outputs in
# target/pooltool/ are rewritten on every run (the shots are the same each time).
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
VENV=$ROOT/target/pooltool-venv
OUT=$ROOT/target/pooltool
PY=$VENV/bin/python
export PYTHONHASHSEED=0   # pinned; the shots' seed (rack jitter included) is shots.py's
export PYTHONDONTWRITEBYTECODE=1   # no __pycache__ in the source tree

mkdir -p "$OUT"
STAMP="pooltool-billiards==0.6.0 $(sha256sum "$HERE/requirements.txt" | cut -c1-16)"
if [[ ! -x $PY || $(cat "$VENV/.installed" 2>/dev/null) != "$STAMP" ]]; then
    echo "== venv: $VENV" >&2
    "${PYTHON:-python3}" -m venv "$VENV"
    "$PY" -m pip install -q --upgrade pip
    # --no-deps: pooltool pins panda3d==1.11.0.dev3702, which PyPI does not have.
    "$PY" -m pip install -q --no-deps pooltool-billiards==0.6.0
    "$PY" -m pip install -q -r "$HERE/requirements.txt"
    echo "$STAMP" > "$VENV/.installed"
fi

echo "== shots" >&2
"$PY" "$HERE/shots.py" "$OUT/shots.json"

# Two modes (README.md, "The two modes"): each side's own ball-ball model, and a
# frictionless ball-ball collision with e = 1 on both (pooltool: FrictionalInelastic with
# zero friction and e_b = 1; ours: the `ideal` model).
for mode in default frictionless; do
    name=pooltool; [[ $mode == default ]] || name=pooltool-$mode
    echo "== pooltool ($mode ball-ball)" >&2
    start=$SECONDS
    "$PY" "$HERE/pooltool_side.py" "$OUT/shots.json" "$OUT/$name.json" --ball-ball "$mode" \
        2> "$OUT/$name.log" || { cat "$OUT/$name.log" >&2; exit 1; }
    echo "   $((SECONDS - start)) s; timing in $OUT/$name-timing.json" >&2
done

for model in kim-grip ideal; do
    name=ours; [[ $model == kim-grip ]] || name=ours-$model
    echo "== ours ($model)" >&2
    if ! (cd "$ROOT" && cargo run --release -q -p cuesight-host --example sim_shots -- \
            "$OUT/shots.json" "$model" > "$OUT/$name.json.tmp"); then
        rm -f "$OUT/$name.json.tmp"
        echo "our side (cargo run ... --example sim_shots -- shots.json $model) failed;" \
             "pooltool's results are in $OUT/" >&2
        exit 1
    fi
    mv "$OUT/$name.json.tmp" "$OUT/$name.json"
done

{
    "$PY" "$HERE/compare.py" "$OUT/shots.json" "$OUT/ours.json" "$OUT/pooltool.json" \
        --title "Default ball-ball models (ours kim-grip, pooltool frictional_inelastic)"
    echo
    "$PY" "$HERE/compare.py" "$OUT/shots.json" "$OUT/ours-ideal.json" \
        "$OUT/pooltool-frictionless.json" --names ours-ideal pooltool-frictionless \
        --title "Frictionless ball-ball, e = 1, on both sides (ours ideal, pooltool u_b = 0)" \
        --far
} | tee "$OUT/report.md"
