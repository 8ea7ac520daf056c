# The bad-input corpus (issue 10; docs/ROBUSTNESS.md): every file here, or made here, must make
# meadow stop with one clear message that names the file and the problem, a non-zero exit status,
# nothing on stdout and no output file left behind (expect_clean_failure.sh). Each case states
# the message it expects. Tests are labelled `corpus` and `cli`.
#
# Included from CMakeLists.txt here; tests/CMakeLists.txt and tests/system/CMakeLists.txt define
# `meadow`, `test_env`, `test_output`, `test_cache` and `test_data`. Regular expressions hold no
# ';' (CMake would split the argument there): '.' stands in.

set(corpus_dir "${CMAKE_CURRENT_SOURCE_DIR}")
set(corpus_out "${test_output}/corpus")
file(MAKE_DIRECTORY "${corpus_out}")
set(corpus_expect bash "${corpus_dir}/expect_clean_failure.sh")

function(meadow_corpus_test name)
  add_test(NAME corpus.${name} COMMAND ${corpus_expect} ${ARGN})
  # A hang is a failure too (a reader looping on a lying count): fail fast instead of at ctest's 25 minutes.
  set_tests_properties(corpus.${name} PROPERTIES LABELS "corpus;cli" ENVIRONMENT "${test_env}" TIMEOUT 180)
endfunction()

# A scene file: `meadow precompute` must refuse it and write no library.
function(meadow_corpus_scene file regex)
  get_filename_component(name "${file}" NAME_WE)
  meadow_corpus_test(scene.${name} "${regex}" --absent "${corpus_out}/scene-${name}.mlib" --
    ${meadow} precompute "${corpus_dir}/scenes/${file}" --preset ci --out "${corpus_out}/scene-${name}.mlib")
endfunction()

# A plant file, named by a scene made here: precompute must refuse it and write no library.
function(meadow_corpus_gltf file regex)
  string(MAKE_C_IDENTIFIER "${file}" name)
  set(scene_file "${corpus_out}/gltf-${name}.json")
  file(WRITE "${scene_file}" "{\"name\": \"bad_gltf\", \"seed\": 1, \"field\": {\"tilesX\": 1, \"tilesY\": 1}, \"plants\": {\"source\": \"gltf\", \"gltf\": \"${file}\"}}\n")
  # The scene names the file relative to itself: copy the file beside it.
  file(COPY "${corpus_dir}/gltf/${file}" DESTINATION "${corpus_out}")
  meadow_corpus_test(gltf.${name} "${regex}" --absent "${corpus_out}/gltf-${name}.mlib" --
    ${meadow} precompute "${scene_file}" --preset ci --out "${corpus_out}/gltf-${name}.mlib")
endfunction()

# An HDR sky map, named by a scene made here.
function(meadow_corpus_sky file regex)
  string(MAKE_C_IDENTIFIER "${file}" name)
  set(scene_file "${corpus_out}/sky-${name}.json")
  file(WRITE "${scene_file}" "{\"name\": \"bad_sky\", \"seed\": 1, \"field\": {\"tilesX\": 1, \"tilesY\": 1}, \"sky\": {\"maps\": [\"${corpus_dir}/sky/${file}\"]}}\n")
  meadow_corpus_test(sky.${name} "${regex}" --absent "${corpus_out}/sky-${name}.mlib" --
    ${meadow} precompute "${scene_file}" --preset ci --out "${corpus_out}/sky-${name}.mlib")
endfunction()

# A library made from the micro scene's library by mutate_library.py: inspect must refuse it.
set(corpus_libraries "${corpus_out}/libraries")
function(meadow_corpus_library name regex)
  meadow_corpus_test(library.${name} "library .*/${name}\\.mlib: ${regex}" --
    ${meadow} inspect "${corpus_libraries}/${name}.mlib" --json)
  set_tests_properties(corpus.library.${name} PROPERTIES FIXTURES_REQUIRED corpus_libraries)
  set_property(GLOBAL APPEND PROPERTY meadow_corpus_library_cases ${name})
endfunction()

# --- scenes -------------------------------------------------------------------------------------
set(s "scene .*/scenes/")
meadow_corpus_scene(wrong_type_name.json "${s}wrong_type_name.json: name must be a non-empty string")
meadow_corpus_scene(wrong_type_seed.json "${s}wrong_type_seed.json: seed must be a non-negative integer \\(got \"one\"\\)")
meadow_corpus_scene(negative_seed.json "${s}negative_seed.json: seed must be a non-negative integer \\(got -3\\)")
meadow_corpus_scene(wrong_type_field.json "${s}wrong_type_field.json: field must be an object")
meadow_corpus_scene(wrong_type_tiles.json "${s}wrong_type_tiles.json: field.tilesX must be an integer \\(got \"five\"\\)")
meadow_corpus_scene(fractional_count.json "${s}fractional_count.json: plants.clumps must be an integer \\(got 2.5\\)")
meadow_corpus_scene(wrong_type_camera_eye.json "${s}wrong_type_camera_eye.json: camera.eye must be an array of three numbers \\(got an array of 2\\)")
meadow_corpus_scene(wrong_type_wind_levels.json "${s}wrong_type_wind_levels.json: wind.levels must be an array of 2 to 8 speeds")
meadow_corpus_scene(wrong_type_preset.json "${s}wrong_type_preset.json: presets.ci must be an object")
meadow_corpus_scene(wrong_type_top_level.json "${s}wrong_type_top_level.json: the top level must be an object")
meadow_corpus_scene(missing_name.json "${s}missing_name.json: name is missing")
meadow_corpus_scene(missing_seed.json "${s}missing_seed.json: seed is missing")
meadow_corpus_scene(missing_field.json "${s}missing_field.json: field is missing")
meadow_corpus_scene(missing_tiles.json "${s}missing_tiles.json: field.tilesX is missing")
meadow_corpus_scene(missing_camera_target.json "${s}missing_camera_target.json: camera.target is missing")
meadow_corpus_scene(missing_gltf_file_key.json "${s}missing_gltf_file_key.json: plants.gltf is missing")
meadow_corpus_scene(nan_literal.json "${s}nan_literal.json: invalid JSON: .*syntax error")
meadow_corpus_scene(infinity_literal.json "${s}infinity_literal.json: invalid JSON: .*syntax error")
meadow_corpus_scene(number_overflow.json "${s}number_overflow.json: invalid JSON: .*number overflow parsing '1e999'")
meadow_corpus_scene(negative_tile_size.json "${s}negative_tile_size.json: field.tileSize must be between 0.5 and 1000.0 \\(got -7\\)")
meadow_corpus_scene(zero_tile_size.json "${s}zero_tile_size.json: field.tileSize must be between 0.5 and 1000.0 \\(got 0\\)")
meadow_corpus_scene(zero_tiles.json "${s}zero_tiles.json: field.tilesX must be between 1 and 1024 \\(got 0\\)")
meadow_corpus_scene(negative_cell_size.json "${s}negative_cell_size.json: field.cellSize must be between 0.002 and 1.0 \\(got -0.025\\)")
meadow_corpus_scene(negative_wind_speed.json "${s}negative_wind_speed.json: wind.levels\\[0\\] must be between 0.0 and 30.0 \\(got -1.0\\)")
meadow_corpus_scene(negative_record_time.json "${s}negative_record_time.json: motion.recordSeconds must be between 0.5 and 300.0 \\(got -4\\)")
meadow_corpus_scene(billion_clumps.json "${s}billion_clumps.json: plants.clumps must be between 1 and 16 \\(got 1000000000\\)")
meadow_corpus_scene(billion_tiles.json "${s}billion_tiles.json: field.tilesX must be between 1 and 1024 \\(got 1000000000\\)")
meadow_corpus_scene(uint64_max_tiles.json "${s}uint64_max_tiles.json: field.tilesX must be between 1 and 1024 \\(got 18446744073709551615\\)")
meadow_corpus_scene(billion_rocks.json "${s}billion_rocks.json: field.rocksPerTile must be between 0 and 1000 \\(got 1000000000\\)")
meadow_corpus_scene(billion_sky_frames.json "${s}billion_sky_frames.json: sky.frames must be between 1 and 4096 \\(got 1000000000\\)")
meadow_corpus_scene(billion_rays.json "${s}billion_rays.json: light.raysPerVertex must be between 8 and 65536 \\(got 1000000000\\)")
meadow_corpus_scene(unknown_key.json "${s}unknown_key.json: field.tileSise is not a known key")
meadow_corpus_scene(stem_diameter_out_of_range.json "${s}stem_diameter_out_of_range.json: plants.stemDiameter must be between 0.0005 and 0.5 \\(got 2\\)")
meadow_corpus_scene(stem_diameter_with_iris.json "${s}stem_diameter_with_iris.json: plants.stemDiameter applies only to plants.source \"gltf\"")
meadow_corpus_scene(unknown_plant_source.json "${s}unknown_plant_source.json: plants.source must be \"iris\" or \"gltf\" \\(got \"fern\"\\)")
meadow_corpus_scene(unknown_preset_key.json "${s}unknown_preset_key.json: presets.huge is not a known key")
meadow_corpus_scene(camera_eye_is_target.json "${s}camera_eye_is_target.json: camera.target must differ from camera.eye")
meadow_corpus_scene(wind_levels_decrease.json "${s}wind_levels_decrease.json: wind.levels must increase from calm to strong")
meadow_corpus_scene(odd_sky_width.json "${s}odd_sky_width.json: sky.imageWidth must be even")
meadow_corpus_scene(name_with_path.json "${s}name_with_path.json: name may hold only letters, digits")
meadow_corpus_scene(long_name.json "${s}long_name.json: name must be at most 64 characters long \\(got 300\\)")
meadow_corpus_scene(deep_nesting.json "${s}deep_nesting.json: the top level nests arrays and objects more than 64 deep")
meadow_corpus_scene(deep_preset.json "${s}deep_preset.json: the top level nests arrays and objects more than 64 deep")
meadow_corpus_scene(invalid_utf8.json "${s}invalid_utf8.json: invalid JSON: .*invalid string: ill-formed UTF-8")
meadow_corpus_scene(truncated.json "${s}truncated.json: invalid JSON: .*unexpected end of input")
meadow_corpus_scene(empty.json "${s}empty.json: invalid JSON: .*unexpected end of input")
meadow_corpus_scene(unknown_plant_file.json "glTF .*/scenes/no_such_plant.glb: cannot open \\(no such file\\)")
meadow_corpus_scene(plant_file_is_folder.json "glTF .*/scenes/?\\.?: is not a regular file \\(a folder or a device\\?\\)")
meadow_corpus_scene(plant_file_is_device.json "glTF /dev/zero: is not a regular file \\(a folder or a device\\?\\)")
meadow_corpus_scene(sky_map_is_device.json "sky map /dev/zero: is not a regular file")
meadow_corpus_scene(missing_sky_map.json "sky map .*/scenes/no_such_sky.exr: no such file")
meadow_corpus_test(scene.is_a_folder "scene .*/robustness/scenes: is a folder, not a scene file" --
  ${meadow} precompute "${corpus_dir}/scenes" --preset ci --out "${corpus_out}/scene-folder.mlib")
# Rendering a bad scene leaves no image and no library in the cache.
meadow_corpus_test(render.bad_scene "${s}billion_clumps.json: plants.clumps" --absent "${corpus_out}/render-bad-scene.png" --
  ${meadow} render "${corpus_dir}/scenes/billion_clumps.json" --preset ci --size 32x32 --out "${corpus_out}/render-bad-scene.png")
meadow_corpus_test(render.unknown_plant_file "glTF .*no_such_plant.glb: cannot open" --absent "${test_cache}/bad-ci-" --
  ${meadow} render "${corpus_dir}/scenes/unknown_plant_file.json" --preset ci --size 32x32 --out "${corpus_out}/render-no-plant.png")
# The far field's options that contradict each other: refused before any work, no image written.
meadow_corpus_test(render.far_lod0_without_far_field
  "meadow render: --far-lod0 draws the far field's clumps as LOD 0 meshes: it needs the far field, which --far-radius 0 turns off"
  --absent "${corpus_out}/render-far-lod0.png" --
  ${meadow} render "${PROJECT_SOURCE_DIR}/data/scenes/irises.json" --preset ci --size 32x32 --far-lod0 --far-radius 0
  --out "${corpus_out}/render-far-lod0.png")
meadow_corpus_test(render.lod0_with_far_lod0
  "meadow render: --lod0 draws every clump at full detail, without a far field: leave out --far-lod0"
  --absent "${corpus_out}/render-lod0-far-lod0.png" --
  ${meadow} render "${PROJECT_SOURCE_DIR}/data/scenes/irises.json" --preset ci --size 32x32 --lod0 --far-lod0
  --out "${corpus_out}/render-lod0-far-lod0.png")
meadow_corpus_test(render.lod0_with_far_field
  "meadow render: --lod0 draws every clump at full detail, without a far field: leave out --far-radius"
  --absent "${corpus_out}/render-lod0-far.png" --
  ${meadow} render "${PROJECT_SOURCE_DIR}/data/scenes/irises.json" --preset ci --size 32x32 --lod0 --far-radius 5
  --out "${corpus_out}/render-lod0-far.png")

# A field larger than the device's memory (here, than MEADOW_GPU_MEMORY_MIB lets meadow count on)
# is refused when it is loaded, before any of it is allocated, with what it needs and what there
# is; no image or benchmark file is written. Under the validation layer, which reports anything
# the failed load left alive on the device (a second line on stderr fails the case).
set(vulkan_no_leak_check bash "${corpus_dir}/vulkan_no_leak_check.sh")
meadow_corpus_test(bench.field_too_large_for_the_device
  "the field \\(2000000 instances of [0-9]+ meshes\\) needs [0-9]+\\.[0-9] MiB of GPU memory. the device has [0-9]+\\.[0-9] MiB \\(.*MEADOW_GPU_MEMORY_MIB allowing 64\\.0 MiB\\): use fewer clumps"
  --absent "${corpus_out}/bench-too-large.json" --
  env MEADOW_GPU_MEMORY_MIB=64 ${vulkan_no_leak_check} ${meadow} bench "${PROJECT_SOURCE_DIR}/data/scenes/irises.json"
  --preset ci --clumps 2000000 --frames 1 --size 32x32 --validation --json "${corpus_out}/bench-too-large.json")
meadow_corpus_test(render.field_too_large_for_the_device
  "the field \\([0-9]+ instances of [0-9]+ meshes\\) needs [0-9]+\\.[0-9] MiB of GPU memory. the device has"
  --absent "${corpus_out}/render-too-large.png" --
  env MEADOW_GPU_MEMORY_MIB=1 ${vulkan_no_leak_check} ${meadow} render "${PROJECT_SOURCE_DIR}/data/scenes/irises.json"
  --preset ci --size 32x32 --validation --out "${corpus_out}/render-too-large.png")
set_tests_properties(corpus.bench.field_too_large_for_the_device corpus.render.field_too_large_for_the_device
                     PROPERTIES FIXTURES_REQUIRED ci_library)

# --- glTF plants ----------------------------------------------------------------------------------
set(g "glTF .*/gltf-[a-z0-9_]*/?.*")
foreach(case
    "accessor_missing.gltf|POSITION names accessor 7, which does not exist"
    "accessor_past_buffer.gltf|POSITION reads past the end of its buffer \\(1000 elements do not fit"
    "accessor_offset_past_view.gltf|NORMAL reads past the end of its buffer"
    "huge_index_count.gltf|indices reads past the end of its buffer \\(9223372036854775809 elements"
    "huge_position_count.gltf|POSITION reads past the end of its buffer \\(9223372036854775809 elements"
    "billion_indices.gltf|indices reads past the end of its buffer \\(4000000002 elements"
    "buffer_view_past_buffer.gltf|POSITION reads past the end of its buffer \\(its buffer view does not fit"
    "index_out_of_range.gltf|has index 200 but only 10 vertices"
    "index_count_not_triangles.gltf|has 16 indices, not a multiple of 3"
    "mode_lines.gltf|draws LINES. meadow imports only TRIANGLES primitives"
    "mode_triangle_strip.gltf|draws TRIANGLE_STRIP. meadow imports only TRIANGLES primitives"
    "mode_triangle_fan.gltf|draws TRIANGLE_FAN. meadow imports only TRIANGLES primitives"
    "normal_count_mismatch.gltf|has 5 normals for 10 positions"
    "position_component_uint.gltf|has a component type meadow cannot read"
    "position_vec2.gltf|POSITION has the wrong accessor type"
    "sparse_accessor.gltf|uses a sparse accessor, which meadow cannot read"
    "node_cycle.gltf|node 0 is reached twice: the node hierarchy has a cycle"
    "node_shared.gltf|node [0-9]+ is reached twice: the node hierarchy has a cycle or a shared node"
    "node_child_missing.gltf|node 3 does not exist"
    "mesh_missing.gltf|node 'plant' names mesh 4, which does not exist"
    "matrix_overflow.gltf|has a vertex position that is not finite"
    "zero_scale.gltf|wrong units\\? the plant is 0 m tall"
    "texture_not_an_image.gltf|material 'leaf' base colour texture: image 0 is neither PNG nor JPEG"
    "buffer_file_missing.gltf|cannot parse: File not found : missing_buffer.bin"
    "buffer_uri_folder.gltf|cannot parse: File read error : .* is not a regular file \\(a folder or a device\\?\\)"
    "buffer_bad_base64.gltf|cannot parse: Failed to decode 'uri'"
    "buffer_length_lie.gltf|cannot parse: .*\\.\\.\\.$"
    "no_scene.gltf|has no scene, so there is no mesh to import"
    "default_scene_missing.gltf|the default scene 3 does not exist"
    "empty.gltf|cannot parse: .*the file is empty"
    "not_json.gltf|cannot parse: .*parse error"
    "truncated.gltf|cannot parse: .*parse error"
    "truncated.glb|cannot parse: Invalid glTF binary"
    "truncated_header.glb|cannot parse: Too short data size for glTF Binary"
    "chunk_length_lie.glb|cannot parse: Invalid glTF binary"
    "bad_magic.glb|cannot parse: Invalid magic")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 file)
  list(GET parts 1 regex)
  string(REPLACE "." "\\." file_regex "${file}")
  meadow_corpus_gltf(${file} "glTF .*/corpus/${file_regex}: .*${regex}")
endforeach()
# The existing importer assets (tests/data/gltf) that must be refused, through the command line.
foreach(case
    "skinned.gltf|uses skinning, which meadow cannot use"
    "points.gltf|draws POINTS. meadow imports only TRIANGLES primitives"
    "no_position.gltf|has no POSITION attribute"
    "no_mesh.gltf|has no mesh with triangles in its default scene"
    "millimetres.gltf|wrong units\\? the plant is 1600 m tall"
    "red_cube.gltf|is a closed solid enclosing 100% of its bounding box \\(1.00 m.*\\) with a mean thickness of 0.33 m \\(33% of its 1.00 m extent\\), not a plant: meadow simulates thin blades and stems on elastic rods"
    "malformed.gltf|cannot parse")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 file)
  list(GET parts 1 regex)
  string(MAKE_C_IDENTIFIER "${file}" name)
  set(scene_file "${corpus_out}/data-gltf-${name}.json")
  file(WRITE "${scene_file}" "{\"name\": \"bad_gltf\", \"seed\": 1, \"field\": {\"tilesX\": 1, \"tilesY\": 1}, \"plants\": {\"source\": \"gltf\", \"gltf\": \"${test_data}/gltf/${file}\"}}\n")
  meadow_corpus_test(gltf.data_${name} "glTF .*/data/gltf/${file}: .*${regex}" --absent "${corpus_out}/data-gltf-${name}.mlib" --
    ${meadow} precompute "${scene_file}" --preset ci --out "${corpus_out}/data-gltf-${name}.mlib")
endforeach()

# --- HDR sky maps ---------------------------------------------------------------------------------
set(m "sky map .*/robustness/sky/")
meadow_corpus_sky(square.exr "${m}square.exr: 16 x 16 is not a 2:1 latitude-longitude panorama")
meadow_corpus_sky(tall.exr "${m}tall.exr: 8 x 16 is not a 2:1 latitude-longitude panorama")
meadow_corpus_sky(one_channel.exr "${m}one_channel.exr: has 1 channel\\(s\\). an RGB panorama needs at least 3")
meadow_corpus_sky(two_channels.exr "${m}two_channels.exr: has 2 channel\\(s\\). an RGB panorama needs at least 3")
meadow_corpus_sky(negative.exr "${m}negative.exr: texel \\(5, 3\\) channel 0 is negative \\(-1\\)")
meadow_corpus_sky(infinite.exr "${m}infinite.exr: texel \\(2, 6\\) channel 1 is not finite \\(inf\\)")
meadow_corpus_sky(huge_header.hdr "${m}huge_header.hdr: 40000 x 20000 is larger than meadow reads \\(at most 16384 x 8192\\)")
meadow_corpus_sky(truncated.hdr "${m}truncated.hdr: cannot read its pixels")
meadow_corpus_sky(not_an_image.hdr "${m}not_an_image.hdr: cannot read it as an image")
meadow_corpus_sky(empty.exr "${m}empty.exr: cannot read it as an image")
meadow_corpus_test(sky.folder "sky map .*/robustness/scenes: is a folder, not an image" --absent "${corpus_out}/sky-folder.mlib" --
  ${meadow} precompute "${corpus_out}/sky-folder.json" --preset ci --out "${corpus_out}/sky-folder.mlib")
file(WRITE "${corpus_out}/sky-folder.json" "{\"name\": \"bad_sky\", \"seed\": 1, \"field\": {\"tilesX\": 1, \"tilesY\": 1}, \"sky\": {\"maps\": [\"${corpus_dir}/scenes\"]}}\n")

# --- libraries ------------------------------------------------------------------------------------
# A folder opens as a stream, and a device never ends: both refused before a byte is read.
meadow_corpus_test(library.folder "library .*/robustness/scenes: is a folder, not a library file" --
  ${meadow} inspect "${corpus_dir}/scenes" --json)
meadow_corpus_test(library.device "library /dev/zero: is not a regular file \\(a device\\?\\)" --
  ${meadow} inspect /dev/zero --json)
meadow_corpus_library(empty "too short to be a meadow library \\(0 bytes\\)")
meadow_corpus_library(truncated_header "too short to be a meadow library \\(20 bytes\\)")
meadow_corpus_library(truncated_table "section table is truncated or corrupt")
meadow_corpus_library(truncated_payload "section '[A-Z]{4}' lies outside the file \\(truncated\\?\\)")
meadow_corpus_library(truncated_last_byte "section 'TFLD' lies outside the file \\(truncated\\?\\)")
meadow_corpus_library(bitflip_magic "not a meadow library \\(bad magic\\)")
meadow_corpus_library(bitflip_section_count "section table is truncated or corrupt \\([0-9]+ sections\\)")
meadow_corpus_library(bitflip_table "section table checksum mismatch \\(corrupt file\\)")
meadow_corpus_library(bitflip_payload "section '[A-Z]{4}' checksum mismatch \\(corrupt file\\)")
meadow_corpus_library(bitflip_last_byte "section 'TFLD' checksum mismatch \\(corrupt file\\)")
meadow_corpus_library(older_version "format version [0-9]+, this meadow reads version [0-9]+ \\(rebuild it with meadow precompute\\)")
meadow_corpus_library(future_version "format version 999, this meadow reads version [0-9]+")
meadow_corpus_library(section_size_lie "section 'CLMP' lies outside the file")
meadow_corpus_library(section_offset_lie "section 'SKYD' lies outside the file")
meadow_corpus_library(section_size_overflow "section 'TFLD' lies outside the file")
meadow_corpus_library(huge_section_count "section table is truncated or corrupt \\(1073741824 sections\\)")
meadow_corpus_library(missing_section "section 'SKYD' is missing")
meadow_corpus_library(duplicate_section "section 'TFLD' appears twice")
meadow_corpus_library(section_shortened "section 'LODS': truncated \\(needs 4 more bytes at offset [0-9]+\\)")
meadow_corpus_library(section_trailing_bytes "section 'CLMP': 4 unexpected trailing bytes")
meadow_corpus_library(scene_not_json "section 'SCNE' is not valid JSON")
meadow_corpus_library(scene_not_object "section 'SCNE' is not a resolved scene")
meadow_corpus_library(clump_count_lie "section 'CLMP' holds 1000 clumps")
meadow_corpus_library(clump_name_length_lie "section 'CLMP': an array of 4294967280 elements at offset 8 does not fit \\(corrupt file\\)")
meadow_corpus_library(triangle_index_out_of_range "section 'CLMP': clump [a-z0-9_-]+: a triangle index is out of range")
meadow_corpus_library(graph_level_out_of_range "section 'CLMP': clump [a-z0-9_-]+: a motion graph node has wind level 200 of 2")
meadow_corpus_library(graph_successor_out_of_range "section 'CLMP': clump [a-z0-9_-]+: a motion graph node's natural successor is outside the graph")
meadow_corpus_library(atlas_size_lie "section 'ATLS' has the wrong size for its atlas")
meadow_corpus_library(instance_count_lie "section 'TFLD' holds [0-9]+ bytes for 4294967295 instances")
meadow_corpus_library(instance_mesh_out_of_range "section 'TFLD' names mesh 4096 of 1")
meadow_corpus_library(instance_position_nan "section 'TFLD' holds a non-finite value")
meadow_corpus_library(light_count_lie "section 'LITE' does not hold one entry per clump")
meadow_corpus_library(sky_frame_count_lie "section 'SKYD': holds 100000 frames")
meadow_corpus_library(sky_time_nan "section 'SKYD': frame 0 holds a non-finite or negative value")
meadow_corpus_library(rock_count_lie "section 'ROCK' holds 65 rocks")
meadow_corpus_library(far_gain_nan "section 'FARS': clump [a-z0-9_-]+: its far-field coverage gain nan is not a positive finite number")
meadow_corpus_library(far_sample_vertex_out_of_range "section 'FARS': clump [a-z0-9_-]+: far-field sample 0 names vertex 2147483647 of [0-9]+")

# The bad libraries are made from the micro scene's library (micro.json: every section, 300 KB,
# built in a second), and the fuzzers' library seed beside them.
get_property(library_cases GLOBAL PROPERTY meadow_corpus_library_cases)
add_test(NAME corpus.make_bad_libraries
  COMMAND bash "${corpus_dir}/make_bad_libraries.sh" ${meadow} "${corpus_dir}/micro.json" "${corpus_libraries}"
          $<TARGET_FILE:meadow_fuzz_make_seed> ${library_cases})
set_tests_properties(corpus.make_bad_libraries PROPERTIES LABELS "corpus;cli" ENVIRONMENT "${test_env}"
                     FIXTURES_SETUP corpus_libraries)
