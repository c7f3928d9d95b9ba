#!/usr/bin/env bash
# One-step set-up for a fresh Debian 12 machine (as root): installs what is missing, builds, then
#   ./setup.sh run [SCENE.toml] [hubbeam run options...]   runs a scene (default cases/spinup_omega4.toml)
#   ./setup.sh test                                         runs the whole test suite through ctest
#   ./setup.sh fuzz [SECONDS]                               fuzzes the scene parser (clang's libFuzzer, default 60 s)
set -euo pipefail
cd "$(dirname "$0")"

# GiNaC (symbolic derivation), Eigen (linear algebra), GSL (odeiv2 integrators), Catch2 (tests), toml++
# (scene files), CLI11 (command line), gnuplot (the benchmark's figures); cmake, ninja and g++ to build.
packages=(build-essential cmake ninja-build pkg-config libginac-dev libeigen3-dev libgsl-dev catch2
          libtomlplusplus-dev libcli11-dev gnuplot-nox)
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
cmake --build --preset release

case "$mode" in
  run)
    scene=cases/spinup_omega4.toml
    if (($#)) && [[ $1 != -* ]]; then scene=$1; shift; fi
    mkdir -p out
    exec build/hubbeam run "$scene" -o "out/$(basename "${scene%.toml}").csv" "$@"
    ;;
  test)
    exec ctest --preset release
    ;;
  *)
    echo "usage: ./setup.sh run [SCENE.toml] [options] | ./setup.sh test | ./setup.sh fuzz [SECONDS]" >&2
    exit 2
    ;;
esac
