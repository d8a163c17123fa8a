# cmake -DSPV=in.spv -DOUT=out.cpp -DNAME=alchemy -P embed_spirv.cmake
# Writes a C++ source defining obscura::gpu::shaders::NAME (declared in src/gpu/spirv.h) as the module's
# 32-bit words, so the library carries its shaders and never looks for files at run time.
file(READ "${SPV}" hex HEX)
string(LENGTH "${hex}" length)
math(EXPR remainder "${length} % 8")
if(length EQUAL 0 OR NOT remainder EQUAL 0)
  message(FATAL_ERROR "${SPV} is not a SPIR-V module (size not a multiple of 4 bytes)")
endif()
# SPIR-V words are stored little-endian: bytes b0 b1 b2 b3 are the word 0xb3b2b1b0.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){8})" "\\1\n    " words "${words}")
file(WRITE "${OUT}.tmp" "// Generated from ${NAME}.comp by cmake/embed_spirv.cmake; do not edit.
#include \"gpu/spirv.h\"

namespace obscura::gpu::shaders {
namespace {
const std::uint32_t kWords[] = {
    ${words}
};
} // namespace
const Spirv ${NAME}{kWords, sizeof kWords / sizeof kWords[0]};
} // namespace obscura::gpu::shaders
")
file(RENAME "${OUT}.tmp" "${OUT}")
