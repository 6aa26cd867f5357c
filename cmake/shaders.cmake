# lightsampler_embed_shaders(TARGET target OUTPUT_DIR dir SOURCES file...)
#
# Compiles each GLSL file (.comp, .vert, .geom, .frag) to SPIR-V at build time and embeds it in a
# header <dir>/spirv/<stem>_<ext>.h that defines
#   namespace lightsampler::spirv { inline constexpr std::uint32_t <stem>_<ext>[] = {...}; }
# (shaders/realize.comp -> #include "spirv/realize_comp.h", lightsampler::spirv::realize_comp).
# A shader includes headers from its own folder (shared with C++); glslang's depfile makes edits
# to them recompile it.

find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED
  DOC "glslangValidator, the GLSL to SPIR-V compiler (Debian: glslang-tools)")

function(lightsampler_embed_shaders)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;OUTPUT_DIR" "SOURCES")
  if(NOT arg_TARGET OR NOT arg_OUTPUT_DIR)
    message(FATAL_ERROR "lightsampler_embed_shaders needs TARGET and OUTPUT_DIR")
  endif()
  set(embed_script ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_spirv.cmake)
  # glslangValidator writes into this folder but does not create it.
  file(MAKE_DIRECTORY ${arg_OUTPUT_DIR}/spirv)
  set(headers)
  foreach(source IN LISTS arg_SOURCES)
    get_filename_component(source ${source} ABSOLUTE)
    get_filename_component(source_dir ${source} DIRECTORY)
    get_filename_component(stem ${source} NAME_WLE)
    get_filename_component(extension ${source} LAST_EXT)
    string(SUBSTRING ${extension} 1 -1 extension)
    set(symbol ${stem}_${extension})
    set(spirv ${arg_OUTPUT_DIR}/spirv/${symbol}.spv)
    set(header ${arg_OUTPUT_DIR}/spirv/${symbol}.h)
    add_custom_command(
      OUTPUT ${spirv} ${header}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.2 -V --spirv-val -I${source_dir}
              --depfile ${spirv}.d -o ${spirv} ${source}
      COMMAND ${CMAKE_COMMAND} -DINPUT=${spirv} -DOUTPUT=${header} -DSYMBOL=${symbol}
              -DSOURCE_NAME=${stem}.${extension} -P ${embed_script}
      DEPENDS ${source} ${embed_script}
      DEPFILE ${spirv}.d
      COMMENT "Compiling ${stem}.${extension} to SPIR-V"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  # Listing the headers as sources makes the target build them before compiling its files.
  target_sources(${arg_TARGET} PRIVATE ${headers})
  target_include_directories(${arg_TARGET} PRIVATE ${arg_OUTPUT_DIR})
endfunction()
