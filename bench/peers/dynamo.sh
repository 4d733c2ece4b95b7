#!/usr/bin/env bash
# DynamO (https://github.com/dynamomd/DynamO, event-driven MD; its extern/stator submodule is
# https://github.com/toastedcrumpets/stator) built from source outside the repo, and run.
#
#   bench/peers/dynamo.sh build                  # build (skipped when built); prints the bin dir
#   bench/peers/dynamo.sh dynarun ARGS...        # build if needed, then run a DynamO program
#   bench/peers/dynamo.sh dynamod ARGS...        #   (dynarun, dynamod, dynahist_rw)
#
# Environment:
#   DYNAMO_ROOT  the source tree (default /work/peers/dynamo); its build/ holds the binaries
#   DYNAMO_GIT   bare git directories to take the sources from when DYNAMO_ROOT is missing
#   STATOR_GIT   (defaults: the mirrors /work/.mirror/dynamomd+DynamO/repo and
#                /work/.mirror/toastedcrumpets+stator/repo; any clone of the two repositories
#                does: the stator commit is the one DynamO's tree pins for extern/stator)
#   DYNAMO_VENV  a venv for CMake >= 3.28 from PyPI (default /work/peers/venv; Debian 12
#                has 3.25)
#
# Needs (Debian): g++, make, libboost-all-dev (system, filesystem, program_options,
# unit_test_framework), libeigen3-dev, libbz2-dev. The visualizer is off; only dynarun,
# dynamod and dynahist_rw are built (Release: -O3 -DNDEBUG), at nice 19 with 2 jobs.
# Nothing of DynamO is copied into haff. See docs/peers-dynamo.md.
set -euo pipefail
root=${DYNAMO_ROOT:-/work/peers/dynamo}
dynamo_git=${DYNAMO_GIT:-/work/.mirror/dynamomd+DynamO/repo}
stator_git=${STATOR_GIT:-/work/.mirror/toastedcrumpets+stator/repo}
venv=${DYNAMO_VENV:-/work/peers/venv}
build=$root/build

have_deps() {
    [ -f /usr/include/eigen3/Eigen/Core ] && [ -d /usr/include/boost/program_options ] &&
        [ -f /usr/include/bzlib.h ] && command -v g++ >/dev/null && command -v make >/dev/null
}

build_dynamo() {
    if [ -x "$build/dynarun" ] && [ -x "$build/dynamod" ] && [ -x "$build/dynahist_rw" ]; then
        echo "$build"
        return
    fi
    if ! have_deps; then
        echo "dynamo.sh: installing the build dependencies with apt-get" >&2
        local sudo=
        [ "$(id -u)" = 0 ] || sudo=sudo
        $sudo apt-get update -qq >&2
        $sudo apt-get install -y -qq g++ make libboost-all-dev libeigen3-dev libbz2-dev >&2
    fi
    if [ ! -f "$root/CMakeLists.txt" ]; then
        [ -d "$dynamo_git" ] || {
            echo "dynamo.sh: no sources at $root and no git directory $dynamo_git" >&2
            exit 1
        }
        mkdir -p "$root"
        git --git-dir="$dynamo_git" archive HEAD | tar -x -C "$root"
        git --git-dir="$dynamo_git" rev-parse HEAD > "$root/DYNAMO_COMMIT"
    fi
    if [ ! -f "$root/extern/stator/CMakeLists.txt" ]; then
        local pin
        pin=$(git --git-dir="$dynamo_git" ls-tree HEAD extern/stator | awk '{print $3}')
        mkdir -p "$root/extern/stator"
        git --git-dir="$stator_git" archive "$pin" | tar -x -C "$root/extern/stator"
        echo "$pin" > "$root/extern/stator/STATOR_COMMIT"
    fi
    if ! "$venv/bin/cmake" --version >/dev/null 2>&1; then
        python3 -m venv "$venv" >&2
        "$venv/bin/pip" install -q 'cmake>=3.28' >&2
    fi
    mkdir -p "$build"
    (
        cd "$build"
        nice -n 19 "$venv/bin/cmake" .. -DCMAKE_BUILD_TYPE=Release -DVISUALIZER_ENABLED=OFF \
            -DBUILD_TESTING=OFF > cmake.log 2>&1 || { tail -30 cmake.log >&2; exit 1; }
        nice -n 19 make -j2 dynarun dynamod dynahist_rw > make.log 2>&1 ||
            { grep -m20 -B2 -A5 'error' make.log >&2; exit 1; }
    )
    echo "$build"
}

cmd=${1:?usage: $0 build | dynarun ARGS... | dynamod ARGS... | dynahist_rw ARGS...}
shift
case "$cmd" in
    build) build_dynamo ;;
    dynarun | dynamod | dynahist_rw)
        build_dynamo > /dev/null
        exec "$build/$cmd" "$@"
        ;;
    *) echo "usage: $0 build | dynarun ARGS... | dynamod ARGS... | dynahist_rw ARGS..." >&2; exit 2 ;;
esac
