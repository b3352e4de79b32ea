#!/usr/bin/env bash
# Sensitivity of the Lube et al. 2005 series to the friction angle, the grid
# and the wall friction (doc/verification.md, "Lube series at 10 mm, and
# what the grid dependence is not"). Model: the one that validates Bui (recoverable
# volume + mu(I), make_lube_series.py --rate-dependent), floor mu = tan phi.
#   usage: bash contrib/granular/lube_study/run.sh [STUDY...]
#   STUDY: phi30 phi33 phi36 (10 mm, a = 0.5 ... 8), phi33_5mm (5 mm,
#          a = 1.5, 3, 5), phi36_5mm (a = 0.5, 1, 1.5, 3), phi36_2p5mm
#          (a = 0.5, 1), phi36_2p5mm_a1p5, phi36_5mm_a5 and phi36_5mm_a8
#          (one column each: 25 to 55 min), phi36_1p25mm_a0p5 (a = 0.5 at
#          1.25 mm: 40 cells over its height; about 1 h), grid (phi 30 and 33: a = 0.5 and 1 at 5 mm,
#          a = 0.5 at 2.5 mm; phi 30: a = 0.5 at 1.25 mm, about 50 min),
#          halfbui (a = 0.5 with Bui's material, phi 19.8, floor tan 19.8,
#          grain 0.625 mm: Bui's column at half the size, at 10, 5 and
#          2.5 mm), grain125 (phi 30, a = 0.5, grain 1.25 mm instead of
#          0.5 mm, at 10, 5 and 2.5 mm), floor (phi 30, a = 0.5 on a
#          no-slip floor and on a floor mu = 0.36, at 10, 5 and 2.5 mm),
#          wall (10 mm, phi 30, wall mu = tan 30, a = 1.5, 3, 8),
#          floor084 (phi 30, a = 0.5 on a floor mu = 0.84 = tan phi_2, at
#          10 and 5 mm), dilatancy (phi 30, a = 0.5 with psi = 10 and 20
#          deg, at 10 and 5 mm), timestep (phi 30, a = 0.5 at 5 mm with the
#          10 mm step, 1 ms),
#          wellposed (a = 0.5 at 10, 5 and 2.5 mm with mu(I) parameters
#          on both sides of the well-posedness limit of Barker et al. 2015:
#          phi 27 and 29 with mu_2 - mu_s = 0.2616 (limit phi 27.8), phi
#          30 with mu_2 - mu_s = 0.6 (limit 0.411); doc/verification.md,
#          "Lube series at 10 mm, and what the grid dependence is not"; wellposed27, wellposed29 and
#          wellposed30 run one of the three cases);
#          default: all. Each study writes its inputs to
#          output/lube_study/<study>/inputs and its results to
#          output/lube_study/<study>.csv (run_collapse_series.sh columns).
# Run from the repository top; one core per study (run two at a time on
# this 2-core machine). Wall times at 10 mm: a = 8 about 8 min, a = 5 about
# 4 min; at 5 mm a = 5 about 40 min.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
cd "$top"
gen=contrib/granular/make_lube_series.py
run=contrib/granular/run_collapse_series.sh
studies=("$@")
[[ ${#studies[@]} -gt 0 ]] || studies=(phi30 phi33 phi36 phi33_5mm phi36_5mm phi36_2p5mm phi36_2p5mm_a1p5 phi36_1p25mm_a0p5 phi36_5mm_a5 phi36_5mm_a8 grid halfbui grain125 floor wall floor084 dilatancy timestep wellposed)

variant() { # study name cell sed-expression: phi 30, a = 0.5, edited input
  local study=$1 name=$2 cell=$3 expr=$4
  local dir=output/lube_study/${name}_$cell
  rm -rf "$dir/inputs"
  python3 $gen -o "$dir/inputs" --cell "$cell" --friction-angle 30 \
    --aspect-ratios 0.5 --rate-dependent --output-prefix "$dir"
  local input=$dir/inputs/lube2005_a0p5.prm
  cp "$input" "$input.orig"
  sed -i "$expr" "$input"
  if cmp -s "$input" "$input.orig"; then
    echo "run.sh: <$expr> changed nothing in $input" >&2
    exit 1
  fi
  rm "$input.orig"
  bash $run -o "output/lube_study/$study.csv" "$input" || true
}

series() { # name cell phi "aspect ratios" [extra generator options]
  local name=$1 cell=$2 phi=$3 ratios=$4
  shift 4
  local dir=output/lube_study/$name
  rm -rf "$dir/inputs"
  python3 $gen -o "$dir/inputs" --cell "$cell" --friction-angle "$phi" \
    --aspect-ratios $ratios --rate-dependent --output-prefix "$dir" "$@"
  local files=()
  for a in $ratios; do files+=("$dir/inputs/lube2005_a${a/./p}.prm"); done
  # Exit status 1 means some run missed the Lube tolerance: a result here.
  bash $run -o "output/lube_study/$name.csv" "${files[@]}" || true
}

for s in "${studies[@]}"; do
  case $s in
    phi30 | phi33 | phi36) series "$s" 0.01 "${s#phi}" "0.5 1 1.5 3 5 8" ;;
    phi33_5mm) series "$s" 0.005 33 "1.5 3 5" ;;
    phi36_5mm) series "$s" 0.005 36 "0.5 1 1.5 3" ;;
    phi36_2p5mm) series "$s" 0.0025 36 "0.5 1" ;;
    phi36_2p5mm_a1p5) series "$s" 0.0025 36 "1.5" ;;
    phi36_1p25mm_a0p5) series "$s" 0.00125 36 "0.5" ;;
    phi36_5mm_a5) series "$s" 0.005 36 "5" ;;
    phi36_5mm_a8) series "$s" 0.005 36 "8" ;;
    grid)
      for phi in 30 33; do
        series "grid_phi${phi}_0.005" 0.005 "$phi" "0.5 1"
        series "grid_phi${phi}_0.0025" 0.0025 "$phi" "0.5"
      done
      series grid_phi30_0.00125 0.00125 30 "0.5" ;;
    halfbui | grain125)
      if [[ $s == halfbui ]]; then phi=19.8 d=0.000625; else phi=30 d=0.00125; fi
      for cell in 0.01 0.005 0.0025; do
        dir=output/lube_study/${s}_$cell
        rm -rf "$dir/inputs"
        python3 $gen -o "$dir/inputs" --cell $cell --friction-angle $phi \
          --aspect-ratios 0.5 --rate-dependent --output-prefix "$dir"
        sed -i "s/set grain diameter = 0.0005/set grain diameter = $d/" \
          "$dir/inputs/lube2005_a0p5.prm"
        bash $run -o "output/lube_study/$s.csv" "$dir/inputs/lube2005_a0p5.prm"
      done ;;
    floor)
      for kind in noslip floor036; do
        for cell in 0.01 0.005 0.0025; do
          dir=output/lube_study/${kind}_$cell
          rm -rf "$dir/inputs"
          python3 $gen -o "$dir/inputs" --cell $cell --friction-angle 30 \
            --aspect-ratios 0.5 --rate-dependent --output-prefix "$dir"
          if [[ $kind == noslip ]]; then
            sed -i 's/  set slip boundaries = 0/  set slip boundaries = 0\n  set fixed boundaries = 2/; s/  set friction boundaries = 2: 0.577/  set friction boundaries =/' \
              "$dir/inputs/lube2005_a0p5.prm"
          else
            sed -i 's/  set friction boundaries = 2: 0.577/  set friction boundaries = 2: 0.36/' \
              "$dir/inputs/lube2005_a0p5.prm"
          fi
          bash $run -o "output/lube_study/$kind.csv" "$dir/inputs/lube2005_a0p5.prm"
        done
      done ;;
    wall) series wall 0.01 30 "1.5 3 8" --wall-friction 0.577 ;;
    floor084)
      for cell in 0.01 0.005; do
        variant floor084 floor084 $cell 's/  set friction boundaries = 2: 0.577/  set friction boundaries = 2: 0.84/'
      done ;;
    dilatancy)
      for psi in 10 20; do
        for cell in 0.01 0.005; do
          variant dilatancy psi$psi $cell "s/set dilatancy angle = 0/set dilatancy angle = $psi/"
        done
      done ;;
    timestep) variant timestep dt1ms 0.005 's/set time step = 0.0005/set time step = 0.001/' ;;
    wellposed | wellposed27 | wellposed29 | wellposed30)
      cases=("27 0.2616" "29 0.2616" "30 0.6")
      [[ $s == wellposed ]] || cases=("$(printf '%s\n' "${cases[@]}" | grep "^${s#wellposed} ")")
      for case in "${cases[@]}"; do
        set -- $case
        for cell in 0.01 0.005 0.0025; do
          series "wellposed_phi$1_dmu$2_$cell" $cell $1 "0.5" \
            --friction-increment $2
          tail -n 1 "output/lube_study/wellposed_phi$1_dmu$2_$cell.csv" |
            sed "s/^/$1,$2,$cell,/" >> output/lube_study/wellposed.csv
        done
      done ;;
    *) echo "run.sh: unknown study <$s>" >&2; exit 2 ;;
  esac
done
