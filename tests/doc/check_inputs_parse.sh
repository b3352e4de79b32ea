#!/usr/bin/env bash
# check_inputs_parse.sh TALUS TOP
# No input file in the repository rots: every .prm (and .prm.in, after the
# substitution cmake makes: @SOURCE_DIR@ = its directory, @TALUS_DATA_DIR@ =
# TOP/data) under prm/, benchmarks/ and tests/ must pass `talus --check`
# (parsed with every declaration of its problem, both passes, plus the
# checks made before a run: no empty file, finite numbers, memory).
# The inputs of tests/errors/ are bad on purpose: `talus --check` must either
# reject them with the message of their "# EXPECT:" line, or accept them
# (their error is found while setting up the run and checked by the ctest
# errors/NAME itself); it must never crash. One talus process checks all
# valid inputs, one all bad ones (a process per file costs ~1 s of MPI and
# library start-up each).
set -u
talus=$1; top=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

good=(); bad=(); declare -A source_of
n_failed=0
while IFS= read -r -d '' input; do
  rel=${input#"$top"/}
  file=$input
  if [[ $input == *.prm.in ]]; then
    file=$tmp/${rel//\//__}
    file=${file%.in}
    sed -e "s#@SOURCE_DIR@#$(dirname "$input")#g" \
        -e "s#@TALUS_DATA_DIR@#$top/data#g" "$input" > "$file"
    if grep -q '@[A-Za-z_]*@' "$file"; then
      echo "FAIL: $rel: unknown @VARIABLE@ left after the substitution"
      n_failed=$((n_failed + 1)); continue
    fi
  fi
  source_of[$file]=$rel
  if [[ $rel == tests/errors/* ]]; then bad+=("$file"); else good+=("$file"); fi
done < <(find "$top/prm" "$top/benchmarks" "$top/tests" -type f \
           \( -name '*.prm' -o -name '*.prm.in' \) -print0 | sort -z)

# The block of FILE in the output of one talus --check run.
block() {
  awk -v head="talus --check: <$2> " '
    index($0, "talus --check: <") == 1 { inside = index($0, head) == 1 }
    inside' <<<"$1"
}

out=$(cd "$tmp" && timeout 600 "$talus" --check "${good[@]}" 2>&1); code=$?
if [[ $code -ge 124 ]]; then
  echo "FAIL: talus --check crashed (exit code $code):"; echo "$out"
  n_failed=$((n_failed + 1))
fi
n_ok=0
for file in "${good[@]}"; do
  b=$(block "$out" "$file")
  if grep -q "^talus --check: <.*> is valid" <<<"$b"; then
    n_ok=$((n_ok + 1))
  else
    echo "FAIL: ${source_of[$file]}:"; echo "$b"; n_failed=$((n_failed + 1))
  fi
done

out=$(cd "$tmp" && timeout 600 "$talus" --check "${bad[@]}" 2>&1); code=$?
if [[ $code -ge 124 ]]; then
  echo "FAIL: talus --check crashed on tests/errors (exit code $code):"
  echo "$out"; n_failed=$((n_failed + 1))
fi
n_rejected=0; n_run_time=0
for file in "${bad[@]}"; do
  b=$(block "$out" "$file")
  expected=$(sed -n 's/^# EXPECT: *//p' "$file" | head -n 1)
  if grep -q "^talus --check: <.*> is valid" <<<"$b"; then
    n_run_time=$((n_run_time + 1))
  elif ! grep -q "is not valid:" <<<"$b"; then
    echo "FAIL: ${source_of[$file]}: no result"; n_failed=$((n_failed + 1))
  elif [[ -n $expected ]] && ! grep -qF -- "$expected" <<<"$b"; then
    echo "FAIL: ${source_of[$file]}: rejected, but without <$expected>:"
    echo "$b"; n_failed=$((n_failed + 1))
  else
    n_rejected=$((n_rejected + 1))
  fi
done

echo "inputs_parse: ${#good[@]} inputs, $n_ok valid; tests/errors:" \
     "$n_rejected rejected by --check with their message, $n_run_time" \
     "found bad only when run; $n_failed failed"
[[ $n_failed -eq 0 && $n_ok -gt 0 && $n_ok -eq ${#good[@]} ]]
