#pragma once
// Penumbra's error tiers (docs/architecture.md, "Errors and validation"):
//  - InputError: bad user input (a file, an option, a parameter). Caught by the CLI and printed
//    as one line, `error: <subject>: <what>`, with a non-zero exit code.
//  - DeviceError: the device failed under us (lost, out of memory at submit). Caught by the CLI
//    like an InputError: one `error:` line, a non-zero exit, no output.
//  - Programmer and driver errors abort through PENUMBRA_CHECK / VK_CHECK with file and line.
//  - Validation-layer messages are counted by the Vulkan context; tests fail on any error.
#include <stdexcept>
#include <string>

namespace penumbra {

class InputError : public std::runtime_error {
public:
    // subject: the file, option or parameter at fault, e.g. "scene.gltf" or "--width".
    InputError(std::string subject, const std::string& what)
        : std::runtime_error(subject + ": " + what), mSubject(std::move(subject)) {}
    const std::string& subject() const { return mSubject; }

private:
    std::string mSubject;
};

class DeviceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

[[noreturn]] void fatal(const char* file, int line, const std::string& message);

} // namespace penumbra

#define PENUMBRA_CHECK(cond, msg)                                                                  \
    do {                                                                                           \
        if (!(cond))                                                                               \
            ::penumbra::fatal(__FILE__, __LINE__, std::string("check failed: ") + (msg));          \
    } while (0)
