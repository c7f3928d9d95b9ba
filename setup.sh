#!/usr/bin/env bash
# One-step set-up for a fresh Debian 12 machine (as root): installs what is missing, builds, then
#   ./setup.sh run [SCENE.toml] [hubbeam run options...]   runs a scene (default cases/spinup_omega4.toml) into
#                                                           NAME.csv here, as hubbeam run does
#   ./setup.sh test                                         runs the whole test suite through ctest
#   ./setup.sh fuzz [SECONDS]                               fuzzes the scene parser (clang's libFuzzer, default 60 s)
#   ./setup.sh figures [DIR]                                the paper's figures (docs/performance.md) into DIR
set -euo pipefail
cd "$(dirname "$0")"

# GiNaC (symbolic derivation), Eigen (linear algebra), GSL (odeiv2 integrators), SUNDIALS (CVODE, the BDF
# stepper family beside GSL's), LAPACK (band LU), Catch2 (tests), toml++
# (scene files), CLI11 (command line), gnuplot (figures), pybind11 and numpy (the Python module), Dask's
# distributed (sweeps), cryptography (the TLS certificates each local sweep cluster makes for itself; Dask does
# not depend on it), pandas (Result.to_pandas, and its test), scipy (the optimization example under examples/ and
# its test; scipy.signal reads linearize's .npz), zlib (the CRC-32 of a .npz's entries), matplotlib (Result.plot
# and plot_campbell; the package imports without it), nbconvert and ipykernel (the suite runs examples/notebooks),
# tqdm (a sweep's progress bar in a notebook); cmake, ninja and g++ to build.
packages=(build-essential cmake ninja-build pkg-config libginac-dev libeigen3-dev libgsl-dev catch2
          libtomlplusplus-dev libcli11-dev libsundials-dev liblapack-dev gnuplot-nox python3 python3-dev pybind11-dev python3-numpy
          python3-distributed python3-cryptography python3-pandas python3-scipy zlib1g-dev python3-matplotlib
          jupyter-nbconvert python3-ipykernel python3-tqdm)
mode=${1:-run}
shift || true
[[ $mode == fuzz ]] && packages+=(clang)  # libFuzzer and the sanitizers' runtime come with Debian's clang
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [[ $mode == fuzz ]]; then
  cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz
  # The working corpus starts from every scene in the tree and the inputs the fuzzer found before; inputs that
  # reach new code are added to it, and a crash is written to build-fuzz/crash-* with the way to replay it.
  mkdir -p build-fuzz/corpus
  export ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
  exec build-fuzz/fuzz_scene -max_total_time="${1:-60}" -dict=tests/fuzz/scene.dict -max_len=4096 \
    -artifact_prefix=build-fuzz/ build-fuzz/corpus cases tests/scenes tests/fuzz/corpus
fi

cmake --preset release >/dev/null
# A run needs the program alone (with the generator it calls for variants not built in, and the Python module its
# sweep command runs); the test suite needs everything, its own programs too (docs/performance.md, "Set-up").
if [[ $mode == test ]]; then
  cmake --build --preset release
else
  cmake --build --preset release --target hubbeam
fi

case "$mode" in
  run)
    scene=cases/spinup_omega4.toml
    if (($#)) && [[ $1 != -* ]]; then scene=$1; shift; fi
    # exactly `hubbeam run`: NAME.csv in the current folder unless the options say -o FILE
    exec build/hubbeam run "$scene" "$@"
    ;;
  test)
    exec ctest --preset release
    ;;
  figures)
    # Each figure from the runs, modes and fields that hubbeam computes, with the commands in plain view.
    dir=${1:-docs/figures}
    data=out/figures
    mkdir -p "$dir" "$data"
    methods=(amm fem bim bsim)
    labels=AMM,FEM,BIM,BSIM
    for scene in spinup_omega4 spinup_omega10 torque_tau1 torque_tau10; do  # Figs. 3-8: Ny = Nx = 4
      files=()
      for m in "${methods[@]}"; do
        build/hubbeam run "cases/$scene.toml" --method "$m" -o "$data/$scene-$m.csv" >/dev/null
        files+=("$data/$scene-$m.csv")
      done
      build/hubbeam plot tip "${files[@]}" --labels "$labels" --title "Tip deflection, $scene, Ny = Nx = 4" \
        -o "$dir/$scene-tip"
      [[ $scene == spinup* ]] && build/hubbeam plot axial "${files[@]}" --labels "$labels" \
        --title "Axial tip displacement, $scene: u_x (with foreshortening, thick) and u_x1 (stretch, thin with points)" -o "$dir/$scene-axial"
    done
    for scene in torque_tau1 torque_tau10; do  # Figs. 9-12: one method, Ny = 4 to 10, Nx = 0
      for m in "${methods[@]}"; do
        files=() names=()
        for ny in 10 4 6 8; do  # the finest first: the difference panel shows the others against it
          build/hubbeam run "cases/$scene.toml" --method "$m" --ny "$ny" --nx 0 -o "$data/$scene-$m-ny$ny.csv" >/dev/null
          files+=("$data/$scene-$m-ny$ny.csv") names+=("Ny = $ny")
        done
        build/hubbeam plot tip "${files[@]}" --labels "$(IFS=,; echo "${names[*]}")" \
          --title "Tip deflection, $scene, ${m^^} against Ny (Nx = 0)" -o "$dir/$scene-$m-dofs"
      done
    done
    build/hubbeam modes cases/spinup_omega4.toml --methods amm,fem,bim,bsim --ny 4 --omega 0:12:0.25 \
      -o "$data/modes.csv" >/dev/null
    build/hubbeam modes cases/spinup_omega4.toml --methods bim --ny 14 --omega 0:12:0.25 \
      -o "$data/modes-all-converged.csv" >/dev/null  # converged: the reference the Ny = 4 lines approach
    awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) if ($i == "label") c = i; print; next} $c ~ /^bending [1-4]$/' \
      "$data/modes-all-converged.csv" > "$data/modes-converged.csv"  # its first four, by the column named label
    build/hubbeam plot campbell "$data/modes.csv" "$data/modes-converged.csv" --harmonics 1,2,3 \
      --title "Campbell diagram: in-plane bending, Nx = 4; Ny = 4 and converged (BIM, Ny = 14)" -o "$dir/campbell"
    files=()
    for m in "${methods[@]}"; do  # paper conclusion 3: FEM's bending moment jumps at its nodes
      build/hubbeam run cases/spinup_omega4.toml --method "$m" --t-end 20 --fields-at 20 \
        -o "$data/moment-$m.csv" >/dev/null
      files+=("$data/moment-$m-fields.csv")
    done
    build/hubbeam plot moment "${files[@]}" --labels "$labels" --time 20 \
      --title "Bending moment along the beam at t = 20 s, spin-up to 4 rad/s, Ny = Nx = 4" -o "$dir/moment"
    ;;
  *)
    echo "usage: ./setup.sh run [SCENE.toml] [options] | ./setup.sh test | ./setup.sh fuzz [SECONDS] | ./setup.sh figures [DIR]" >&2
    exit 2
    ;;
esac
