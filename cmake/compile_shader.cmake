# Run by meadow_add_shaders for one shader: GLSL -> SPIR-V, spirv-val, then the bytes as a C
# initializer list. On any failure nothing is left behind, so a stale or invalid module can
# never be embedded.
set(include_flags)
foreach(dir IN LISTS INCLUDE_DIRS)
  list(APPEND include_flags "-I${dir}")
endforeach()
file(REMOVE "${SPV}" "${INC}")
execute_process(
  COMMAND "${GLSLANG}" --quiet --target-env vulkan1.3 -S ${STAGE} ${include_flags}
          --depfile "${DEPFILE}" -o "${SPV}" "${SOURCE}"
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(REMOVE "${SPV}")
  message(FATAL_ERROR "glslangValidator failed on ${SOURCE}")
endif()
execute_process(COMMAND "${SPIRV_VAL}" --target-env vulkan1.3 "${SPV}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(REMOVE "${SPV}")
  message(FATAL_ERROR "spirv-val rejected ${SPV} (from ${SOURCE})")
endif()
# Ninja expects the depfile to name the rule's first output, the embedded words.
file(READ "${DEPFILE}" deps)
string(REPLACE "${SPV}:" "${INC}:" deps "${deps}")
file(WRITE "${DEPFILE}" "${deps}")
file(READ "${SPV}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE "${INC}" "${bytes}\n")
