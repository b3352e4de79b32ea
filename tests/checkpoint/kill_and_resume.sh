#!/usr/bin/env bash
# kill_and_resume.sh TALUS INPUT MODE WORKDIR [CSV_FILES [RANKS_TOLERANCE
#                    [SKIPPED_COLUMNS]]]
# Checkpoint and restart tests (doc/checkpoint.md, doc/testing.md). Every
# run writes its final material points in full precision
# (TALUS_DEBUG_DUMP_POINTS) next to its time_series.csv; compare_runs.py
# compares them with the uninterrupted run.
#   kill     1 rank: killed with SIGKILL after step 25 (checkpoints every
#            10 steps; TALUS_DEBUG_KILL_AFTER_STEP), a half-written newer
#            checkpoint left behind, resumed: identical to 1e-10
#   ranks12  written on 1 rank, resumed on 2: agree to solver tolerance
#   ranks21  written on 2 ranks, resumed on 1: agree to solver tolerance
#            (with block_floor.prm, whose 1- and 2-rank runs agree)
#   errors   truncated, damaged and foreign checkpoints, none at all, and a
#            run whose Newton iteration fails: clear errors, non-zero exit
#   coupled_errors  (a coupled INPUT) a checkpoint of another structure,
#            accelerator or problem: clear errors, non-zero exit
#   wall_limit  stopped by 'stop after minutes' after step 1, the
#            checkpoint named; resumed from it: identical to 1e-10
#   exception  an exception inside step 15 (TALUS_DEBUG_THROW_AFTER_TIME,
#            after the step's Newton iteration): the run stops, names the
#            checkpoint of step 14; resumed from it: identical to 1e-10
#            (a coupled INPUT: to RANKS_TOLERANCE without SKIPPED_COLUMNS,
#            since the accelerator's reused windows are dropped as after
#            any rejected step)
#   lost_points  (an INPUT with 'abort on lost material points = true')
#            the run stops with a checkpoint and names it; resumed from it
#            without the abort: identical to the run without the abort
# CSV_FILES: the CSV files compared (comma-separated; default
# time_series.csv, a coupled run coupling.csv,structure.csv);
# RANKS_TOLERANCE: of ranks12 and ranks21 (default 1e-6); SKIPPED_COLUMNS:
# CSV columns ranks12 and ranks21 do not compare (compare_runs.py).
set -u
talus=$1; input=$2; mode=$3; work=$4
csv_files=${5:-time_series.csv}; ranks_tolerance=${6:-1e-6}
skipped_columns=${7:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
cp "$input" case.prm

fail() { echo "FAIL: $*"; exit 1; }

# expect WHAT TALUS-ARGS...: talus exits non-zero (no crash) with message WHAT
expect() {
  local what=$1; shift
  local out code
  out=$(timeout 120 "$talus" "$@" 2>&1); code=$?
  echo "$out" | tail -n 3
  [ $code -ne 0 ] || fail "exit code 0 for: $*"
  [ $code -lt 124 ] || fail "exit code $code (crash or signal) for: $*"
  grep -qF -- "$what" <<<"$out" || fail "no message '$what' for: $*"
  echo "ok: exit code $code, '$what'"
}

# resume_failure_checkpoint FILE SUMMARY: resumed from the checkpoint a
# failed run wrote, FILE runs to its end and prints the line SUMMARY
resume_failure_checkpoint() {
  timeout 300 "$talus" --resume output/checkpoints/checkpoint-00000000 \
    "$1" > log_failure_resumed.txt 2>&1 ||
    { tail -n 5 log_failure_resumed.txt;
      fail "the run resumed from the failure checkpoint failed"; }
  grep -q "resumed from output/checkpoints/checkpoint-00000000 at step 0" \
    log_failure_resumed.txt || fail "not resumed from the failure checkpoint"
  grep -q "^$2" log_failure_resumed.txt ||
    fail "the resumed run did not finish"
  echo "ok: resumed from the failure checkpoint and finished"
}

# run DIR RANKS [talus arguments before the file...]: talus in DIR
run() {
  local dir=$1 ranks=$2; shift 2
  mkdir -p "$dir"
  ( cd "$dir" && TALUS_DEBUG_DUMP_POINTS=output/points.txt \
      timeout 300 mpirun -np "$ranks" "$talus" "$@" ../case.prm \
      > log.txt 2>&1 )
}

# the uninterrupted run (with its checkpoints, which change nothing)
reference() {
  run ref 1 || { cat ref/log.txt; fail "the uninterrupted run failed"; }
}

# killed RANKS: a run killed after step 25
killed() {
  mkdir -p run
  ( cd run && TALUS_DEBUG_KILL_AFTER_STEP=25 timeout 300 \
      mpirun -np "$1" "$talus" ../case.prm > log_killed.txt 2>&1 )
  [ -f run/output/checkpoints/checkpoint-00000020/manifest ] ||
    { cat run/log_killed.txt; fail "no checkpoint of step 20 before the kill"; }
  [ -f run/output/checkpoints/checkpoint-00000010/manifest ] ||
    fail "the checkpoint of step 10 (keep = 2) is missing"
  grep -q "checkpoint (scheduled) at step 20" run/log_killed.txt ||
    fail "the killed run did not report its checkpoint"
  if grep -qE "^(Summary|Done:)" run/log_killed.txt; then
    fail "the run was not killed"
  fi
  echo "killed after step 25; checkpoints: $(ls run/output/checkpoints)"
}

case $mode in
  kill)
    reference
    killed 1
    # a crash while writing the checkpoint of step 30: a partial directory
    mkdir -p run/output/checkpoints/tmp-checkpoint-00000030
    head -c 100 run/output/checkpoints/checkpoint-00000020/mpm_state \
      > run/output/checkpoints/tmp-checkpoint-00000030/mpm_state
    run run 1 --resume output/checkpoints ||
      { cat run/log.txt; fail "the resumed run failed"; }
    grep "resumed from" run/log.txt
    grep -q "resumed from output/checkpoints/checkpoint-00000020 at step 20" \
      run/log.txt || fail "not resumed from the checkpoint of step 20"
    # the summaries (test mode; a coupled run's from 'Done:') must be the
    # same
    diff <(sed -n '/^\(Summary\|Done:\)/,$p' ref/log.txt) \
         <(sed -n '/^\(Summary\|Done:\)/,$p' run/log.txt) ||
      fail "the summaries differ"
    python3 "$here/compare_runs.py" ref/output run/output 1e-10 \
      "killed and resumed" 18,19 "$csv_files" || fail "resumed run differs"
    # the PVD indices (of the points, of a coupled run's structure
    # meshes) list each output once, as the uninterrupted run's
    for pvd in ref/output/*.pvd; do
      [ -f "$pvd" ] || continue
      name=$(basename "$pvd")
      diff <(grep -v 'generated by' "$pvd") \
           <(grep -v 'generated by' "run/output/$name") ||
        fail "$name differs"
    done
    # resume = true in the file: the newest checkpoint again
    sed -i 's/set keep = 2/set keep = 2\n  set resume = true/' case.prm
    ( cd run && rm -f output/points.txt &&
        TALUS_DEBUG_DUMP_POINTS=output/points.txt timeout 300 \
        "$talus" ../case.prm > log_resume_true.txt 2>&1 ) ||
      fail "resume = true failed"
    grep -q "resumed from output/checkpoints/checkpoint-[0-9]" \
      run/log_resume_true.txt || fail "resume = true did not resume"
    ;;
  ranks12|ranks21)
    reference
    if [ "$mode" = ranks12 ]; then write=1; read=2; else write=2; read=1; fi
    killed $write
    run run $read --resume output/checkpoints/checkpoint-00000020 ||
      { cat run/log.txt; fail "the resumed run failed"; }
    grep "resumed from" run/log.txt || fail "not resumed"
    python3 "$here/compare_runs.py" ref/output run/output "$ranks_tolerance" \
      "written on $write rank(s), resumed on $read" 18,19 "$csv_files" \
      "$skipped_columns" ||
      fail "resumed run differs"
    ;;
  errors)
    killed 1
    good=run/output/checkpoints/checkpoint-00000020
    cp -r $good truncated
    size=$(stat -c %s truncated/mpm_grid_fixed.data)
    truncate -s $((size / 2)) truncated/mpm_grid_fixed.data
    expect "truncated/mpm_grid_fixed.data> has $((size / 2)) bytes, its manifest says $size (truncated" \
      --resume truncated case.prm
    cp -r $good damaged
    printf 'X' | dd of=damaged/time_loop bs=1 seek=40 conv=notrunc 2>/dev/null
    expect "damaged/time_loop> has the CRC-32" --resume damaged case.prm
    cp -r $good cut_manifest
    head -n 3 $good/manifest > cut_manifest/manifest
    expect "is truncated (no final 'end' line)" --resume cut_manifest case.prm
    mkdir foreign
    echo "something else" > foreign/manifest
    expect "does not start with 'talus-checkpoint': this is not a Talus checkpoint" \
      --resume foreign case.prm
    mkdir empty
    expect "holds no complete checkpoint" --resume empty case.prm
    expect "is neither a checkpoint" --resume does_not_exist case.prm
    # a checkpoint of another problem: a finer grid, another material
    sed 's/set subdivisions = 32, 16/set subdivisions = 64, 32/' case.prm \
      > finer.prm
    expect "it was written for a background grid of coarse cells 512, the parameter file gives 2048" \
      --resume $good finer.prm
    sed 's/set model = Mohr-Coulomb/set model = neo-Hookean/' case.prm \
      > elastic.prm
    expect "it was written for material points with history variables" \
      --resume $good elastic.prm
    # a failing run writes a checkpoint and says which
    sed 's/set linear solver = direct/set linear solver = direct\n  set maximum Newton iterations = 1/;
         s/set time step = 0.005/set time step = 0.005\n  set maximum step halvings = 1/' \
      case.prm > failing.prm
    expect "is in the checkpoint <output/checkpoints/checkpoint-00000000>" \
      failing.prm
    [ -f output/checkpoints/checkpoint-00000000/manifest ] ||
      fail "no failure checkpoint"
    # ... from which the run with the parameters that work continues (for
    # 10 steps: the end time is not part of the checkpoint)
    sed 's/set end time = .*/set end time = 0.05/' case.prm > short.prm
    resume_failure_checkpoint short.prm "Summary"
    ;;
  coupled_errors)
    killed 1
    good=run/output/checkpoints/checkpoint-00000020
    # another structure: fewer elements, static instead of dynamic
    sed 's/set elements per member = 20/set elements per member = 10/' \
      case.prm > coarser.prm
    expect "$good/structure_state> does not fit the parameter file: it holds a structure of 63 DoFs, the parameter file's has 33" \
      --resume $good coarser.prm
    sed 's/set dynamic = true/set dynamic = false/' case.prm > static.prm
    expect "it holds a dynamic structure, the parameter file's is static" \
      --resume $good static.prm
    # another structure model (a coupled file of the plane solid): the
    # model's name is checked before anything else of the structure
    expect "$good/structure_state> does not fit the parameter file: it holds the state of the structure model 'plane string', the parameter file sets 'plane solid'" \
      --resume $good "$here/../coupled/split_cantilever.prm"
    # another accelerator (its history does not fit)
    sed 's/set acceleration = IQN-ILS/set acceleration = Aitken/' case.prm \
      > aitken.prm
    expect "$good/coupling_state> does not fit the parameter file: it holds the history of the accelerator 'IQN-ILS', the parameter file sets 'Aitken'" \
      --resume $good aitken.prm
    # another problem: an MPM file with this checkpoint, and this file
    # with a checkpoint of an MPM run (a manifest without the key)
    expect "it was written by a run of 'problem = coupled', the parameter file <$here/block_wall.prm> sets 'problem = mpm'" \
      --resume $good "$here/block_wall.prm"
    cp -r $good mpm_checkpoint
    sed -i '/^key problem = /d' mpm_checkpoint/manifest
    expect "it was written by a run of 'problem = mpm', the parameter file <case.prm> sets 'problem = coupled'" \
      --resume mpm_checkpoint case.prm
    # a damaged structure state (CRC)
    cp -r $good damaged
    printf 'X' | dd of=damaged/structure_state bs=1 seek=60 conv=notrunc \
      2>/dev/null
    expect "damaged/structure_state> has the CRC-32" --resume damaged case.prm
    # a coupled step that cannot be solved writes a checkpoint and says which
    sed 's/set relative tolerance = 1e-6/set relative tolerance = 1e-6\n  set maximum coupling iterations = 2/;
         s/set time step = 0.005/set time step = 0.005\n  set maximum step halvings = 1/' \
      case.prm > failing.prm
    expect "is in the checkpoint <output/checkpoints/checkpoint-00000000>" \
      failing.prm
    [ -f output/checkpoints/checkpoint-00000000/structure_state ] ||
      fail "no failure checkpoint"
    # ... from which the run with the parameters that work continues (for
    # 10 steps: the end time is not part of the checkpoint; without the
    # verification, whose mean coupling iterations a run this short with
    # the halved first steps exceeds)
    sed 's/set end time = .*/set end time = 0.05/;
         /subsection Verification/,/^  end/d' case.prm > short.prm
    resume_failure_checkpoint short.prm "Done:"
    ;;
  lost_points)
    # (an INPUT with 'abort on lost material points = true') the run
    # stops with a checkpoint of the step that lost points and names it;
    # resumed from it without the abort, identical to the uninterrupted
    # run without the abort
    sed 's/set abort on lost material points = true/set abort on lost material points = false/' \
      case.prm > continue.prm
    grep -q "abort on lost material points = false" continue.prm ||
      fail "the input does not set 'abort on lost material points = true'"
    mkdir -p ref
    ( cd ref && TALUS_DEBUG_DUMP_POINTS=output/points.txt timeout 300 \
        "$talus" ../continue.prm > log.txt 2>&1 ) ||
      { cat ref/log.txt; fail "the uninterrupted run failed"; }
    mkdir -p run
    ( cd run && timeout 300 "$talus" ../case.prm > log_stopped.txt 2>&1 )
    code=$?
    tail -n 2 run/log_stopped.txt
    [ $code -ne 0 ] || fail "exit code 0 of the run that loses points"
    [ $code -lt 124 ] || fail "exit code $code (crash or signal)"
    checkpoint=$(sed -n 's/.*without the lost points) is in the checkpoint <\([^>]*\)>.*/\1/p' \
      run/log_stopped.txt | head -n 1)
    [ -n "$checkpoint" ] ||
      fail "the stop message does not name a checkpoint"
    grep -q "left the background grid" run/log_stopped.txt ||
      fail "the stop message does not say that points left the grid"
    [ -f "run/$checkpoint/manifest" ] || fail "no checkpoint <$checkpoint>"
    grep -q "^key reason = failure: material points lost" \
      "run/$checkpoint/manifest" || fail "the manifest gives another reason"
    echo "stopped with the checkpoint $checkpoint"
    ( cd run && rm -f output/points.txt &&
        TALUS_DEBUG_DUMP_POINTS=output/points.txt timeout 300 \
        "$talus" --resume "$checkpoint" ../continue.prm > log.txt 2>&1 ) ||
      { cat run/log.txt; fail "the run resumed from <$checkpoint> failed"; }
    grep "resumed from" run/log.txt || fail "not resumed"
    python3 "$here/compare_runs.py" ref/output run/output 1e-10 \
      "stopped by lost points and resumed" 18,19 "$csv_files" ||
      fail "resumed run differs"
    ;;
  wall_limit)
    # 'stop after minutes' of 60 microseconds: the run stops after its
    # first step with a checkpoint and names it; resumed from it without
    # the limit, identical to the uninterrupted run
    reference
    sed 's/set keep = 2/set keep = 2\n  set stop after minutes = 1e-6/' \
      case.prm > limited.prm
    mkdir -p run
    ( cd run && timeout 300 "$talus" ../limited.prm > log_stopped.txt 2>&1 )
    code=$?
    tail -n 1 run/log_stopped.txt
    [ $code -eq 1 ] || fail "exit code $code of the run stopped by its limit"
    grep -q "stopped at its wall-time limit" run/log_stopped.txt ||
      fail "no message of the wall-time limit"
    checkpoint=$(sed -n 's/.*The state after this step is in the checkpoint <\([^>]*\)>.*/\1/p' \
      run/log_stopped.txt | head -n 1)
    [ "$checkpoint" = output/checkpoints/checkpoint-00000001 ] ||
      fail "the message names <$checkpoint>, not the checkpoint of step 1"
    grep -q "^key reason = wall-time limit" "run/$checkpoint/manifest" ||
      fail "no checkpoint of the wall-time limit"
    run run 1 --resume "$checkpoint" ||
      { cat run/log.txt; fail "the resumed run failed"; }
    grep "resumed from" run/log.txt || fail "not resumed"
    python3 "$here/compare_runs.py" ref/output run/output 1e-10 \
      "stopped by the wall-time limit and resumed" 18,19 "$csv_files" ||
      fail "resumed run differs"
    ;;
  exception)
    reference
    mkdir -p run
    ( cd run && TALUS_DEBUG_THROW_AFTER_TIME=0.0725 timeout 300 \
        "$talus" ../case.prm > log_stopped.txt 2>&1 )
    code=$?
    tail -n 2 run/log_stopped.txt
    [ $code -eq 1 ] || fail "exit code $code of the run stopped by the exception"
    grep -q "The step after step 14 (t = 0.07 s) stopped with an exception: TALUS_DEBUG_THROW_AFTER_TIME" \
      run/log_stopped.txt || fail "no message of the exception in step 15"
    checkpoint=$(sed -n 's/.*The last accepted step (14, t = 0.07 s) is in the checkpoint <\([^>]*\)>.*/\1/p' \
      run/log_stopped.txt | head -n 1)
    [ "$checkpoint" = output/checkpoints/checkpoint-00000014 ] ||
      fail "the message names <$checkpoint>, not the checkpoint of step 14"
    grep -q "^key reason = failure: exception in the step" \
      "run/$checkpoint/manifest" || fail "no checkpoint of the exception"
    run run 1 --resume "$checkpoint" ||
      { cat run/log.txt; fail "the resumed run failed"; }
    grep "resumed from" run/log.txt || fail "not resumed"
    python3 "$here/compare_runs.py" ref/output run/output "${6:-1e-10}" \
      "stopped by an exception and resumed" 18,19 "$csv_files" \
      "$skipped_columns" || fail "resumed run differs"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo PASS
