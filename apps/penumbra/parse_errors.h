#pragma once
// CLI11's parse errors in the words of Penumbra's other errors: the option first, then what is
// wrong with what was given (main.cpp prints the line after "error: ").
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::cli {

// "Could not convert: --width = abc" -> "--width: 'abc' is not a value it takes (--help gives
// its kind)"; "--n: Value 0 not in range 0.000000 to <the largest double>" -> "--n: '0' is not
// a number above zero" (another range: "is outside 2..64"); "--format: Check xyz value in
// {both->2,exr->1} OR {2,1} FAILED" and "--emit: pbs not in {slurm,kubernetes}" -> "'xyz' is
// not one of both, exr";
// "--frames: At Most 1 required but received 2" -> "--frames: given 2 values; it takes one";
// "The following argument was not expected: x" -> "x: not an argument of this command (--help
// lists them)", and several likewise. Any other message is returned as it is.
std::string parseErrorLine(std::string_view what);

// No command given ("a command is required: render, ...") or `given` is none of `commands`
// ("'rendr' is not a command: render, ..."), with where the commands are explained.
std::string missingCommandLine(std::string_view given, const std::vector<std::string>& commands);

} // namespace penumbra::cli
