# Warnings as errors for the project's own targets only (system headers stay quiet).
function(penumbra_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                           -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion -Werror
                           # designated initializers zero the members they omit, by design
                           -Wno-missing-field-initializers)
endfunction()
