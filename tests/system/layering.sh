#!/usr/bin/env bash
# The layering test (docs/ARCHITECTURE.md): the run time reads libraries through meadow_library
# only. Fails, naming the file or the target, when
#   - a file of engine/vk, render, ui or io includes a header of an offline stage, the scene or
#     the pipeline (anything but core/, library/, vk/, render/, ui/, io/ and shaders/shared/),
#   - a file of precompute/library includes anything of meadow but core/, library/ and
#     shaders/shared/,
#   - meadow_engine or meadow_library links, directly or through another target, a stage
#     (meadow_scene, meadow_plants, ... meadow_precompute),
#   - a file of engine/ outside vk/ records push constants or buffer updates, maps memory or
#     casts a mapped buffer writable: the CPU's writes for the device go through vk/memory.h and
#     vk/pipeline.h, which count them (Context::hostBytesWritten, the per-frame upload figures).
#   tests/system/layering.sh SOURCE_DIR LINK_GRAPH_FILE
# LINK_GRAPH_FILE (written by tests/CMakeLists.txt at configure time) holds one line per meadow
# target: `target: dependency;dependency;...`.
set -euo pipefail
src="$1"
graph="$2"
failures=0
fail() {
    echo "layering: $*" >&2
    failures=$((failures + 1))
}

shared_headers=$(cd "$src/shaders/shared" && ls)
# check_includes FOLDER ALLOWED_PREFIXES...: every quoted include of FOLDER's sources must start
# with an allowed folder, name a shaders/shared header, or be the file's own neighbour.
check_includes() {
    local folder="$1"
    shift
    local file include ok prefix
    while IFS= read -r file; do
        while IFS= read -r include; do
            ok=0
            for prefix in "$@"; do
                [[ "$include" == "$prefix"/* ]] && ok=1
            done
            grep -qxF "$include" <<<"$shared_headers" && ok=1
            [[ "$include" != */* && -f "$(dirname "$file")/$include" ]] && ok=1
            [[ $ok == 1 ]] || fail "${file#"$src"/} includes \"$include\", which the run time may not depend on"
        done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$file")
    done < <(find "$folder" -name '*.h' -o -name '*.cpp' | sort)
}

for part in vk render ui io; do
    [[ -d "$src/engine/$part" ]] || fail "engine/$part is missing"
    check_includes "$src/engine/$part" core library vk render ui io
done
check_includes "$src/precompute/library" core library

while IFS=: read -r file line _; do
    fail "${file#"$src"/}:$line writes for the device around engine/vk's counted writes"
done < <(grep -rnE 'vkCmdPushConstants|vkCmdUpdateBuffer|vkMapMemory|const_cast<[^>]*>\([^)]*mapped\(\)' \
    --include='*.h' --include='*.cpp' "$src/engine" | grep -v "^$src/engine/vk/" || true)

# The link graph's closure from meadow_engine and from meadow_library.
declare -A deps
while IFS= read -r line; do
    target="${line%%:*}"
    deps[$target]="${line#*: }"
done <"$graph"
for root in meadow_engine meadow_library; do
    [[ -n "${deps[$root]+set}" ]] || { fail "$root is not in $graph"; continue; }
    declare -A seen=()
    queue=("$root")
    while ((${#queue[@]})); do
        target="${queue[0]}"
        queue=("${queue[@]:1}")
        IFS=';' read -r -a next <<<"${deps[$target]:-}"
        for dep in "${next[@]}"; do
            dep="${dep#\$<LINK_ONLY:}"
            dep="${dep%>}"
            [[ -z "$dep" || -n "${seen[$dep]+set}" ]] && continue
            seen[$dep]=1
            case "$dep" in
            meadow_scene | meadow_plants | meadow_wind | meadow_sim | meadow_motion | meadow_light | meadow_sky | \
                meadow_transfer | meadow_placement | meadow_lod | meadow_precompute)
                fail "$root links $dep (through $target)" ;;
            esac
            [[ -n "${deps[$dep]+set}" ]] && queue+=("$dep")
        done
    done
    unset seen
done

if ((failures)); then
    echo "layering: $failures violation(s)" >&2
    exit 1
fi
echo "layering: engine/{vk,render,ui,io} and precompute/library depend on the library and the core only;" \
    "the CPU writes for the device through engine/vk only"
