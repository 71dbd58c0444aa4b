# Warnings as errors for the project's own targets only (system headers stay quiet).
# GCC 12 at -O3 (CMAKE_BUILD_TYPE=Release) reports bounds and uninitialized reads deep inside
# inlined standard library code that -O2 (the presets' RelWithDebInfo) does not: there they stay
# warnings, so that a Release build builds.
set(PENUMBRA_GCC_O3_FALSE_ALARMS
    "-Wno-error=stringop-overflow;-Wno-error=maybe-uninitialized;-Wno-error=restrict;-Wno-error=array-bounds")
function(penumbra_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                           -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion -Werror
                           # designated initializers zero the members they omit, by design
                           -Wno-missing-field-initializers
                           "$<$<AND:$<CXX_COMPILER_ID:GNU>,$<CONFIG:Release>>:${PENUMBRA_GCC_O3_FALSE_ALARMS}>")
endfunction()
